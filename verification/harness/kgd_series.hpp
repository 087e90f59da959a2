#pragma once
// What the KGD-type cases share: a single fracture driven from one injection point,
// compared at every step with a self-similar solution for the half-length l, the inlet
// width w0 and the inlet net pressure p0 (seed 3.2, M-vertex, Figures 3.4-3.6; seed 4.5,
// K-vertex, Figures 4.11-4.14; solutions in solver/analytical/kgd.hpp). Reads the
// injection set-up from the case file and the three quantities from the run record,
// pairs them with the solution, picks the sample at the end time, and writes the CSV
// files that plot.py (verification/harness/kgd_plots.py) draws:
//   series_<variant>.csv   one row per step: measured and exact l, w0, p0, the open
//                          extent along x, the mass balance error, effort
//   analytical*.csv        the solution on a time grid denser at early times
// The case keeps its own checks of the set-up, its solution and its result.json keys.

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness.hpp"

namespace hfdda::verification {

/// The injection as a KGD solution needs it, from a case file with a fluid and exactly
/// one injection (throws std::runtime_error otherwise). Rates per metre of height.
struct KgdInjection {
  double youngs_modulus_Pa = kNaN, poissons_ratio = kNaN;  ///< of materials[0]
  double viscosity_Pa_s = kNaN, leak_off_coefficient_m_sqrt_s = kNaN;
  double mass_rate_kg_s = kNaN;
  double total_rate_m2_s = kNaN;  ///< Q0 = mass rate / fluid density, both wings
  double start_time_s = 0.0;      ///< injection start: t = 0 of the solution
  double dt_s = kNaN, end_time_s = kNaN;
};
KgdInjection kgd_injection_of(const io::CaseConfig& c);

/// l, w0, p0 of the solution, or of a run.
struct KgdValues {
  double half_length_m = kNaN, inlet_width_m = kNaN, inlet_net_pressure_Pa = kNaN;
};
/// The solution at time t since the injection start [s].
using KgdSolution = std::function<KgdValues(double t)>;

/// The three quantities of any solution struct that names them as analytical/kgd.hpp does.
template <class Solution>
KgdValues kgd_values(const Solution& s) {
  return {s.half_length_m, s.inlet_width_m, s.inlet_net_pressure_Pa};
}

/// One step of the run record next to the solution at the same time.
struct KgdSample {
  double time_s = kNaN;  ///< simulation time
  double t = kNaN;       ///< time since the injection start
  double open_xmin_m = kNaN, open_xmax_m = kNaN;
  KgdValues run, exact;  ///< run: l = (xmax - xmin) / 2, w0 and p0 at the injection point
  double mass_balance_error = kNaN, coupling_iterations = kNaN, step_wall_s = kNaN;
  double mass_injected_kg = kNaN, mass_stored_kg = kNaN, mass_leaked_kg = kNaN;
};

/// The record's rows with t > 0 (the solutions start at t = 0+). p0 is the injection
/// pressure minus `sigma0_Pa`, the background stress (compression positive).
std::vector<KgdSample> kgd_samples(const simulation::RunRecord& record, const KgdInjection& injection,
                                   double sigma0_Pa, const KgdSolution& solution);

/// The last sample if the run completed and it lies at the end time (to 1e-6 relative), else null.
const KgdSample* kgd_end_sample(const std::vector<KgdSample>& samples, bool completed, double end_time_s);

/// Relative errors (run - exact) / exact of l, w0, p0; all NaN without a sample.
KgdValues kgd_errors(const KgdSample* sample);

/// Largest |mass_balance_error| of the samples; NaN if none or any is not finite.
double kgd_max_mass_balance_error(const std::vector<KgdSample>& samples);

/// result.json "at_end": run and exact l, w0, p0 of a sample.
nlohmann::json kgd_at_end_json(const KgdSample& sample);
/// result.json "error_at_end": relative errors of l, w0, p0.
nlohmann::json kgd_errors_json(const KgdValues& errors);

/// series_<variant>.csv: time_s, half_length_m, half_length_exact_m, open_xmin_m,
/// open_xmax_m, inlet_width_m, inlet_width_exact_m, inlet_net_pressure_Pa,
/// inlet_net_pressure_exact_Pa, mass_balance_error, coupling_iterations, step_wall_s.
std::string kgd_series_csv(const std::vector<KgdSample>& samples);

/// Columns a case adds to its analytical CSV (e.g. the seed's own form of a formula).
struct KgdExtraCurves {
  std::vector<std::string> names;
  std::function<std::vector<double>(double t)> values;  ///< one value per name at time t since the start
};

/// The solution for plotting: time_s, half_length_m, inlet_width_m,
/// inlet_net_pressure_Pa and the extra columns, at 400 times up to the end time, denser
/// at early times (the solutions change fastest there).
std::string kgd_analytical_csv(const KgdInjection& injection, const KgdSolution& solution,
                               const KgdExtraCurves& extra = {});

}  // namespace hfdda::verification
