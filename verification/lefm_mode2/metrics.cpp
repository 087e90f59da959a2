// Metrics of the Mode II LEFM case (seed 4.3, Figure 4.8): the far-field shear at which a
// centre crack of half-length a fails (the level of the stop condition, over 75 % of the
// path sheared) against eq. 4.24 with N = 0, tau = C0 sqrt(L / 2a), and against the
// exact-field relation tau = C0 sqrt(L / (2a + L)) (the shear stress
// tau x / sqrt(x^2 - a^2) on the crack line integrated over the joint [a, a + L] and set
// equal to C0 L); the levels of the first bond failure and of the first whole-joint
// failure. With the toughness criterion at crack tips (fracture.criterion:
// energy_release_rate) the reference is the LEFM relation tau = K_IIC / sqrt(pi a)
// (K_II = tau sqrt(pi a)), and the same K_IIC on L = 0.5 and 1 m are compared with each
// other (study metrics objectivity_a2/a3/a5); delaunay_mesh marks the runs on a constrained
// Delaunay mesh. Variants, thresholds and checks are in study.yaml. Writes failure_stress.csv
// (one row per variant) for plot.py. Stresses in Pa, lengths in m.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "fracture/fracture_criteria.hpp"
#include "harness.hpp"
#include "mesh/mesh.hpp"
#include "statistics.hpp"

