// Metrics of the KGD toughness-storage case (seed 4.5, Figures 4.11-4.14): half-length,
// inlet width and inlet net pressure of each run's record against the zero-viscosity,
// zero-leak-off KGD solution (K-vertex, analytical/kgd.hpp) with the toughness of the
// run's path joints (K_IC = T0 sqrt(pi L / 2), seed eq. 4.13), at every step and at the
// end time; the stair-step of the length and the oscillation of the pressure and width
// around the solution; the mass ledger; and, across variants, the half-lengths of the
// K_IC-matched pairs. Variants, thresholds and checks are in study.yaml. Writes
// series_<variant>.csv and analytical_<variant>.csv per variant for plot.py.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "analytical/kgd.hpp"
#include "fracture/fracture_criteria.hpp"
#include "harness.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::verification {
namespace {

/// Physical parameters of a variant, read from its case file (and its mesh for K_IC).
struct Physics {
  double youngs_modulus_Pa = kNaN, poissons_ratio = kNaN;
  double total_rate_m2_s = kNaN;  ///< Q0 = mass rate / fluid density (per metre of height)
  double mass_rate_kg_s = kNaN;
  double start_time_s = 0.0;
  double end_time_s = kNaN;
  double toughness_Pa_sqrt_m = kNaN;  ///< K_IC of the path joints (eq. 4.13)
};

/// The breakable joints on y = 0 (the path) and the K_IC their bonds stand for.
struct Path {
  int joints = 0;
  double length_min_m = kNaN, length_max_m = kNaN;
  double t0_min_Pa = kNaN, t0_max_Pa = kNaN;
  double kic_min = kNaN, kic_max = kNaN;
};

/// One row of the comparison with the K-vertex.
struct Sample {
  double t = kNaN, time_s = kNaN;
  double half_length = kNaN, xmin = kNaN, xmax = kNaN, width = kNaN, net_pressure = kNaN;
  double half_length_exact = kNaN, width_exact = kNaN, net_pressure_exact = kNaN;
  double mass_balance_error = kNaN, step_wall_s = kNaN;
};

double relative_error(double value, double exact) { return (value - exact) / exact; }
double min_nan(double a, double b) { return std::isnan(a) ? b : std::min(a, b); }
double max_nan(double a, double b) { return std::isnan(a) ? b : std::max(a, b); }

Physics physics_of(const io::CaseConfig& c) {
  Physics p;
  if (!c.fluid) throw std::runtime_error("case has no 'fluid' section (no flow network)");
  if (c.injections.size() != 1) throw std::runtime_error("case needs exactly one injection");
  if (c.fluid->leak_off_coefficient_m_sqrt_s != 0.0)
    throw std::runtime_error("the K-vertex has no leak-off (fluid.leak_off_coefficient must be 0)");
  if (c.far_field.sxx_Pa != 0.0 || c.far_field.syy_Pa != 0.0 || c.far_field.sxy_Pa != 0.0)
    throw std::runtime_error("the comparison assumes no background stress");
  const io::MaterialConfig& rock = c.materials.at(0);
  p.youngs_modulus_Pa = rock.youngs_modulus_Pa;
  p.poissons_ratio = rock.poissons_ratio;
  p.mass_rate_kg_s = c.injections[0].mass_rate_kg_s;
  p.total_rate_m2_s = p.mass_rate_kg_s / c.fluid->density_kg_m3;  // Q0, both wings, per metre
  p.start_time_s = c.injections[0].start_time_s;
  p.end_time_s = c.time.end_time_s;
  return p;
}

Path path_of(const mesh::Mesh& mesh, const io::CaseConfig& c) {
  Path path;
  const Rect& in = *c.domain.inner;
  for (int j : mesh::joints_on_segment(mesh, Vec2(in.xmin, 0), Vec2(in.xmax, 0), 1e-6)) {
    const mesh::Joint& joint = mesh.joints[j];
    if (!joint.properties.breakable || joint.properties.initially_open) continue;
    const double length = (mesh.points[joint.point_q] - mesh.points[joint.point_p]).norm();
    const double t0 = fracture::bond_strength(joint.properties, length).tensile_strength_Pa;
    const double kic = analytical::toughness_of_tensile_strength(t0, length);  // eq. 4.13
    ++path.joints;
    path.length_min_m = min_nan(path.length_min_m, length);
    path.length_max_m = max_nan(path.length_max_m, length);
    path.t0_min_Pa = min_nan(path.t0_min_Pa, t0);
    path.t0_max_Pa = max_nan(path.t0_max_Pa, t0);
    path.kic_min = min_nan(path.kic_min, kic);
    path.kic_max = max_nan(path.kic_max, kic);
  }
  return path;
}

analytical::KgdToughnessSolution exact_at(const Physics& p, double t) {
  return analytical::kgd_toughness_storage(p.youngs_modulus_Pa, p.poissons_ratio, p.toughness_Pa_sqrt_m,
                                           p.total_rate_m2_s, t);
}

std::vector<Sample> samples_of(const simulation::RunRecord& record, const Physics& p) {
  std::vector<Sample> samples;
  for (std::size_t row = 0; row < record.rows(); ++row) {
    auto value = [&](const std::string& name) { return record.value(row, name); };
    Sample s;
    s.time_s = value("time_s");
    s.t = s.time_s - p.start_time_s;
    if (!(s.t > 0.0)) continue;  // the K-vertex starts at t = 0+
    s.xmin = value("open_xmin_m");
    s.xmax = value("open_xmax_m");
    s.half_length = 0.5 * (s.xmax - s.xmin);
    s.width = value("injection_aperture_m");
    s.net_pressure = value("injection_pressure_Pa");  // no background stress
    s.mass_balance_error = value("mass_balance_error");
    s.step_wall_s = value("step_wall_s");
    const auto exact = exact_at(p, s.t);
    s.half_length_exact = exact.half_length_m;
    s.width_exact = exact.inlet_width_m;
    s.net_pressure_exact = exact.inlet_net_pressure_Pa;
    samples.push_back(s);
  }
  return samples;
}

std::string series_csv(const std::vector<Sample>& samples) {
  std::string text =
      "time_s,half_length_m,half_length_exact_m,open_xmin_m,open_xmax_m,inlet_width_m,inlet_width_exact_m,"
      "inlet_net_pressure_Pa,inlet_net_pressure_exact_Pa,mass_balance_error,step_wall_s\n";
  for (const Sample& s : samples) {
    for (double v : {s.time_s, s.half_length, s.half_length_exact, s.xmin, s.xmax, s.width, s.width_exact,
                     s.net_pressure, s.net_pressure_exact, s.mass_balance_error})
      text += number(v) + ",";
    text += number(s.step_wall_s) + "\n";
  }
  return text;
}

/// The K-vertex curves of a variant for the plots, from the function the checks use.
std::string analytical_csv(const Physics& p) {
  std::string text = "time_s,half_length_m,inlet_width_m,inlet_net_pressure_Pa\n";
  const int n = 400;
  const double t_end = p.end_time_s - p.start_time_s;
  for (int i = 1; i <= n; ++i) {
    const double t = t_end * std::pow(double(i) / n, 2.0);  // denser at early times
    const auto e = exact_at(p, t);
    text += number(t + p.start_time_s) + "," + number(e.half_length_m) + "," + number(e.inlet_width_m) + "," +
            number(e.inlet_net_pressure_Pa) + "\n";
  }
  return text;
}

/// Stair-step of the length and oscillation of p0, w0 around the K-vertex.
struct Discreteness {
  int growth_steps = 0;          ///< steps in which the fracture got longer
  int still_steps = 0;           ///< steps in which it did not
  double largest_jump_joints = kNaN;  ///< largest growth of the total length in one step, in joints
  double p_rms = kNaN, p_max = kNaN;  ///< relative deviation of p0 over the second half of the run
  double w_rms = kNaN, w_max = kNaN;  ///< same for w0
  double l_rms = kNaN;                ///< same for l
};

Discreteness discreteness_of(const std::vector<Sample>& samples, double joint_length_m, double t_end) {
  Discreteness d;
  double previous = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double total = samples[i].xmax - samples[i].xmin;
    if (i > 0) {
      const double jump = (total - previous) / joint_length_m;
      if (jump > 0.5) ++d.growth_steps; else ++d.still_steps;
      d.largest_jump_joints = max_nan(d.largest_jump_joints, jump);
    }
    previous = total;
  }
  double sp = 0.0, sw = 0.0, sl = 0.0;
  int n = 0;
  for (const Sample& s : samples) {
    if (s.t <= 0.5 * t_end) continue;
    const double ep = relative_error(s.net_pressure, s.net_pressure_exact);
    const double ew = relative_error(s.width, s.width_exact);
    const double el = relative_error(s.half_length, s.half_length_exact);
    sp += ep * ep;
    sw += ew * ew;
    sl += el * el;
    d.p_max = max_nan(d.p_max, std::abs(ep));
    d.w_max = max_nan(d.w_max, std::abs(ew));
    ++n;
  }
  if (n > 0) {
    d.p_rms = std::sqrt(sp / n);
    d.w_rms = std::sqrt(sw / n);
    d.l_rms = std::sqrt(sl / n);
  }
  return d;
}

