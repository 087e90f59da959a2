// Metrics of the KGD viscosity-storage case (seed 3.2, Figures 3.4-3.6): half-length,
// inlet width and inlet net pressure of each run's record against the zero-toughness,
// zero-leak-off KGD solution (M-vertex, analytical/kgd.hpp) at every step and at the
// end time, and the mass ledger. Variants, thresholds and checks are in study.yaml.
// Writes series_<variant>.csv per variant and analytical.csv (the reference curves)
// for plot.py.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "analytical/kgd.hpp"
#include "harness.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::verification {
namespace {

/// Physical parameters of a variant, read from its case file.
struct Physics {
  double youngs_modulus_Pa = kNaN, poissons_ratio = kNaN, viscosity_Pa_s = kNaN;
  double total_rate_m2_s = kNaN;   ///< Q0 = mass rate / fluid density (per metre of height)
  double mass_rate_kg_s = kNaN;
  double start_time_s = 0.0;
  double sigma0_Pa = kNaN;         ///< background stress, compression positive
  double dt_s = kNaN, end_time_s = kNaN;
};

/// One row of the comparison with the M-vertex.
struct Sample {
  double t = kNaN;  // time since injection start
  double time_s = kNaN;
  double half_length = kNaN, width = kNaN, net_pressure = kNaN;
  double half_length_exact = kNaN, width_exact = kNaN, net_pressure_exact = kNaN;
  double mass_balance_error = kNaN, coupling_iterations = kNaN, step_wall_s = kNaN;
  double mass_injected = kNaN, mass_stored = kNaN, mass_leaked = kNaN;
};

double relative_error(double value, double exact) { return (value - exact) / exact; }

Physics physics_of(const io::CaseConfig& c) {
  Physics p;
  if (!c.fluid) throw std::runtime_error("case has no 'fluid' section (no flow network)");
  if (c.injections.size() != 1) throw std::runtime_error("case needs exactly one injection");
  const io::MaterialConfig& rock = c.materials.at(0);
  p.youngs_modulus_Pa = rock.youngs_modulus_Pa;
  p.poissons_ratio = rock.poissons_ratio;
  p.viscosity_Pa_s = c.fluid->viscosity_Pa_s;
  p.mass_rate_kg_s = c.injections[0].mass_rate_kg_s;
  p.total_rate_m2_s = p.mass_rate_kg_s / c.fluid->density_kg_m3;  // Q0, both wings, per metre
  p.start_time_s = c.injections[0].start_time_s;
  if (c.far_field.sxx_Pa != c.far_field.syy_Pa)
    throw std::runtime_error("KGD comparison needs an isotropic background stress (sxx == syy)");
  p.sigma0_Pa = 0.0 - c.far_field.syy_Pa;  // tension positive in the case file (0 - x: no -0)
  p.dt_s = c.time.dt_s;
  p.end_time_s = c.time.end_time_s;
  return p;
}

analytical::KgdViscositySolution exact_at(const Physics& p, double t) {
  return analytical::kgd_viscosity_storage(p.youngs_modulus_Pa, p.poissons_ratio, p.viscosity_Pa_s,
                                           p.total_rate_m2_s, t);
}

/// The run's record as samples compared with the M-vertex (t > 0 only).
std::vector<Sample> samples_of(const simulation::RunRecord& record, const Physics& p) {
  std::vector<Sample> samples;
  for (std::size_t row = 0; row < record.rows(); ++row) {
    auto value = [&](const std::string& name) { return record.value(row, name); };
    Sample s;
    s.time_s = value("time_s");
    s.t = s.time_s - p.start_time_s;
    if (!(s.t > 0.0)) continue;  // the M-vertex starts at t = 0+
    s.half_length = 0.5 * (value("open_xmax_m") - value("open_xmin_m"));
    s.width = value("injection_aperture_m");
    s.net_pressure = value("injection_pressure_Pa") - p.sigma0_Pa;
    s.mass_balance_error = value("mass_balance_error");
    s.coupling_iterations = value("flow_newton_iterations");
    s.step_wall_s = value("step_wall_s");
    s.mass_injected = value("mass_injected_kg");
    s.mass_stored = value("mass_stored_kg");
    s.mass_leaked = value("mass_leaked_kg");
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
      "time_s,half_length_m,half_length_exact_m,inlet_width_m,inlet_width_exact_m,inlet_net_pressure_Pa,"
      "inlet_net_pressure_exact_Pa,mass_balance_error,coupling_iterations,step_wall_s\n";
  for (const Sample& s : samples) {
    for (double v : {s.time_s, s.half_length, s.half_length_exact, s.width, s.width_exact, s.net_pressure,
                     s.net_pressure_exact, s.mass_balance_error, s.coupling_iterations})
      text += number(v) + ",";
    text += number(s.step_wall_s) + "\n";
  }
  return text;
}

/// Reference curves for the plots, from the same function the checks use.
std::string analytical_csv(const Physics& p) {
  std::string text =
      "time_s,half_length_m,inlet_width_m,inlet_net_pressure_Pa,inlet_width_seed_form_m,"
      "inlet_net_pressure_seed_form_Pa\n";
  const int n = 400;
  const double t_end = p.end_time_s - p.start_time_s;
  for (int i = 1; i <= n; ++i) {
    const double t = t_end * std::pow(double(i) / n, 2.0);  // denser at early times
    const auto e = exact_at(p, t);
    text += number(t + p.start_time_s) + "," + number(e.half_length_m) + "," + number(e.inlet_width_m) + "," +
            number(e.inlet_net_pressure_Pa) + "," + number(e.inlet_width_seed_form_m) + "," +
            number(e.inlet_net_pressure_seed_form_Pa) + "\n";
  }
  return text;
}

Metrics variant_metrics(const VariantRun& r) {
  Physics physics;
  if (r.config) try {
      physics = physics_of(*r.config);
    } catch (const std::exception&) {
      // reported by validate as "case not built"
    }
  Metrics out;
  nlohmann::json& m = out.json;
  int blocks = 0, path_joints = 0;
  double path_min = kNaN, path_max = kNaN;
  if (r.model) {
    blocks = r.model->system->n_blocks();
    const mesh::Mesh& mesh = r.model->system->mesh();
    const auto path = mesh::joints_on_segment(mesh, Vec2(-24, 0), Vec2(24, 0), 1e-6);
    path_joints = static_cast<int>(path.size());
    for (int j : path) {
      const double length = (mesh.points[mesh.joints[j].point_q] - mesh.points[mesh.joints[j].point_p]).norm();
      path_min = std::isnan(path_min) ? length : std::min(path_min, length);
      path_max = std::isnan(path_max) ? length : std::max(path_max, length);
    }
  }
  const std::vector<Sample> samples = r.built ? samples_of(r.record(), physics) : std::vector<Sample>{};
  if (r.built) out.files["series_" + r.variant->name + ".csv"] = series_csv(samples);

  // At the end time: the last sample, if the run completed and reached it.
  const Sample* end = nullptr;
  if (!samples.empty() && r.completed &&
      std::abs(samples.back().time_s - physics.end_time_s) <= 1e-6 * physics.end_time_s)
    end = &samples.back();
  auto end_error = [&](double Sample::*value, double Sample::*exact) {
    return end ? relative_error(end->*value, end->*exact) : kNaN;
  };
  double max_mass = kNaN;
  if (r.built && !samples.empty()) {
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
  out.numbers = {{"end_time_s", physics.end_time_s},
                 {"max_mass_balance_error", max_mass},
                 {"abs_half_length_error", std::abs(e_l)},
                 {"abs_inlet_width_error", std::abs(e_w)},
                 {"abs_inlet_net_pressure_error", std::abs(e_p)}};

  m["dt_s"] = finite_or_null(physics.dt_s);
  m["sigma0_Pa"] = finite_or_null(physics.sigma0_Pa);
  m["blocks"] = blocks;
  m["path_joints"] = path_joints;
  m["path_joint_length_m"] = {finite_or_null(path_min), finite_or_null(path_max)};
  m["max_mass_balance_error"] = finite_or_null(max_mass);
  if (!samples.empty()) {
    // Independent of the solver's own mass_balance_error: the ledger from the mass
    // columns, in increments since the first step (the initially fluid-filled joints
    // hold some mass at t = 0), and the injected mass against rate x time.
    const Sample& first = samples.front();
    double iterations = 0.0, max_ledger = 0.0, max_rate = 0.0;
    for (const Sample& s : samples) {
      iterations += s.coupling_iterations;
      if (s.mass_injected > 0.0) {
        const double residual = (s.mass_injected - first.mass_injected) - (s.mass_stored - first.mass_stored) -
                                (s.mass_leaked - first.mass_leaked);
        max_ledger = std::max(max_ledger, std::abs(residual) / s.mass_injected);
        max_rate = std::max(max_rate, std::abs(s.mass_injected / (physics.mass_rate_kg_s * s.t) - 1.0));
      }
    }
    m["coupling_iterations_total"] = finite_or_null(iterations);
    m["coupling_iterations_per_step"] = finite_or_null(iterations / double(samples.size()));
    m["ledger_increments_rel_max"] = max_ledger;
    m["injected_vs_rate_times_time_rel_max"] = max_rate;
  }
  if (end) {
    m["at_end"] = {{"half_length_m", end->half_length},   {"half_length_exact_m", end->half_length_exact},
                   {"inlet_width_m", end->width},         {"inlet_width_exact_m", end->width_exact},
                   {"inlet_net_pressure_Pa", end->net_pressure},
                   {"inlet_net_pressure_exact_Pa", end->net_pressure_exact}};
    m["error_at_end"] = {{"half_length", e_l}, {"inlet_width", e_w}, {"inlet_net_pressure", e_p}};
  }
  char line[160];
  std::snprintf(line, sizeof line, "blocks %5d  path joints %3d  l %+.4f  w0 %+.4f  p0 %+.4f  mass %.2e", blocks,
                path_joints, e_l, e_w, e_p, max_mass);
  out.summary = line;
  return out;
}

void study_metrics(StudyOutcome& s) {
  for (const VariantOutcome& v : s.variants) {
    if (!v.run.built) continue;
    // The reference solution at the end time, both published forms, and its curves.
    const Physics p = physics_of(*v.run.config);
    const auto e = exact_at(p, p.end_time_s - p.start_time_s);
    auto& a = s.metrics.json["m_vertex_at_end"];
    a["Q0_m2_s"] = p.total_rate_m2_s;
    a["half_length_m"] = e.half_length_m;
    a["inlet_width_m"] = e.inlet_width_m;
    a["inlet_net_pressure_Pa"] = e.inlet_net_pressure_Pa;
    a["inlet_width_seed_form_m"] = e.inlet_width_seed_form_m;
    a["inlet_net_pressure_seed_form_Pa"] = e.inlet_net_pressure_seed_form_Pa;
    s.metrics.files["analytical.csv"] = analytical_csv(p);
    break;
  }
}

}  // namespace

CaseDefinition case_definition() {
  return {[](const io::CaseConfig& c, const VariantSpec&) { physics_of(c); }, variant_metrics, study_metrics};
}

}  // namespace hfdda::verification