namespace hfdda::verification {
namespace {

/// What the comparison needs from the case file.
struct Setup {
  double half_length_m = 0.0;  ///< a: half-length of the initially open crack (0: none)
  double increment_Pa = kNaN;  ///< ramp increment
  Vec2 path_from{0, 0}, path_to{0, 0};
  double mode2_toughness_Pa_sqrt_m = kNaN;  ///< K_IIC with the toughness criterion, NaN otherwise
};

constexpr double kPi = 3.14159265358979323846;

/// The breakable joints of the path: their lengths and cohesion.
struct Path {
  int joints = 0;
  Range length_m, cohesion_Pa;
};

Setup setup_of(const io::CaseConfig& c) {
  if (!c.load_ramp) throw std::runtime_error("case has no load_ramp");
  const io::LoadRampConfig& ramp = *c.load_ramp;
  if (ramp.sxx != 0.0 || ramp.syy != 0.0 || ramp.sxy != 1.0)
    throw std::runtime_error("the comparison needs pure far-field shear: load_ramp sxx = syy = 0, sxy = 1");
  if (!ramp.history.empty() || !ramp.increment_Pa) throw std::runtime_error("the ramp must be uniform");
  if (ramp.stop_when != "broken_fraction") throw std::runtime_error("the ramp must stop on broken_fraction");
  if (c.far_field.sxx_Pa != 0.0 || c.far_field.syy_Pa != 0.0 || c.far_field.sxy_Pa != 0.0)
    throw std::runtime_error("the comparison assumes no background stress");
  if (c.fluid) throw std::runtime_error("the case has no fluid");
  Setup s;
  s.increment_Pa = *ramp.increment_Pa;
  if (c.fracture.criterion == io::FailureCriterionKind::energy_release_rate) {
    if (!c.fracture.fracture_toughness_Pa_sqrt_m) throw std::runtime_error("the toughness criterion needs fracture_toughness");
    s.mode2_toughness_Pa_sqrt_m = c.fracture.mode2_toughness_Pa_sqrt_m.value_or(*c.fracture.fracture_toughness_Pa_sqrt_m);
  }
  bool have_path = false;
  for (const io::FractureConfig& f : c.fractures) {
    if (f.name == "path") {
      s.path_from = f.from;
      s.path_to = f.to;
      have_path = true;
    } else if (f.initially_open) {
      if (std::abs(f.from.y()) > 0.0 || std::abs(f.to.y()) > 0.0 || std::abs(f.from.x() + f.to.x()) > 1e-9)
        throw std::runtime_error("the initial crack must be centred on y = 0");
      s.half_length_m = std::max(s.half_length_m, 0.5 * std::abs(f.to.x() - f.from.x()));
    }
  }
  if (!have_path) throw std::runtime_error("case needs a fracture named 'path'");
  return s;
}

Path path_of(const mesh::Mesh& mesh, const Setup& s) {
  Path p;
  for (int j : mesh::joints_on_segment(mesh, s.path_from, s.path_to, 1e-6)) {
    const mesh::Joint& joint = mesh.joints[j];
    if (!joint.properties.breakable || joint.properties.initially_open) continue;
    const double length = (mesh.points[joint.point_q] - mesh.points[joint.point_p]).norm();
    const double c0 = fracture::bond_strength(joint.properties, length).cohesion_Pa;
    ++p.joints;
    p.length_m.add(length);
    p.cohesion_Pa.add(c0);
  }
  return p;
}

/// Eq. 4.24 with N = 0 (infinite for a = 0: the near-tip field alone has no limit).
double eq_4_24(double c0, double l, double a) { return a > 0.0 ? c0 * std::sqrt(l / (2.0 * a)) : kNaN; }
/// The exact-field relation: C0 at a = 0, eq. 4.24 for a >> L.
double exact_field(double c0, double l, double a) { return c0 * std::sqrt(l / (2.0 * a + l)); }
/// LEFM: K_II = tau sqrt(pi a) reaches K_IIC.
double lefm(double k_iic, double a) { return a > 0.0 ? k_iic / std::sqrt(kPi * a) : kNaN; }

Metrics variant_metrics(const VariantRun& r) {
  Metrics out;
  Setup s;
  Path path;
  if (r.config) try {
      s = setup_of(*r.config);
    } catch (const std::exception&) {
      // reported by validate
    }
  if (r.model) path = path_of(r.model->system->mesh(), s);
  const double l = path.length_m.max, c0 = path.cohesion_Pa.max, a = s.half_length_m;
  simulation::LoadRampOutcome o;
  if (r.model && r.model->ramp) o = r.model->ramp->outcome();
  const double stop = o.stop_reached ? o.stop_Pa : kNaN;
  const double tau_424 = eq_4_24(c0, l, a), tau_exact = exact_field(c0, l, a);
  const double err_424 = (stop - tau_424) / tau_424, err_exact = (stop - tau_exact) / tau_exact;
  const double k_iic = s.mode2_toughness_Pa_sqrt_m, tau_lefm = lefm(k_iic, a), err_lefm = (stop - tau_lefm) / tau_lefm;
  // a = 0: the path is intact in a uniform field, so it must fail at C0.
  const double a0_increments = a == 0.0 ? std::abs(stop - c0) / s.increment_Pa : kNaN;

  out.numbers = {{"a_m", a},
                 {"joint_length_m", l},
                 {"cohesion_Pa", c0},
                 {"stop_reached", o.stop_reached ? 1.0 : 0.0},
                 {"failure_stress_Pa", stop},
                 {"first_failure_Pa", o.first_failure_Pa},
                 {"first_joint_failure_Pa", o.first_joint_failure_Pa},
                 {"eq_4_24_Pa", tau_424},
                 {"exact_field_Pa", tau_exact},
                 {"error_eq_4_24", err_424},
                 {"error_exact_field", err_exact},
                 {"abs_error_exact_field", std::abs(err_exact)},
                 {"a0_offset_increments", a0_increments},
                 {"first_failure_at_jump", o.first_failure_at_jump ? 1.0 : 0.0},
                 {"path_length_spread", path.length_m.spread()},
                 {"path_cohesion_spread", path.cohesion_Pa.spread()},
                 {"spread_first_failure_Pa", stop - o.first_failure_Pa},
                 {"spread_first_joint_failure_Pa", stop - o.first_joint_failure_Pa},
                 {"K_IIC_Pa_sqrt_m", k_iic},
                 {"lefm_Pa", tau_lefm},
                 {"error_lefm", err_lefm},
                 {"abs_error_lefm", std::abs(err_lefm)},
                 // seed eq. 4.13 with C0 for T0: the same rock under both criteria
                 {"toughness_mismatch", std::abs(k_iic / (c0 * std::sqrt(kPi * l / 2.0)) - 1.0)},
                 // 1: constrained Delaunay mesh, 0: structured
                 {"delaunay_mesh", r.config && r.config->mesh.kind == io::MeshKind::delaunay ? 1.0 : 0.0}};
  nlohmann::json& m = out.json;
  for (const auto& [key, value] : out.numbers) m[key] = finite_or_null(value);
  m["path_joints"] = path.joints;
  m["blocks"] = r.model ? r.model->system->n_blocks() : 0;
  m["increment_Pa"] = finite_or_null(s.increment_Pa);
  m["levels_solved"] = o.levels_solved;
  m["predicted_first_failure_Pa"] = finite_or_null(o.predicted_first_failure_Pa);
  m["broken_fraction"] = o.broken_fraction;
  char line[240];
  std::snprintf(line, sizeof line,
                "a %.2g L %.2g C0 %.3g: stop %.6g Pa (eq 4.24 %+.4f, exact %+.4f), first bond %.6g, first joint %.6g",
                a, l, c0, stop, err_424, err_exact, o.first_failure_Pa, o.first_joint_failure_Pa);
  out.summary = line;
  if (std::isfinite(k_iic)) {
    std::snprintf(line, sizeof line, "; LEFM %.6g Pa (%+.4f)", tau_lefm, err_lefm);
    out.summary += line;
  }
  return out;
}

/// failure_stress.csv: one row per variant, for plot.py.
void study_metrics(StudyOutcome& st) {
  std::string text =
      "variant,a_m,joint_length_m,cohesion_Pa,failure_stress_Pa,first_failure_Pa,first_joint_failure_Pa,"
      "eq_4_24_Pa,exact_field_Pa,K_IIC_Pa_sqrt_m,lefm_Pa,delaunay_mesh\n";
  for (const VariantOutcome& v : st.variants) {
    const auto& n = v.metrics.numbers;
    auto get = [&](const char* key) { return n.count(key) ? n.at(key) : kNaN; };
    text += v.variant().name;
    for (const char* key : {"a_m", "joint_length_m", "cohesion_Pa", "failure_stress_Pa", "first_failure_Pa",
                            "first_joint_failure_Pa", "eq_4_24_Pa", "exact_field_Pa", "K_IIC_Pa_sqrt_m", "lefm_Pa",
                            "delaunay_mesh"}) {
      text += ',';
      text += number(get(key));
    }
    text += "\n";
  }
  st.metrics.files["failure_stress.csv"] = text;
  // Mesh objectivity of the toughness criterion: K_IIC = 0.886 MPa m^0.5 on L = 1 m
  // (C0 = 0.707 MPa) against L = 0.5 m (C0 = 1 MPa) at the same a.
  for (const int a : {2, 3, 5}) {
    const std::string key = "objectivity_a" + std::to_string(a);
    const VariantOutcome* fine = st.find("l05_c1_a" + std::to_string(a) + "_e");
    const VariantOutcome* coarse = st.find("l1_c07_a" + std::to_string(a) + "_e");
    const double ratio = fine && coarse ? coarse->metrics.numbers.at("failure_stress_Pa") /
                                              fine->metrics.numbers.at("failure_stress_Pa")
                                        : kNaN;
    st.metrics.numbers[key] = std::abs(ratio - 1.0);
    st.metrics.json[key] = finite_or_null(std::abs(ratio - 1.0));
    st.metrics.json["objectivity_ratio_a" + std::to_string(a)] = finite_or_null(ratio);
  }
}

}  // namespace

CaseDefinition case_definition() {
  return {[](const io::CaseConfig& c, const VariantSpec&) { setup_of(c); }, variant_metrics, study_metrics};
}

}  // namespace hfdda::verification
