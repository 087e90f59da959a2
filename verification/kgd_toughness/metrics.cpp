// Metrics of the KGD toughness-storage case (seed 4.5, Figures 4.11-4.14): half-length,
// inlet width and inlet net pressure of each run's record against the zero-viscosity,
// zero-leak-off KGD solution (K-vertex, analytical/kgd.hpp) with the toughness of the
// run's path joints (K_IC = T0 sqrt(pi L / 2), seed eq. 4.13), at every step and at the
// end time, and at the end time against the solution with the toughness and the run's
// own viscosity (analytical/kgd_transition.hpp); the stair-step of the length and the
// oscillation of the pressure and width
// around the solution; the mass ledger; and, across variants, the half-lengths of the
// K_IC-matched pairs. Variants, thresholds and checks are in study.yaml. Writes
// series_<variant>.csv and analytical_<variant>.csv per variant for plot.py; the record
// reading and the CSV formats are shared with the viscosity case
// (verification/harness/kgd_series.hpp).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "analytical/kgd.hpp"
#include "analytical/kgd_transition.hpp"
#include "fracture/fracture_criteria.hpp"
#include "harness.hpp"
#include "kgd_series.hpp"
#include "mesh/mesh.hpp"
#include "statistics.hpp"

namespace hfdda::verification {
namespace {

/// A variant's injection (kgd_series.hpp) and the K_IC of its path joints (eq. 4.13).
struct Physics {
  KgdInjection injection;
  double toughness_Pa_sqrt_m = kNaN;
};

/// The breakable joints on y = 0 (the path) and the K_IC their bonds stand for.
struct Path {
  int joints = 0;
  Range length_m, t0_Pa, kic_Pa_sqrt_m;
};

double relative_error(double value, double exact) { return (value - exact) / exact; }

Physics physics_of(const io::CaseConfig& c) {
  Physics p;
  p.injection = kgd_injection_of(c);
  if (p.injection.leak_off_coefficient_m_sqrt_s != 0.0)
    throw std::runtime_error("the K-vertex has no leak-off (fluid.leak_off_coefficient must be 0)");
  if (c.far_field.sxx_Pa != 0.0 || c.far_field.syy_Pa != 0.0 || c.far_field.sxy_Pa != 0.0)
    throw std::runtime_error("the comparison assumes no background stress");
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
    ++path.joints;
    path.length_m.add(length);
    path.t0_Pa.add(t0);
    path.kic_Pa_sqrt_m.add(analytical::toughness_of_tensile_strength(t0, length));  // eq. 4.13
  }
  return path;
}

KgdSolution k_vertex_of(const Physics& p) {
  return [i = p.injection, k = p.toughness_Pa_sqrt_m](double t) {
    return kgd_values(
        analytical::kgd_toughness_storage(i.youngs_modulus_Pa, i.poissons_ratio, k, i.total_rate_m2_s, t));
  };
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

Discreteness discreteness_of(const std::vector<KgdSample>& samples, double joint_length_m, double t_end) {
  Discreteness d;
  double previous = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double total = samples[i].open_xmax_m - samples[i].open_xmin_m;
    if (i > 0) {
      const double jump = (total - previous) / joint_length_m;
      if (jump > 0.5) ++d.growth_steps; else ++d.still_steps;
      d.largest_jump_joints = nan_max(d.largest_jump_joints, jump);
    }
    previous = total;
  }
  double sp = 0.0, sw = 0.0, sl = 0.0;
  int n = 0;
  for (const KgdSample& s : samples) {
    if (s.t <= 0.5 * t_end) continue;
    const KgdValues e = kgd_errors(&s);
    sp += e.inlet_net_pressure_Pa * e.inlet_net_pressure_Pa;
    sw += e.inlet_width_m * e.inlet_width_m;
    sl += e.half_length_m * e.half_length_m;
    d.p_max = nan_max(d.p_max, std::abs(e.inlet_net_pressure_Pa));
    d.w_max = nan_max(d.w_max, std::abs(e.inlet_width_m));
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
    physics.toughness_Pa_sqrt_m = 0.5 * (path.kic_Pa_sqrt_m.min + path.kic_Pa_sqrt_m.max);
  }
  const KgdInjection& injection = physics.injection;
  Metrics out;
  nlohmann::json& m = out.json;
  // No background stress (physics_of): the inlet pressure is the net pressure.
  const std::vector<KgdSample> samples = r.built && path.joints > 0
                                             ? kgd_samples(r.record(), injection, 0.0, k_vertex_of(physics))
                                             : std::vector<KgdSample>{};
  if (!samples.empty()) {
    out.files["series_" + r.variant->name + ".csv"] = kgd_series_csv(samples);
    out.files["analytical_" + r.variant->name + ".csv"] = kgd_analytical_csv(injection, k_vertex_of(physics));
  }

  const KgdSample* end = kgd_end_sample(samples, r.completed, injection.end_time_s);
  const KgdValues error = kgd_errors(end);
  const double max_mass = kgd_max_mass_balance_error(samples);
  const Discreteness d =
      discreteness_of(samples, path.length_m.max, injection.end_time_s - injection.start_time_s);
  // How far the run is from the K-vertex's regime by its physics alone (analytical/kgd.hpp):
  // below about 4 the fluid's pressure drop along the fracture is not negligible.
  const double dimensionless_toughness =
      analytical::kgd_dimensionless_toughness(injection.youngs_modulus_Pa, injection.poissons_ratio,
                                              physics.toughness_Pa_sqrt_m, injection.viscosity_Pa_s,
                                              injection.total_rate_m2_s);
  // The same end against the toughness-and-viscosity solution of the run's own fluid
  // (analytical/kgd_transition.hpp), which the K-vertex approximates for K_m >~ 4.
  KgdValues error_km{kNaN, kNaN, kNaN};
  nlohmann::json km_json = nullptr;
  if (end && std::isfinite(physics.toughness_Pa_sqrt_m)) try {
    const analytical::KgdTransitionSolution km = analytical::kgd_toughness_viscosity(
        injection.youngs_modulus_Pa, injection.poissons_ratio, physics.toughness_Pa_sqrt_m, injection.viscosity_Pa_s,
        injection.total_rate_m2_s, end->t);
    error_km = {relative_error(end->run.half_length_m, km.half_length_m),
                relative_error(end->run.inlet_width_m, km.inlet_width_m),
                relative_error(end->run.inlet_net_pressure_Pa, km.inlet_net_pressure_Pa)};
    km_json = {{"half_length_m", km.half_length_m},
               {"inlet_width_m", km.inlet_width_m},
               {"inlet_net_pressure_Pa", km.inlet_net_pressure_Pa},
               {"mean_net_pressure_Pa", km.mean_net_pressure_Pa},
               {"error_half_length", error_km.half_length_m},
               {"error_inlet_width", error_km.inlet_width_m},
               {"error_inlet_net_pressure", error_km.inlet_net_pressure_Pa}};
  } catch (const std::exception& e) {
    km_json = {{"error", e.what()}};  // the checks then see NaN and fail
  }
  out.numbers = {{"end_time_s", injection.end_time_s},
                 {"abs_half_length_error_km", std::abs(error_km.half_length_m)},
                 {"abs_inlet_width_error_km", std::abs(error_km.inlet_width_m)},
                 {"abs_inlet_net_pressure_error_km", std::abs(error_km.inlet_net_pressure_Pa)},
                 {"dimensionless_toughness", dimensionless_toughness},
                 {"max_mass_balance_error", max_mass},
                 {"half_length_m", end ? end->run.half_length_m : kNaN},
                 {"abs_half_length_error", std::abs(error.half_length_m)},
                 {"abs_inlet_width_error", std::abs(error.inlet_width_m)},
                 {"abs_inlet_net_pressure_error", std::abs(error.inlet_net_pressure_Pa)},
                 {"toughness_spread", path.kic_Pa_sqrt_m.spread()},
                 {"pressure_rms_deviation", d.p_rms}};

  m["path_joints"] = path.joints;
  m["path_joint_length_m"] = {finite_or_null(path.length_m.min), finite_or_null(path.length_m.max)};
  m["path_tensile_strength_Pa"] = {finite_or_null(path.t0_Pa.min), finite_or_null(path.t0_Pa.max)};
  m["fracture_toughness_Pa_sqrt_m"] = finite_or_null(physics.toughness_Pa_sqrt_m);
  m["dimensionless_toughness"] = finite_or_null(dimensionless_toughness);
  m["toughness_viscosity_solution_at_end"] = km_json;
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
    m["at_end"] = kgd_at_end_json(*end);
    m["at_end"]["open_xmin_m"] = end->open_xmin_m;
    m["at_end"]["open_xmax_m"] = end->open_xmax_m;
    m["error_at_end"] = kgd_errors_json(error);
    // The wings may grow unequally. Under the K-vertex's uniform pressure the opening is
    // elliptic, w(x) = w_centre sqrt(1 - (x - c)^2 / l^2), so an inlet off the centre c of
    // the open fracture sees a narrower opening than w0 even with the right l and p.
    const double l = end->run.half_length_m;
    const double offset = 0.5 * (end->open_xmax_m + end->open_xmin_m);
    const double ellipse = std::sqrt(std::max(0.0, 1.0 - (offset / l) * (offset / l)));
    m["asymmetry_at_end"] = {
        {"centre_offset_m", offset},
        {"centre_offset_over_l", offset / l},
        {"inlet_width_error_vs_offset_ellipse",
         relative_error(end->run.inlet_width_m, end->exact.inlet_width_m * ellipse)}};
  }
  char line[240];
  std::snprintf(line, sizeof line,
                "K_IC %.4g  K_m %.3g  path joints %3d  l %+.4f  w0 %+.4f  p0 %+.4f  jumps %d (max %.0f joints)  p rms %.3f  "
                "mass %.2e",
                physics.toughness_Pa_sqrt_m, dimensionless_toughness, path.joints, error.half_length_m, error.inlet_width_m,
                error.inlet_net_pressure_Pa, d.growth_steps, d.largest_jump_joints, d.p_rms, max_mass);
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
