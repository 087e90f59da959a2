// Metrics of the mixed-mode LEFM case (seed 4.4, Figure 4.10): the far-field stress s at
// which the first joint has failed on both sides of the crack (the load ramp's stop
// level) against
//   - the corrected G-criterion relation s = T0 sqrt(L / (2 a cos^2 beta)) (erratum 5),
//   - the seed's eq. 4.30 as printed,
//   - the exact-field estimate: the far field at which the normal force of the exact
//     crack field on a joint leaving the tip reaches T0 times its length, lowest over the
//     joints at the tip (analytical/lefm_mixed.hpp); for a = 0 the uniform field;
// and the kink: the direction of the failed joints leaving each tip, in the tip's axes
// (x' ahead of the tip, angle counter-clockwise from x'; at the right tip x' = +x, at
// the left tip x' = -x), where the maximum hoop stress criterion gives -43.2 degrees for
// beta = 30 degrees, and kink_error_deg, the largest deviation of the joints failed at
// the tips from that direction (the rosette variants at beta = 15, 45, 60 degrees, on a
// Delaunay mesh: L is then the crack's segment_length). Units: Pa, m, degrees. Variants, thresholds and checks: study.yaml.
// Writes failed_<variant>.csv (broken joints of the inner domain) per variant, and
// failure_stress.csv and relations.csv (the curves of Figure 4.10) for plot.py.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "analytical/lefm_mixed.hpp"
#include "fracture/fracture_criteria.hpp"
#include "harness.hpp"

