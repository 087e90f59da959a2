// Metrics of the Mode I LEFM study (seed 4.2, Figure 4.6): the far-field tension at
// which the crack fails completely (the load ramp's stop level: more than 75 % of the
// 48 m path broken), against
//   eq. 4.14 (singular near-tip field):  s_f = T0 sqrt(L / 2a)
//   exact Griffith field (erratum 6):    s_f = T0 sqrt(L / (2a + L))
// with the level of the first bond failure (the tip half of the first joint), of the
// first whole-joint failure, and the spread to complete failure. Variant attributes
// a_m, L_m, T0_Pa and increment_Pa state the parameters; validate() checks them against
// the case. Variants with the toughness criterion at crack tips
// (fracture.criterion: energy_release_rate, attribute K_IC_Pa_sqrt_m) are compared with
// the LEFM relation s_f = K_IC / sqrt(pi a) (K_I = s sqrt(pi a), Griffith crack), and the
// same K_IC on L = 0.5 and 1 m with each other (study metrics objectivity_a2/a3/a5), and
// on L = 0.25, 0.5 and 1 m (objectivity3_a2/a3/a5: largest over smallest failure stress
// minus 1). Variants with the attribute mesh_kind: delaunay run on a constrained Delaunay
// mesh (validate() checks it). Writes failure_stress.csv (one row per variant, with the
// mesh) for plot.py.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

#include "harness.hpp"