Metrics variant_metrics(const VariantRun& r) {
  Physics physics;
  Path path;
  if (r.config) try {
      physics = physics_of(*r.config);
    } catch (const std::exception&) {
      // reported by validate as "case not built"
    }
  if (r.model) {
    path = path_of(r.model->system->mesh(), *r.config);
    physics.toughness_Pa_sqrt_m = 0.5 * (path.kic_min + path.kic_max);
  }
  Metrics out;
  nlohmann::json& m = out.json;
  const std::vector<Sample> samples =
      r.built && path.joints > 0 ? samples_of(r.record(), physics) : std::vector<Sample>{};
  if (!samples.empty()) {
    out.files["series_" + r.variant->name + ".csv"] = series_csv(samples);
    out.files["analytical_" + r.variant->name + ".csv"] = analytical_csv(physics);
  }

  const Sample* end = nullptr;
  if (!samples.empty() && r.completed &&
      std::abs(samples.back().time_s - physics.end_time_s) <= 1e-6 * physics.end_time_s)
    end = &samples.back();
  auto end_error = [&](double Sample::*value, double Sample::*exact) {
    return end ? relative_error(end->*value, end->*exact) : kNaN;
  };
  double max_mass = kNaN;
  if (!samples.empty()) {
    max_mass = 0.0;
    for (const Sample& s : samples) {
      if (!std::isfinite(s.mass_balance_error)) {
        max_mass = kNaN;
        break;
      }
      max_mass = std::max(max_mass, std::abs(s.mass_balance_error));
    }
  }
  const double e_l = end_error(&Sample::half_length, &Sample::half_length_exact);
  const double e_w = end_error(&Sample::width, &Sample::width_exact);
  const double e_p = end_error(&Sample::net_pressure, &Sample::net_pressure_exact);
  const Discreteness d = discreteness_of(samples, path.length_max_m, physics.end_time_s - physics.start_time_s);
  out.numbers = {{"end_time_s", physics.end_time_s},
                 {"max_mass_balance_error", max_mass},
                 {"half_length_m", end ? end->half_length : kNaN},
                 {"abs_half_length_error", std::abs(e_l)},
                 {"abs_inlet_width_error", std::abs(e_w)},
                 {"abs_inlet_net_pressure_error", std::abs(e_p)},
                 {"toughness_spread", path.joints > 0 ? path.kic_max / path.kic_min - 1.0 : kNaN},
                 {"pressure_rms_deviation", d.p_rms}};

  m["path_joints"] = path.joints;
  m["path_joint_length_m"] = {finite_or_null(path.length_min_m), finite_or_null(path.length_max_m)};
  m["path_tensile_strength_Pa"] = {finite_or_null(path.t0_min_Pa), finite_or_null(path.t0_max_Pa)};
  m["fracture_toughness_Pa_sqrt_m"] = finite_or_null(physics.toughness_Pa_sqrt_m);
  m["blocks"] = r.model ? r.model->system->n_blocks() : 0;
  m["max_mass_balance_error"] = finite_or_null(max_mass);
  m["stair_step"] = {{"growth_steps", d.growth_steps},
                     {"steps_without_growth", d.still_steps},
                     {"largest_jump_joints", finite_or_null(d.largest_jump_joints)}};
  m["second_half_relative_deviation"] = {
      {"inlet_net_pressure_rms", finite_or_null(d.p_rms)}, {"inlet_net_pressure_max", finite_or_null(d.p_max)},
      {"inlet_width_rms", finite_or_null(d.w_rms)},        {"inlet_width_max", finite_or_null(d.w_max)},
      {"half_length_rms", finite_or_null(d.l_rms)}};
  if (end) {
    m["at_end"] = {{"half_length_m", end->half_length},
                   {"half_length_exact_m", end->half_length_exact},
                   {"open_xmin_m", end->xmin},
                   {"open_xmax_m", end->xmax},
                   {"inlet_width_m", end->width},
                   {"inlet_width_exact_m", end->width_exact},
                   {"inlet_net_pressure_Pa", end->net_pressure},
                   {"inlet_net_pressure_exact_Pa", end->net_pressure_exact}};
    m["error_at_end"] = {{"half_length", e_l}, {"inlet_width", e_w}, {"inlet_net_pressure", e_p}};
    // The wings may grow unequally. Under the K-vertex's uniform pressure the opening is
    // elliptic, w(x) = w_centre sqrt(1 - (x - c)^2 / l^2), so an inlet off the centre c of
    // the open fracture sees a narrower opening than w0 even with the right l and p.
    const double offset = 0.5 * (end->xmax + end->xmin);
    const double ellipse = std::sqrt(std::max(0.0, 1.0 - (offset / end->half_length) * (offset / end->half_length)));
    m["asymmetry_at_end"] = {
        {"centre_offset_m", offset},
        {"centre_offset_over_l", offset / end->half_length},
        {"inlet_width_error_vs_offset_ellipse", relative_error(end->width, end->width_exact * ellipse)}};
  }
  char line[200];
  std::snprintf(line, sizeof line,
                "K_IC %.4g  path joints %3d  l %+.4f  w0 %+.4f  p0 %+.4f  jumps %d (max %.0f joints)  p rms %.3f  "
                "mass %.2e",
                physics.toughness_Pa_sqrt_m, path.joints, e_l, e_w, e_p, d.growth_steps, d.largest_jump_joints,
                d.p_rms, max_mass);
  out.summary = line;
  return out;
}