namespace hfdda::verification {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

/// What the case file says: the crack, the joints' strength and size, the far field.
struct Setup {
  double half_length_m = 0.0;    ///< a (0: no crack)
  double cell_size_m = kNaN;     ///< L of the grid-line joints (the seed's L)
  double tensile_strength_Pa = kNaN;
  double beta_rad = kNaN;
  double increment_Pa = kNaN;
  analytical::StressPattern far;
  double toughness_Pa_sqrt_m = kNaN;  ///< K_IC with fracture.criterion: energy_release_rate, NaN otherwise
};

/// The far-field pattern must be a uniaxial tension at angle beta to the crack (seed eq.
/// 4.26): sxx = sin^2, syy = cos^2, sxy = sin cos.
Setup setup_of(const io::CaseConfig& c) {
  if (!c.load_ramp) throw std::runtime_error("case needs a load_ramp");
  const io::LoadRampConfig& r = *c.load_ramp;
  if (r.stop_when != "failed_both_sides") throw std::runtime_error("load_ramp.stop_when must be failed_both_sides");
  if (r.crack_centre.norm() > 1e-9 || std::abs(r.crack_direction.y()) > 1e-12 || r.crack_direction.x() <= 0.0)
    throw std::runtime_error("load_ramp: the crack is centred at the origin along +x");
  if (std::abs(r.sxx + r.syy - 1.0) > 1e-9 || std::abs(r.sxx * r.syy - r.sxy * r.sxy) > 1e-9 || r.syy <= 0.0)
    throw std::runtime_error("load_ramp: sxx, syy, sxy must be sin^2, cos^2, sin cos of one angle (seed eq. 4.26)");
  if (r.sides.size() != 4) throw std::runtime_error("load_ramp: the far field acts on all four sides");
  if (c.far_field.sxx_Pa != 0.0 || c.far_field.syy_Pa != 0.0 || c.far_field.sxy_Pa != 0.0)
    throw std::runtime_error("the comparison assumes no other far-field stress");
  if (c.joints.fracture_toughness_Pa_sqrt_m) throw std::runtime_error("the case gives T0, not K_IC");
  const bool grid = c.mesh.kind == io::MeshKind::structured && c.mesh.split == mesh::CellSplit::four;
  if (!grid && c.mesh.kind != io::MeshKind::delaunay)
    throw std::runtime_error("the case needs a structured mesh split into four triangles, or a Delaunay mesh");
  Setup s;
  s.beta_rad = std::atan2(r.sxy, r.syy);
  s.far = {r.sxx, r.syy, r.sxy};
  s.cell_size_m = c.mesh.cell_size_m;
  s.tensile_strength_Pa = c.joints.tensile_strength_Pa;
  s.increment_Pa = r.increment_Pa.value_or(kNaN);
  if (c.fracture.criterion == io::FailureCriterionKind::energy_release_rate) {
    if (c.fracture.mode2_toughness_Pa_sqrt_m) throw std::runtime_error("the study takes K_IIC = K_IC");
    s.toughness_Pa_sqrt_m = c.fracture.fracture_toughness_Pa_sqrt_m.value_or(kNaN);
  }
  int cracks = 0;
  for (const io::FractureConfig& f : c.fractures) {
    if (f.name != "crack") continue;
    ++cracks;
    if (!f.initially_open || f.from.y() != 0.0 || f.to.y() != 0.0 || std::abs(f.from.x() + f.to.x()) > 1e-9)
      throw std::runtime_error("the fracture 'crack' is initially open, on y = 0 and centred at the origin");
    s.half_length_m = 0.5 * std::abs(f.to.x() - f.from.x());
    // On a Delaunay mesh (the tip rosettes) L is the crack's joint length.
    if (!grid) s.cell_size_m = f.segment_length_m;
  }
  if (cracks > 1) throw std::runtime_error("one fracture named 'crack' at most");
  if (!grid && !(s.cell_size_m > 0.0))
    throw std::runtime_error("on a Delaunay mesh the crack needs a segment_length: its joint length L");
  return s;
}

/// A failed joint leaving a tip: its angle in the tip's axes and its length.
struct TipJoint {
  double angle_deg = kNaN, length_m = kNaN;
};

/// What happened at one tip (a > 0) or at the centre (a = 0, `right` only).
struct Tip {
  std::vector<TipJoint> failed;        ///< fully failed joints leaving the tip
  double exact_Pa = kNaN;              ///< exact-field failure stress, lowest over its joints
  double exact_angle_deg = kNaN;       ///< angle of that joint
};

/// Angle of the direction (dx, dy) in the axes of the tip whose x' is `ahead` (+1: +x,
/// -1: -x), in (-180, 180].
double tip_angle_deg(double dx, double dy, double ahead) {
  return std::atan2(ahead * dy, ahead * dx) * kDeg;
}

Tip tip_of(const simulation::Model& model, const Setup& s, double ahead) {
  const dda::BlockSystem& system = *model.system;
  const mesh::Mesh& mesh = system.mesh();
  const auto& contacts = system.contacts();
  const Vec2 tip(ahead * s.half_length_m, 0.0);
  const double tol = 1e-6 * s.cell_size_m;
  Tip t;
  for (std::size_t j = 0; j < mesh.joints.size(); ++j) {
    const mesh::Joint& joint = mesh.joints[j];
    if (!joint.properties.breakable || joint.properties.initially_open) continue;
    Vec2 other;
    if ((mesh.points[joint.point_p] - tip).norm() < tol) other = mesh.points[joint.point_q];
    else if ((mesh.points[joint.point_q] - tip).norm() < tol) other = mesh.points[joint.point_p];
    else continue;
    const Vec2 d = other - tip;
    const double angle = tip_angle_deg(d.x(), d.y(), ahead);
    const double length = d.norm();
    const double t0 = fracture::bond_strength(joint.properties, length).tensile_strength_Pa;
    const double exact = analytical::joint_failure_stress(t0, s.half_length_m, s.far, angle / kDeg, length);
    if (std::isnan(t.exact_Pa) || exact < t.exact_Pa) {
      t.exact_Pa = exact;
      t.exact_angle_deg = angle;
    }
    const auto ends = system.joint_contacts(static_cast<int>(j));
    if (!contacts[ends[0]].bonded && !contacts[ends[1]].bonded) t.failed.push_back({angle, length});
  }
  return t;
}

/// The one failed joint at a tip, or NaN when none or several failed there.
double kink_deg(const Tip& t) { return t.failed.size() == 1 ? t.failed[0].angle_deg : kNaN; }

/// The largest |angle - prediction| over the joints failed at the two tips, NaN when a
/// tip has none (no kink to measure there).
double kink_error_deg(const Tip& right, const Tip& left, double prediction_deg) {
  if (right.failed.empty() || left.failed.empty()) return kNaN;
  double worst = 0.0;
  for (const Tip* t : {&right, &left})
    for (const TipJoint& f : t->failed) worst = std::max(worst, std::abs(f.angle_deg - prediction_deg));
  return worst;
}

/// Broken or initially open joints of the inner domain: failed_<variant>.csv.
struct Broken {
  std::string csv;
  int full = 0, half = 0, full_minus_45 = 0;  ///< joints failed at both ends / one end; of those, -45 deg
};

Broken broken_of(const simulation::Model& model, const io::CaseConfig& c) {
  const dda::BlockSystem& system = *model.system;
  const mesh::Mesh& mesh = system.mesh();
  const auto& contacts = system.contacts();
  const Rect in = c.domain.inner.value_or(c.domain.outer);
  Broken b;
  b.csv = "px_m,py_m,qx_m,qy_m,ends_failed,initially_open\n";
  for (std::size_t j = 0; j < mesh.joints.size(); ++j) {
    const mesh::Joint& joint = mesh.joints[j];
    const Vec2 p = mesh.points[joint.point_p], q = mesh.points[joint.point_q];
    const Vec2 mid = 0.5 * (p + q);
    if (mid.x() < in.xmin || mid.x() > in.xmax || mid.y() < in.ymin || mid.y() > in.ymax) continue;
    const auto ends = system.joint_contacts(static_cast<int>(j));
    const int failed = int(!contacts[ends[0]].bonded) + int(!contacts[ends[1]].bonded);
    const bool open = joint.properties.initially_open;
    if (failed == 0 && !open) continue;
    if (!open) {
      if (failed == 2) {
        ++b.full;
        const Vec2 d = q - p;
        if (std::abs(d.x() + d.y()) < 1e-6 * d.norm()) ++b.full_minus_45;  // along y = -x + c
      } else {
        ++b.half;
      }
    }
    b.csv += number(p.x()) + "," + number(p.y()) + "," + number(q.x()) + "," + number(q.y()) + "," +
             std::to_string(failed) + "," + (open ? "1" : "0") + "\n";
  }
  return b;
}

Metrics variant_metrics(const VariantRun& r) {
  Metrics out;
  Setup s;
  bool have_setup = false;
  if (r.config) try {
      s = setup_of(*r.config);
      have_setup = true;
    } catch (const std::exception&) {
      // reported by validate as "case not built"
    }
  const simulation::LoadRampOutcome* o = r.model && r.model->ramp ? &r.model->ramp->outcome() : nullptr;
  const double stop = o && o->stop_reached ? o->stop_Pa : kNaN;
  const double a = s.half_length_m;
  const bool crack = have_setup && a > 0.0;
  const double g = crack ? analytical::mixed_mode_failure_stress_g(s.tensile_strength_Pa, s.cell_size_m, a, s.beta_rad)
                         : kNaN;
  const double eq430 =
      crack ? analytical::mixed_mode_failure_stress_eq430(s.tensile_strength_Pa, s.cell_size_m, a, s.beta_rad) : kNaN;
  // Toughness criterion: K_I = s cos^2(beta) sqrt(pi a), K_II = s sin(beta) cos(beta) sqrt(pi a),
  // and K_I^2 + K_II^2 = K_IC^2 (K_IIC = K_IC) gives s = K_IC / (cos(beta) sqrt(pi a)).
  const double k_ic = s.toughness_Pa_sqrt_m;
  const double lefm = crack && std::isfinite(k_ic) ? k_ic / (std::cos(s.beta_rad) * std::sqrt(std::numbers::pi * a)) : kNaN;
  // Seed eq. 4.13 with the grid-line joint length: the same rock under both criteria.
  const double toughness_mismatch =
      std::abs(k_ic / (s.tensile_strength_Pa * std::sqrt(std::numbers::pi * s.cell_size_m / 2.0)) - 1.0);
  // Maximum hoop stress kink angle for this loading: K_II / K_I = sxy / syy.
  const double hoop_deg = have_setup ? analytical::max_hoop_stress_kink_angle(s.far.syy, s.far.sxy) * kDeg : kNaN;

  Tip right, left;
  Broken broken;
  if (r.model && have_setup) {
    right = tip_of(*r.model, s, 1.0);
    if (crack) left = tip_of(*r.model, s, -1.0);
    broken = broken_of(*r.model, *r.config);
    out.files["failed_" + r.variant->name + ".csv"] = broken.csv;
  }
  // a = 0: the uniform field; the exact-field value at the centre point is T0 / (largest
  // normal stress over the joint directions there).
  const double exact = crack ? std::min(right.exact_Pa, left.exact_Pa) : right.exact_Pa;
  auto rel = [&](double ref) { return std::isfinite(ref) && std::isfinite(stop) ? stop / ref - 1.0 : kNaN; };
  const double kink_r = crack ? kink_deg(right) : kNaN, kink_l = crack ? kink_deg(left) : kNaN;
  // Both tips kinked along the -45 degree diagonal (one failed joint each, at -45 deg).
  const double on_diagonals =
      crack ? double(std::abs(kink_r + 45.0) < 1e-3 && std::abs(kink_l + 45.0) < 1e-3) : kNaN;
  const double minus45_fraction = broken.full > 0 ? double(broken.full_minus_45) / broken.full : kNaN;
  out.numbers = {{"half_length_m", a},
                 {"tensile_strength_Pa", s.tensile_strength_Pa},
                 {"increment_Pa", s.increment_Pa},
                 {"stop_Pa", stop},
                 {"g_relation_Pa", g},
                 {"eq430_Pa", eq430},
                 {"exact_field_Pa", exact},
                 {"error_vs_g", rel(g)},
                 {"abs_error_vs_g", std::abs(rel(g))},
                 {"error_vs_eq430", rel(eq430)},
                 {"abs_error_vs_eq430", std::abs(rel(eq430))},
                 {"error_vs_exact", rel(exact)},
                 {"abs_error_vs_exact", std::abs(rel(exact))},
                 {"stop_over_t0", stop / s.tensile_strength_Pa},
                 {"abs_stop_minus_exact_in_increments", std::abs(stop - exact) / s.increment_Pa},
                 {"kink_right_deg", kink_r},
                 {"kink_left_deg", kink_l},
                 {"kink_on_minus45_diagonals", on_diagonals},
                 {"hoop_stress_angle_deg", hoop_deg},
                 {"kink_error_deg", crack ? kink_error_deg(right, left, hoop_deg) : kNaN},
                 {"failed_at_right_tip", crack ? double(right.failed.size()) : kNaN},
                 {"failed_at_left_tip", crack ? double(left.failed.size()) : kNaN},
                 {"failed_joints", double(broken.full)},
                 {"failed_minus45_fraction", minus45_fraction},
                 {"K_IC_Pa_sqrt_m", k_ic},
                 {"lefm_Pa", lefm},
                 {"error_lefm", rel(lefm)},
                 {"abs_error_lefm", std::abs(rel(lefm))},
                 {"toughness_mismatch", toughness_mismatch}};

  nlohmann::json& m = out.json;
  m["half_length_m"] = a;
  m["K_IC_Pa_sqrt_m"] = finite_or_null(k_ic);
  m["lefm_Pa"] = finite_or_null(lefm);
  m["error_lefm"] = finite_or_null(rel(lefm));
  m["joint_length_L_m"] = finite_or_null(s.cell_size_m);
  m["tensile_strength_Pa"] = finite_or_null(s.tensile_strength_Pa);
  m["beta_deg"] = finite_or_null(s.beta_rad * kDeg);
  m["blocks"] = r.model ? r.model->system->n_blocks() : 0;
  if (o) {
    m["ramp"] = {{"levels_solved", o->levels_solved},
                 {"predicted_first_failure_Pa", finite_or_null(o->predicted_first_failure_Pa)},
                 {"jumped_to_Pa", finite_or_null(o->jumped_to_Pa)},
                 {"first_failure_Pa", finite_or_null(o->first_failure_Pa)},
                 {"first_failure_at_jump", o->first_failure_at_jump},
                 {"first_joint_failure_Pa", finite_or_null(o->first_joint_failure_Pa)},
                 {"stop_Pa", finite_or_null(stop)}};
  }
  m["failure_stress_Pa"] = {{"dda", finite_or_null(stop)},
                            {"g_relation", finite_or_null(g)},
                            {"eq430", finite_or_null(eq430)},
                            {"exact_field", finite_or_null(exact)}};
  m["relative_error"] = {{"vs_g_relation", finite_or_null(rel(g))},
                         {"vs_eq430", finite_or_null(rel(eq430))},
                         {"vs_exact_field", finite_or_null(rel(exact))}};
  auto tip_json = [&](const Tip& t) {
    nlohmann::json j;
    j["failed_joint_angles_deg"] = nlohmann::json::array();
    for (const TipJoint& f : t.failed) j["failed_joint_angles_deg"].push_back(f.angle_deg);
    j["exact_field_weakest_joint_deg"] = finite_or_null(t.exact_angle_deg);
    j["exact_field_Pa"] = finite_or_null(t.exact_Pa);
    return j;
  };
  if (crack) m["tips"] = {{"right", tip_json(right)}, {"left", tip_json(left)}};
  else m["centre"] = tip_json(right);
  m["kink_convention"] =
      "angle of the failed joint leaving the tip, from the crack direction ahead of the tip, counter-clockwise "
      "positive in the tip's axes (right tip: from +x; left tip: from -x)";
  m["hoop_stress_kink_deg"] = finite_or_null(hoop_deg);
  m["kink_error_deg"] = finite_or_null(crack ? kink_error_deg(right, left, hoop_deg) : kNaN);
  m["failed_joints"] = {{"both_ends", broken.full}, {"one_end", broken.half}, {"minus_45_of_both_ends", broken.full_minus_45}};

  char line[220];
  std::snprintf(line, sizeof line,
                "a %.1f m  T0 %.0f MPa  stop %.4g Pa  vs G %+.3f  vs eq.4.30 %+.3f  vs exact %+.3f  kink %g / %g deg",
                a, s.tensile_strength_Pa / 1e6, stop, rel(g), rel(eq430), rel(exact), kink_r, kink_l);
  out.summary = line;
  return out;
}

/// failure_stress.csv (one row per run) and relations.csv (the three relations against a
/// for each T0 of the study, L and beta of the first run) for plot.py; abs_scale_error of
/// the runs with `scale_of`.
void study_metrics(StudyOutcome& st) {
  std::string rows = "variant,half_length_m,tensile_strength_Pa,stop_Pa,g_relation_Pa,eq430_Pa,exact_field_Pa\n";
  std::vector<double> strengths;
  const VariantRun* first = nullptr;
  for (const VariantOutcome& v : st.variants) {
    const auto& n = v.metrics.numbers;
    rows += v.variant().name;
    for (const char* k : {"half_length_m", "tensile_strength_Pa", "stop_Pa", "g_relation_Pa", "eq430_Pa",
                          "exact_field_Pa"})
      rows += "," + number(n.at(k));
    rows += "\n";
    const double t0 = n.at("tensile_strength_Pa");
    if (std::isfinite(t0) && std::find(strengths.begin(), strengths.end(), t0) == strengths.end())
      strengths.push_back(t0);
    if (!first && v.run.config) first = &v.run;
  }
  st.metrics.files["failure_stress.csv"] = rows;
  // T0 scaling: a variant with `scale_of: <name>` has the T0 of `t0_MPa` times that of
  // the named run, which its stop level should follow.
  for (VariantOutcome& v : st.variants) {
    if (!v.variant().has("scale_of")) continue;
    const VariantOutcome* base = st.find(v.variant().text("scale_of"));
    double error = kNaN;
    if (base) {
      const double ratio = v.variant().number("t0_MPa") / base->variant().number("t0_MPa");
      error = std::abs(v.metrics.numbers.at("stop_Pa") / (ratio * base->metrics.numbers.at("stop_Pa")) - 1.0);
    }
    v.metrics.numbers["abs_scale_error"] = error;
    v.metrics.json["scale_of"] = {{"variant", v.variant().text("scale_of")}, {"abs_error", finite_or_null(error)}};
  }
  if (!first) return;
  Setup s;
  try {
    s = setup_of(*first->config);
  } catch (const std::exception&) {
    return;
  }
  // The exact-field curve on the -45 degree diagonal (length L / sqrt 2) and the grid
  // line ahead (length L): the lower of the two, as for the runs' tips.
  std::string curves = "tensile_strength_Pa,half_length_m,g_relation_Pa,eq430_Pa,exact_field_Pa\n";
  const double diag = s.cell_size_m / std::sqrt(2.0);
  for (double t0 : strengths)
    for (int i = 1; i <= 120; ++i) {
      const double a = 0.05 * i;
      const double exact =
          std::min(analytical::joint_failure_stress(t0, a, s.far, -std::numbers::pi / 4, diag),
                   analytical::joint_failure_stress(t0, a, s.far, 0.0, s.cell_size_m));
      curves += number(t0) + "," + number(a) + "," +
                number(analytical::mixed_mode_failure_stress_g(t0, s.cell_size_m, a, s.beta_rad)) + "," +
                number(analytical::mixed_mode_failure_stress_eq430(t0, s.cell_size_m, a, s.beta_rad)) + "," +
                number(exact) + "\n";
    }
  st.metrics.files["relations.csv"] = curves;
}

}  // namespace

CaseDefinition case_definition() {
  return {[](const io::CaseConfig& c, const VariantSpec&) { setup_of(c); }, variant_metrics, study_metrics};
}

}  // namespace hfdda::verification
