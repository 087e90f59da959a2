// Metrics of the KGD viscosity-storage case (seed 3.2, Figures 3.4-3.6): half-length,
// inlet width and inlet net pressure of each run's record against the zero-toughness,
// zero-leak-off KGD solution (M-vertex, analytical/kgd.hpp) at every step and at the
// end time, and the mass ledger. Variants, thresholds and checks are in study.yaml.
// Writes series_<variant>.csv per variant and analytical.csv (the reference curves)
// for plot.py; the record reading and the CSV formats are shared with the toughness case
// (verification/harness/kgd_series.hpp).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "analytical/kgd.hpp"
#include "harness.hpp"
#include "kgd_series.hpp"
#include "mesh/mesh.hpp"
#include "statistics.hpp"

namespace hfdda::verification {
namespace {

/// A variant's injection (kgd_series.hpp) and its background stress.
struct Physics {
  KgdInjection injection;
  double sigma0_Pa = kNaN;  ///< background stress, compression positive
};

Physics physics_of(const io::CaseConfig& c) {
  Physics p;
  p.injection = kgd_injection_of(c);
  if (c.far_field.sxx_Pa != c.far_field.syy_Pa)
    throw std::runtime_error("KGD comparison needs an isotropic background stress (sxx == syy)");
  p.sigma0_Pa = 0.0 - c.far_field.syy_Pa;  // tension positive in the case file (0 - x: no -0)
  return p;
}

analytical::KgdViscositySolution m_vertex(const KgdInjection& p, double t) {
  return analytical::kgd_viscosity_storage(p.youngs_modulus_Pa, p.poissons_ratio, p.viscosity_Pa_s,
                                           p.total_rate_m2_s, t);
}

KgdSolution m_vertex_of(const KgdInjection& p) {
  return [p](double t) { return kgd_values(m_vertex(p, t)); };
}

Metrics variant_metrics(const VariantRun& r) {
  Physics physics;
  if (r.config) try {
      physics = physics_of(*r.config);
    } catch (const std::exception&) {
      // reported by validate as "case not built"
    }
  const KgdInjection& injection = physics.injection;
  Metrics out;
  nlohmann::json& m = out.json;
  int blocks = 0, path_joints = 0;
  Range path_length;
  if (r.model) {
    blocks = r.model->system->n_blocks();
    const mesh::Mesh& mesh = r.model->system->mesh();
    const auto path = mesh::joints_on_segment(mesh, Vec2(-24, 0), Vec2(24, 0), 1e-6);
    path_joints = static_cast<int>(path.size());
    for (int j : path)
      path_length.add((mesh.points[mesh.joints[j].point_q] - mesh.points[mesh.joints[j].point_p]).norm());
  }
  const std::vector<KgdSample> samples =
      r.built ? kgd_samples(r.record(), injection, physics.sigma0_Pa, m_vertex_of(injection))
              : std::vector<KgdSample>{};
  if (r.built) out.files["series_" + r.variant->name + ".csv"] = kgd_series_csv(samples);

  const KgdSample* end = kgd_end_sample(samples, r.completed, injection.end_time_s);
  const KgdValues error = kgd_errors(end);
  const double max_mass = kgd_max_mass_balance_error(samples);
  out.numbers = {{"end_time_s", injection.end_time_s},
                 {"max_mass_balance_error", max_mass},
                 {"abs_half_length_error", std::abs(error.half_length_m)},
                 {"abs_inlet_width_error", std::abs(error.inlet_width_m)},
                 {"abs_inlet_net_pressure_error", std::abs(error.inlet_net_pressure_Pa)}};

  m["dt_s"] = finite_or_null(injection.dt_s);
  m["sigma0_Pa"] = finite_or_null(physics.sigma0_Pa);
  m["blocks"] = blocks;
  m["path_joints"] = path_joints;
  m["path_joint_length_m"] = {finite_or_null(path_length.min), finite_or_null(path_length.max)};
  m["max_mass_balance_error"] = finite_or_null(max_mass);
  if (!samples.empty()) {
    // Independent of the solver's own mass_balance_error: the ledger from the mass
    // columns, in increments since the first step (the initially fluid-filled joints
    // hold some mass at t = 0), and the injected mass against rate x time.
    const KgdSample& first = samples.front();
    double iterations = 0.0, max_ledger = 0.0, max_rate = 0.0;
    for (const KgdSample& s : samples) {
      iterations += s.coupling_iterations;
      if (s.mass_injected_kg > 0.0) {
        const double residual = (s.mass_injected_kg - first.mass_injected_kg) -
                                (s.mass_stored_kg - first.mass_stored_kg) -
                                (s.mass_leaked_kg - first.mass_leaked_kg);
        max_ledger = std::max(max_ledger, std::abs(residual) / s.mass_injected_kg);
        max_rate = std::max(max_rate, std::abs(s.mass_injected_kg / (injection.mass_rate_kg_s * s.t) - 1.0));
      }
    }
    m["coupling_iterations_total"] = finite_or_null(iterations);
    m["coupling_iterations_per_step"] = finite_or_null(iterations / double(samples.size()));
    m["ledger_increments_rel_max"] = max_ledger;
    m["injected_vs_rate_times_time_rel_max"] = max_rate;
  }
  if (end) {
    m["at_end"] = kgd_at_end_json(*end);
    m["error_at_end"] = kgd_errors_json(error);
  }
  char line[160];
  std::snprintf(line, sizeof line, "blocks %5d  path joints %3d  l %+.4f  w0 %+.4f  p0 %+.4f  mass %.2e", blocks,
                path_joints, error.half_length_m, error.inlet_width_m, error.inlet_net_pressure_Pa, max_mass);
  out.summary = line;
  return out;
}

void study_metrics(StudyOutcome& s) {
  for (const VariantOutcome& v : s.variants) {
    if (!v.run.built) continue;
    // The reference solution at the end time, both published forms, and its curves.
    const KgdInjection p = physics_of(*v.run.config).injection;
    const auto e = m_vertex(p, p.end_time_s - p.start_time_s);
    auto& a = s.metrics.json["m_vertex_at_end"];
    a["Q0_m2_s"] = p.total_rate_m2_s;
    a["half_length_m"] = e.half_length_m;
    a["inlet_width_m"] = e.inlet_width_m;
    a["inlet_net_pressure_Pa"] = e.inlet_net_pressure_Pa;
    a["inlet_width_seed_form_m"] = e.inlet_width_seed_form_m;
    a["inlet_net_pressure_seed_form_Pa"] = e.inlet_net_pressure_seed_form_Pa;
    const KgdExtraCurves seed_forms{{"inlet_width_seed_form_m", "inlet_net_pressure_seed_form_Pa"}, [p](double t) {
                                      const auto x = m_vertex(p, t);
                                      return std::vector<double>{x.inlet_width_seed_form_m,
                                                                 x.inlet_net_pressure_seed_form_Pa};
                                    }};
    s.metrics.files["analytical.csv"] = kgd_analytical_csv(p, m_vertex_of(p), seed_forms);
    break;
  }
}

}  // namespace

CaseDefinition case_definition() {
  return {[](const io::CaseConfig& c, const VariantSpec&) { physics_of(c); }, variant_metrics, study_metrics};
}

}  // namespace hfdda::verification