/// Matched pairs: a variant with attribute `matches: <name>` has the same K_IC as that
/// variant on another joint length; its half-length at the end time is compared.
void study_metrics(StudyOutcome& s) {
  for (VariantOutcome& v : s.variants) {
    if (!v.variant().has("matches")) continue;
    const VariantOutcome* other = s.find(v.variant().text("matches"));
    double difference = kNaN, toughness_difference = kNaN;
    if (other != nullptr) {
      const double mine = v.metrics.numbers.at("half_length_m");
      const double theirs = other->metrics.numbers.at("half_length_m");
      difference = std::abs(mine - theirs) / theirs;
      const double k_mine = v.metrics.json.value("fracture_toughness_Pa_sqrt_m", nlohmann::json()).is_number()
                                ? v.metrics.json["fracture_toughness_Pa_sqrt_m"].get<double>() : kNaN;
      const double k_theirs =
          other->metrics.json.value("fracture_toughness_Pa_sqrt_m", nlohmann::json()).is_number()
              ? other->metrics.json["fracture_toughness_Pa_sqrt_m"].get<double>() : kNaN;
      toughness_difference = std::abs(k_mine - k_theirs) / k_theirs;
    }
    v.metrics.numbers["abs_half_length_vs_match"] = difference;
    v.metrics.json["half_length_vs_match"] = {{"matches", v.variant().text("matches")},
                                              {"relative_difference", finite_or_null(difference)},
                                              {"toughness_relative_difference", finite_or_null(toughness_difference)}};
  }
}

}  // namespace

CaseDefinition case_definition() {
  return {[](const io::CaseConfig& c, const VariantSpec&) {
            physics_of(c);
            if (!c.domain.inner) throw std::runtime_error("case needs domain.inner (the path runs across it)");
          },
          variant_metrics, study_metrics};
}

}  // namespace hfdda::verification
