#include "kgd_series.hpp"

#include <cmath>
#include <stdexcept>

#include "statistics.hpp"

namespace hfdda::verification {
namespace {

double relative_error(double value, double exact) { return (value - exact) / exact; }

}  // namespace

KgdInjection kgd_injection_of(const io::CaseConfig& c) {
  if (!c.fluid) throw std::runtime_error("case has no 'fluid' section (no flow network)");
  if (c.injections.size() != 1) throw std::runtime_error("case needs exactly one injection");
  KgdInjection p;
  const io::MaterialConfig& rock = c.materials.at(0);
  p.youngs_modulus_Pa = rock.youngs_modulus_Pa;
  p.poissons_ratio = rock.poissons_ratio;
  p.viscosity_Pa_s = c.fluid->viscosity_Pa_s;
  p.leak_off_coefficient_m_sqrt_s = c.fluid->leak_off_coefficient_m_sqrt_s;
  p.mass_rate_kg_s = c.injections[0].mass_rate_kg_s;
  p.total_rate_m2_s = p.mass_rate_kg_s / c.fluid->density_kg_m3;  // Q0, both wings, per metre
  p.start_time_s = c.injections[0].start_time_s;
  p.dt_s = c.time.dt_s;
  p.end_time_s = c.time.end_time_s;
  return p;
}

std::vector<KgdSample> kgd_samples(const simulation::RunRecord& record, const KgdInjection& injection,
                                   double sigma0_Pa, const KgdSolution& solution) {
  std::vector<KgdSample> samples;
  for (std::size_t row = 0; row < record.rows(); ++row) {
    auto value = [&](const std::string& name) { return record.value(row, name); };
    KgdSample s;
    s.time_s = value("time_s");
    s.t = s.time_s - injection.start_time_s;
    if (!(s.t > 0.0)) continue;  // the self-similar solutions start at t = 0+
    s.open_xmin_m = value("open_xmin_m");
    s.open_xmax_m = value("open_xmax_m");
    s.run.half_length_m = 0.5 * (s.open_xmax_m - s.open_xmin_m);
    s.run.inlet_width_m = value("injection_aperture_m");
    s.run.inlet_net_pressure_Pa = value("injection_pressure_Pa") - sigma0_Pa;
    s.mass_balance_error = value("mass_balance_error");
    s.coupling_iterations = value("flow_newton_iterations");
    s.step_wall_s = value("step_wall_s");
    s.mass_injected_kg = value("mass_injected_kg");
    s.mass_stored_kg = value("mass_stored_kg");
    s.mass_leaked_kg = value("mass_leaked_kg");
    s.exact = solution(s.t);
    samples.push_back(s);
  }
  return samples;
}

const KgdSample* kgd_end_sample(const std::vector<KgdSample>& samples, bool completed, double end_time_s) {
  if (samples.empty() || !completed) return nullptr;
  return std::abs(samples.back().time_s - end_time_s) <= 1e-6 * end_time_s ? &samples.back() : nullptr;
}

KgdValues kgd_errors(const KgdSample* s) {
  if (!s) return {};
  return {relative_error(s->run.half_length_m, s->exact.half_length_m),
          relative_error(s->run.inlet_width_m, s->exact.inlet_width_m),
          relative_error(s->run.inlet_net_pressure_Pa, s->exact.inlet_net_pressure_Pa)};
}

double kgd_max_mass_balance_error(const std::vector<KgdSample>& samples) {
  return max_abs_finite(samples, [](const KgdSample& s) { return s.mass_balance_error; });
}

nlohmann::json kgd_at_end_json(const KgdSample& s) {
  return {{"half_length_m", s.run.half_length_m},
          {"half_length_exact_m", s.exact.half_length_m},
          {"inlet_width_m", s.run.inlet_width_m},
          {"inlet_width_exact_m", s.exact.inlet_width_m},
          {"inlet_net_pressure_Pa", s.run.inlet_net_pressure_Pa},
          {"inlet_net_pressure_exact_Pa", s.exact.inlet_net_pressure_Pa}};
}

nlohmann::json kgd_errors_json(const KgdValues& e) {
  return {{"half_length", e.half_length_m}, {"inlet_width", e.inlet_width_m},
          {"inlet_net_pressure", e.inlet_net_pressure_Pa}};
}

std::string kgd_series_csv(const std::vector<KgdSample>& samples) {
  std::string text =
      "time_s,half_length_m,half_length_exact_m,open_xmin_m,open_xmax_m,inlet_width_m,inlet_width_exact_m,"
      "inlet_net_pressure_Pa,inlet_net_pressure_exact_Pa,mass_balance_error,coupling_iterations,step_wall_s\n";
  for (const KgdSample& s : samples) {
    for (double v : {s.time_s, s.run.half_length_m, s.exact.half_length_m, s.open_xmin_m, s.open_xmax_m,
                     s.run.inlet_width_m, s.exact.inlet_width_m, s.run.inlet_net_pressure_Pa,
                     s.exact.inlet_net_pressure_Pa, s.mass_balance_error, s.coupling_iterations})
      text += number(v) + ",";
    text += number(s.step_wall_s) + "\n";
  }
  return text;
}

std::string kgd_analytical_csv(const KgdInjection& injection, const KgdSolution& solution,
                               const KgdExtraCurves& extra) {
  std::string text = "time_s,half_length_m,inlet_width_m,inlet_net_pressure_Pa";
  for (const std::string& name : extra.names) text += ',' + name;
  text += "\n";
  const int n = 400;
  const double t_end = injection.end_time_s - injection.start_time_s;
  for (int i = 1; i <= n; ++i) {
    const double t = t_end * std::pow(double(i) / n, 2.0);  // denser at early times
    const KgdValues e = solution(t);
    text += number(t + injection.start_time_s) + "," + number(e.half_length_m) + "," + number(e.inlet_width_m) +
            "," + number(e.inlet_net_pressure_Pa);
    if (!extra.names.empty()) {
      const std::vector<double> more = extra.values(t);
      if (more.size() != extra.names.size())
        throw std::logic_error("kgd_analytical_csv: extra curves return " + std::to_string(more.size()) +
                               " values for " + std::to_string(extra.names.size()) + " names");
      for (double v : more) text += ',' + number(v);
    }
    text += "\n";
  }
  return text;
}

}  // namespace hfdda::verification
