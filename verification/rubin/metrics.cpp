// Metrics of Rubin's experiment (seed 3.3, Table 3.2, Figures 3.8-3.9): the run's
// wellbore pressure, half-length, aperture at the LVDT (x = 28.5 mm) and pressures at
// x = 15 mm and 41 mm against Rubin's measurements (reference_data/rubin1983_experiment.csv),
// and the peer simulator's results (reference_data/geos_rubin_model_results.csv) scored
// by the same code. Variants, thresholds and checks are in study.yaml.
//
// Error of a series: mean over the measured points with t > t_min (10 s; 28 s at
// x = 41 mm) of |model(t) - measured| / |measured|, model(t) interpolated linearly
// between its own samples (our steps; the peer's rows with 3.7 s added to its clock).
// A measured time outside the model's samples gives no value (NaN: the check fails).
//
// Files for plot.py: series_<variant>.csv (ours), experiment.csv, peer.csv (SI units).

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness.hpp"
#include "rubin_series.hpp"

namespace hfdda::verification {
namespace {

using rubin::interpolate;
using rubin::kQuantities;
using rubin::mean_relative_error;
using rubin::Series;

/// Our five series from a run's record, in kQuantities order.
std::vector<Series> model_series(const simulation::RunRecord& r) {
  std::vector<Series> out(5);
  const std::vector<double> t = r.series("time_s");
  const std::vector<double> xmin = r.series("fracture_xmin_m"), xmax = r.series("fracture_xmax_m");
  const std::vector<double> p_well = r.series("probe_wellbore_pressure_Pa");
  const std::vector<double> w_lvdt = r.series("probe_lvdt_aperture_m");
  const std::vector<double> p15 = r.series("probe_gauge_b_pressure_Pa");
  const std::vector<double> p41 = r.series("probe_gauge_d_pressure_Pa");
  for (auto& s : out) s.t = t;
  out[0].v = p_well;
  for (std::size_t i = 0; i < t.size(); ++i) out[1].v.push_back(0.5 * (xmax[i] - xmin[i]));  // (-X1 + X2) / 2, Fig. 3.9 D
  out[2].v = w_lvdt;
  out[3].v = p15;
  out[4].v = p41;
  return out;
}

std::string series_csv(const simulation::RunRecord& r) {
  std::string text =
      "time_s,wellbore_pressure_Pa,half_length_m,aperture_28p5mm_m,pressure_15mm_Pa,pressure_41mm_Pa,"
      "pressure_minus15mm_Pa,mass_balance_error\n";
  const std::vector<Series> s = model_series(r);
  const std::vector<double> pa = r.series("probe_gauge_a_pressure_Pa"), mb = r.series("mass_balance_error");
  char line[320];
  for (std::size_t i = 0; i < s[0].t.size(); ++i) {
    std::snprintf(line, sizeof line, "%.6g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.3g\n", s[0].t[i], s[0].v[i], s[1].v[i],
                  s[2].v[i], s[3].v[i], s[4].v[i], pa[i], mb[i]);
    text += line;
  }
  return text;
}

Metrics variant_metrics(const VariantRun& r) {
  Metrics m;
  if (!r.built || r.record().rows() == 0) return m;
  const simulation::RunRecord& rec = r.record();
  const io::CaseConfig& c = *r.config;
  const double rate = c.injections.at(0).mass_rate_kg_s, start = c.injections.at(0).start_time_s;
  double max_balance = 0.0, max_rate_error = 0.0, injected_before_start = 0.0, min_growth = 0.0;
  double last_half_length = 0.0;
  for (std::size_t row = 0; row < rec.rows(); ++row) {
    const double t = rec.value(row, "time_s"), injected = rec.value(row, "mass_injected_kg");
    max_balance = std::max(max_balance, rec.value(row, "mass_balance_error"));
    if (t <= start) injected_before_start = std::max(injected_before_start, injected);
    else max_rate_error = std::max(max_rate_error, std::abs(injected / (rate * (t - start)) - 1.0));
    const double l = 0.5 * (rec.value(row, "fracture_xmax_m") - rec.value(row, "fracture_xmin_m"));
    if (row > 0) min_growth = std::min(min_growth, l - last_half_length);
    last_half_length = l;
  }
  m.numbers["max_mass_balance_error"] = max_balance;
  m.numbers["injected_vs_rate_times_time_rel_max"] = max_rate_error;
  m.numbers["injected_before_start_kg"] = injected_before_start;
  m.numbers["half_length_end_m"] = last_half_length;
  m.numbers["half_length_largest_decrease_m"] = -min_growth;
  m.json["blocks"] = r.model ? r.model->system->n_blocks() : 0;
  m.json["youngs_modulus_Pa"] = c.materials.at(0).youngs_modulus_Pa;
  // The early geometry, against the experiment's 30 mm and 69 um at 11.9 s: at 10 s, before
  // any fluid enters, it is the notch fill's doing alone.
  const std::vector<Series> s = model_series(rec);
  m.numbers["half_length_at_10s_m"] = interpolate(s[1], 10.0);
  m.numbers["half_length_at_11p9s_m"] = interpolate(s[1], 11.9);
  // Growth once fluid enters (t = start): what injection did, not the notch fill. A run
  // whose injection starts with it (as_run.yaml) counts from its first step.
  const double half_length_at_start = start < s[1].t.front() ? s[1].v.front() : interpolate(s[1], start);
  m.numbers["half_length_growth_after_injection_m"] = last_half_length - half_length_at_start;
  m.numbers["aperture_28p5mm_at_11p9s_m"] = interpolate(s[2], 11.9);
  for (const auto& [name, value] : m.numbers) m.json[name] = finite_or_null(value);
  m.files["series_" + r.variant->name + ".csv"] = series_csv(rec);
  char line[160];
  std::snprintf(line, sizeof line, "half-length %.1f mm at 10 s, %.1f mm at 11.9 s, %.1f mm at end  mass %.2e",
                1e3 * m.numbers["half_length_at_10s_m"], 1e3 * m.numbers["half_length_at_11p9s_m"],
                1e3 * last_half_length, max_balance);
  m.summary = line;
  return m;
}

void study_metrics(StudyOutcome& s) {
  const std::string experiment_file = s.references.at("experiment");
  const std::string peer_file = s.references.at("peer");
  const rubin::Table experiment = rubin::read_table(experiment_file);
  const std::vector<Series> measured = rubin::measured_series(experiment_file);

  // The peer, scored by the same code: reported for comparison (its recomputation is a
  // unit test of this metric, verification/tests/test_rubin_metric.cpp, not a check).
  const std::vector<Series> peer_series = rubin::peer_series(peer_file);
  std::vector<double> peer_error(measured.size());
  for (std::size_t i = 0; i < measured.size(); ++i) {
    peer_error[i] = mean_relative_error(peer_series[i], measured[i], kQuantities[i].t_min_s);
    s.metrics.json["peer_error"][kQuantities[i].key] = finite_or_null(peer_error[i]);
  }

  for (VariantOutcome& v : s.variants) {
    if (!v.run.built || v.run.record().rows() == 0) continue;
    const std::vector<Series> ours = model_series(v.run.record());
    const double t_end = ours[0].t.back();
    for (std::size_t i = 0; i < measured.size(); ++i) {
      const double e = mean_relative_error(ours[i], measured[i], kQuantities[i].t_min_s);
      v.metrics.numbers[std::string("error_") + kQuantities[i].key] = e;
      v.metrics.json["error"][kQuantities[i].key] = finite_or_null(e);
      // Against the peer's error on the same series by the same measure (< 1: better).
      v.metrics.numbers[std::string("error_over_peer_") + kQuantities[i].key] = e / peer_error[i];
      v.metrics.json["error_over_peer"][kQuantities[i].key] = finite_or_null(e / peer_error[i]);
      // The same error over the measured points the run reached (the quick tier's 20 s).
      const double w = mean_relative_error(ours[i], measured[i], kQuantities[i].t_min_s, t_end);
      v.metrics.numbers[std::string("error_to_end_") + kQuantities[i].key] = w;
      v.metrics.json["error_to_end"][kQuantities[i].key] = finite_or_null(w);
    }
  }

  // For plot.py, in SI units.
  std::string text = "time_s,wellbore_pressure_Pa,half_length_m,aperture_28p5mm_m,pressure_15mm_Pa,pressure_41mm_Pa\n";
  for (const auto& row : experiment.rows) {
    text += row.at(0);
    for (std::size_t i = 0; i < measured.size(); ++i) {
      const std::size_t col = experiment.column(kQuantities[i].experiment, experiment_file);
      text += ",";
      if (col < row.size() && !row[col].empty()) text += number(std::stod(row[col]) * kQuantities[i].experiment_to_si);
    }
    text += "\n";
  }
  s.metrics.files["experiment.csv"] = text;
  text = "time_s,wellbore_pressure_Pa,half_length_m,aperture_28p5mm_m,pressure_15mm_Pa,pressure_41mm_Pa\n";
  for (std::size_t j = 0; j < peer_series[0].t.size(); ++j) {
    text += number(peer_series[0].t[j]);
    for (const Series& ps : peer_series) {
      text += ',';  // appended: `"," + std::string` trips a false -Wrestrict in GCC 12
      text += number(ps.v[j]);
    }
    text += "\n";
  }
  s.metrics.files["peer.csv"] = text;
}

void validate(const io::CaseConfig& c, const VariantSpec&) {
  if (!c.fluid || c.injections.size() != 1) throw std::runtime_error("the Rubin case needs a fluid and one injection");
  for (const char* probe : {"wellbore", "gauge_a", "gauge_b", "lvdt", "gauge_d"}) {
    bool found = false;
    for (const auto& p : c.probes) found = found || p.name == probe;
    if (!found) throw std::runtime_error(std::string("the Rubin case needs a probe named '") + probe + "'");
  }
}

}  // namespace

CaseDefinition case_definition() { return {validate, variant_metrics, study_metrics}; }

}  // namespace hfdda::verification