namespace hfdda::verification {
namespace {

constexpr double kPi = 3.14159265358979323846;

double exact_field_stress(double t0, double a, double l) { return t0 * std::sqrt(l / (2.0 * a + l)); }
double near_tip_stress(double t0, double a, double l) { return a > 0.0 ? t0 * std::sqrt(l / (2.0 * a)) : kNaN; }
/// LEFM, Griffith crack: K_I = s sqrt(pi a) reaches K_IC.
double lefm_stress(double k_ic, double a) { return a > 0.0 ? k_ic / std::sqrt(kPi * a) : kNaN; }
/// K_IC of the variant: its attribute with the toughness criterion, NaN with the strength rule.
double toughness_of(const VariantSpec& v) { return v.has("K_IC_Pa_sqrt_m") ? v.number("K_IC_Pa_sqrt_m") : kNaN; }

void validate(const io::CaseConfig& c, const VariantSpec& v) {
  if (!c.load_ramp) throw std::runtime_error("the case has no load_ramp");
  if (std::abs(c.joints.tensile_strength_Pa - v.number("T0_Pa")) > 1e-9 * v.number("T0_Pa"))
    throw std::runtime_error("joints.tensile_strength differs from the variant's T0_Pa");
  if (std::abs(*c.load_ramp->increment_Pa - v.number("increment_Pa")) > 1e-9 * v.number("increment_Pa"))
    throw std::runtime_error("load_ramp.increment differs from the variant's increment_Pa");
  double crack = 0.0;
  for (const auto& f : c.fractures)
    if (f.initially_open) crack = 0.5 * (f.to - f.from).norm();
  if (std::abs(crack - v.number("a_m")) > 1e-9) throw std::runtime_error("the open crack's half-length is not a_m");
  const bool delaunay = v.has("mesh_kind") && v.text("mesh_kind") == "delaunay";
  if (delaunay != (c.mesh.kind == io::MeshKind::delaunay))
    throw std::runtime_error("the variant's mesh_kind (delaunay or absent: structured) differs from mesh.type");
  const bool energy = c.fracture.criterion == io::FailureCriterionKind::energy_release_rate;
  if (energy != v.has("K_IC_Pa_sqrt_m"))
    throw std::runtime_error("a variant with K_IC_Pa_sqrt_m must use fracture.criterion: energy_release_rate, and only it");
  if (energy) {
    const double k = v.number("K_IC_Pa_sqrt_m");
    if (!c.fracture.fracture_toughness_Pa_sqrt_m || std::abs(*c.fracture.fracture_toughness_Pa_sqrt_m - k) > 1e-9 * k)
      throw std::runtime_error("fracture.fracture_toughness differs from the variant's K_IC_Pa_sqrt_m");
    if (c.fracture.mode2_toughness_Pa_sqrt_m) throw std::runtime_error("the study takes K_IIC = K_IC");
    // Seed eq. 4.13: the same rock under both criteria.
    if (std::abs(k / (v.number("T0_Pa") * std::sqrt(kPi * v.number("L_m") / 2.0)) - 1.0) > 1e-6)
      throw std::runtime_error("K_IC_Pa_sqrt_m is not T0 sqrt(pi L / 2) (seed eq. 4.13)");
  }
}

Metrics variant_metrics(const VariantRun& r) {
  Metrics m;
  const VariantSpec& v = *r.variant;
  const double a = v.number("a_m"), l = v.number("L_m"), t0 = v.number("T0_Pa"), inc = v.number("increment_Pa");
  const double exact = exact_field_stress(t0, a, l), near_tip = near_tip_stress(t0, a, l);
  const double k_ic = toughness_of(v), lefm = lefm_stress(k_ic, a);
  m.numbers["K_IC_Pa_sqrt_m"] = k_ic;
  m.numbers["lefm_Pa"] = lefm;
  m.numbers["exact_field_Pa"] = exact;
  m.numbers["near_tip_Pa"] = near_tip;
  m.numbers["a_at_least_2L"] = a >= 2.0 * l - 1e-12 ? 1.0 : 0.0;
  for (const char* k : {"failure_Pa", "first_failure_Pa", "first_joint_failure_Pa", "predicted_first_failure_Pa",
                        "error_exact_field", "abs_error_exact_field", "error_near_tip", "error_lefm", "abs_error_lefm", "spread_Pa",
                        "a0_error_increments", "stop_reached", "first_failure_at_jump", "levels_solved"})
    m.numbers[k] = kNaN;
  if (!r.model || !r.model->ramp) {
    m.summary = "not run";
    return m;
  }
  const simulation::LoadRampOutcome& o = r.model->ramp->outcome();
  const double failure = o.stop_reached ? o.stop_Pa : kNaN;
  m.numbers["failure_Pa"] = failure;
  m.numbers["first_failure_Pa"] = o.first_failure_Pa;
  m.numbers["first_joint_failure_Pa"] = o.first_joint_failure_Pa;
  m.numbers["predicted_first_failure_Pa"] = o.predicted_first_failure_Pa;
  m.numbers["error_exact_field"] = failure / exact - 1.0;
  m.numbers["abs_error_exact_field"] = std::abs(failure / exact - 1.0);
  m.numbers["error_near_tip"] = failure / near_tip - 1.0;
  m.numbers["error_lefm"] = failure / lefm - 1.0;
  m.numbers["abs_error_lefm"] = std::abs(failure / lefm - 1.0);
  m.numbers["spread_Pa"] = failure - o.first_joint_failure_Pa;
  m.numbers["a0_error_increments"] = std::abs(failure - t0) / inc;
  m.numbers["stop_reached"] = o.stop_reached ? 1.0 : 0.0;
  m.numbers["first_failure_at_jump"] = o.first_failure_at_jump ? 1.0 : 0.0;
  m.numbers["levels_solved"] = o.levels_solved;
  for (const auto& [k, value] : m.numbers) m.json[k] = finite_or_null(value);
  char line[200];
  std::snprintf(line, sizeof line, "s_f %.0f Pa (exact field %.0f, %+.2f %%), first bond %.0f, first joint %.0f Pa",
                failure, exact, 100.0 * (failure / exact - 1.0), o.first_failure_Pa, o.first_joint_failure_Pa);
  m.summary = line;
  if (std::isfinite(k_ic)) {
    std::snprintf(line, sizeof line, "; LEFM %.0f Pa (%+.2f %%)", lefm, 100.0 * (failure / lefm - 1.0));
    m.summary += line;
  }
  return m;
}

void study_metrics(StudyOutcome& s) {
  std::ostringstream csv;
  csv << "variant,a_m,L_m,T0_Pa,increment_Pa,failure_Pa,first_failure_Pa,first_joint_failure_Pa,"
         "exact_field_Pa,near_tip_Pa,K_IC_Pa_sqrt_m,lefm_Pa,wall_s,mesh\n";
  csv.precision(10);
  for (const VariantOutcome& v : s.variants) {
    const auto& n = v.metrics.numbers;
    csv << v.variant().name << ',' << v.variant().number("a_m") << ',' << v.variant().number("L_m") << ','
        << v.variant().number("T0_Pa") << ',' << v.variant().number("increment_Pa") << ',' << n.at("failure_Pa")
        << ',' << n.at("first_failure_Pa") << ',' << n.at("first_joint_failure_Pa") << ',' << n.at("exact_field_Pa")
        << ',' << n.at("near_tip_Pa") << ',' << n.at("K_IC_Pa_sqrt_m") << ',' << n.at("lefm_Pa") << ','
        << v.run.run.wall_seconds << ','
        << (v.variant().has("mesh_kind") ? v.variant().text("mesh_kind") : std::string("structured")) << '\n';
  }
  s.metrics.files["failure_stress.csv"] = csv.str();
  // Mesh objectivity of the toughness criterion: K_IC = 0.886 MPa m^0.5 on L = 1 m
  // (T0 = 0.707 MPa) against L = 0.5 m (T0 = 1 MPa) at the same a.
  for (const int a : {2, 3, 5}) {
    const std::string key = "objectivity_a" + std::to_string(a);
    const VariantOutcome* fine = s.find("e_a" + std::to_string(a) + "_L05_K089");
    const VariantOutcome* coarse = s.find("e_a" + std::to_string(a) + "_L10_K089");
    const double ratio = fine && coarse ? coarse->metrics.numbers.at("failure_Pa") / fine->metrics.numbers.at("failure_Pa") : kNaN;
    s.metrics.numbers[key] = std::abs(ratio - 1.0);
    s.metrics.json[key] = finite_or_null(std::abs(ratio - 1.0));
    s.metrics.json["objectivity_ratio_a" + std::to_string(a)] = finite_or_null(ratio);
    // The same K_IC on L = 0.25, 0.5 and 1 m: largest over smallest failure stress.
    const std::string key3 = "objectivity3_a" + std::to_string(a);
    const VariantOutcome* finest = s.find("e_a" + std::to_string(a) + "_L025_K089");
    double spread = kNaN;
    if (finest && fine && coarse) {
      const double f1 = finest->metrics.numbers.at("failure_Pa"), f2 = fine->metrics.numbers.at("failure_Pa"),
                   f3 = coarse->metrics.numbers.at("failure_Pa");
      spread = std::max({f1, f2, f3}) / std::min({f1, f2, f3}) - 1.0;  // NaN if any is NaN
      if (!std::isfinite(f1) || !std::isfinite(f2) || !std::isfinite(f3)) spread = kNaN;
    }
    s.metrics.numbers[key3] = spread;
    s.metrics.json[key3] = finite_or_null(spread);
  }
}

}  // namespace

CaseDefinition case_definition() { return {validate, variant_metrics, study_metrics}; }

}  // namespace hfdda::verification
