// Metrics of the fracture-network cases (seed 5.3, Table 5.3, Figures 5.10-5.16): the
// open and invaded joints at the end of each run (harness/fracture_pattern.hpp), the band
// the open joints form, the share of the open length on natural fractures, and the
// comparisons between runs that the seed's findings are about (stress, viscosity,
// rate): the variants of one network share their mesh, so their joints are compared by
// their end points. Variants, thresholds and checks are in study.yaml. Writes joints_<variant>.csv
// and patterns.csv for plot.py.

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "fracture_pattern.hpp"
#include "harness.hpp"

namespace hfdda::verification {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void validate(const io::CaseConfig& c, const VariantSpec& v) {
  const double delta_MPa = (c.far_field.syy_Pa - c.far_field.sxx_Pa) / 1e6;  // compression negative
  if (std::abs(delta_MPa - v.number("delta_sigma_MPa")) > 1e-6 || c.far_field.sxy_Pa != 0.0)
    throw std::runtime_error("far_field gives dsigma = sigma_x - sigma_y = " + std::to_string(delta_MPa) +
                             " MPa, the variant says delta_sigma_MPa = " + v.text("delta_sigma_MPa") +
                             " (the maximum stress must be along x)");
  if (c.fracture_sets.empty()) throw std::runtime_error("the case has no fracture_sets (no natural network)");
}

Metrics variant_metrics(const VariantRun& r) {
  Metrics m;
  const VariantSpec& v = *r.variant;
  m.json["network"] = v.text("network");
  m.json["delta_sigma_MPa"] = v.number("delta_sigma_MPa");
  if (!r.built || !r.model) return m;
  const JointPattern jp = joint_pattern(*r.model);
  measure_pattern(jp, m);
  m.json["blocks"] = r.model->system->n_blocks();
  m.json["time_s"] = r.run.time_s;
  m.json["wall_s_per_step"] = r.run.steps > 0 ? r.run.wall_seconds / r.run.steps : kNaN;
  m.files["joints_" + v.name + ".csv"] = pattern_csv(jp);
  char line[160];
  std::snprintf(line, sizeof line, "open %.0f m (%.0f %% natural), band %.0f x %.0f m, invaded %.0f m",
                m.numbers["open_length_m"], 100.0 * m.numbers["open_natural_fraction"], m.numbers["open_x_extent_m"],
                m.numbers["open_y_extent_m"], m.numbers["invaded_length_m"]);
  m.summary = line;
  return m;
}

void study_metrics(StudyOutcome& st) {
  std::ostringstream table;
  table << "variant,network,delta_sigma_MPa,open_length_m,open_natural_fraction,open_x_extent_m,open_y_extent_m,"
           "invaded_length_m,invaded_closed_natural_m,wall_s\n";
  for (VariantOutcome& o : st.variants) {
    const VariantSpec& v = o.variant();
    auto number = [](const VariantOutcome& x, const char* name) {
      const auto it = x.metrics.numbers.find(name);
      return it == x.metrics.numbers.end() ? kNaN : it->second;
    };
    char row[512];
    std::snprintf(row, sizeof row, "%s,%s,%g,%g,%g,%g,%g,%g,%g,%g\n", v.name.c_str(), v.text("network").c_str(),
                  v.number("delta_sigma_MPa"), number(o, "open_length_m"), number(o, "open_natural_fraction"),
                  number(o, "open_x_extent_m"), number(o, "open_y_extent_m"), number(o, "invaded_length_m"),
                  number(o, "invaded_closed_natural_m"), o.run.run.wall_seconds);
    table << row;
    // dsigma = 0 against dsigma = 12 MPa on the same network.
    if (v.has("stress_pair")) {
      const VariantOutcome* other = st.find(v.text("stress_pair"));
      o.metrics.numbers["natural_fraction_over_stressed"] =
          other ? number(o, "open_natural_fraction") - number(*other, "open_natural_fraction") : kNaN;
      o.metrics.json["natural_fraction_over_stressed"] = finite_or_null(o.metrics.numbers["natural_fraction_over_stressed"]);
    }
    // Viscosity and rate against the 20 mPa s, 1 kg/s run.
    if (v.has("compare_with")) {
      const VariantOutcome* other = st.find(v.text("compare_with"));
      double similarity = kNaN, closed_diff = kNaN;
      if (other && o.run.built && other->run.built) {
        similarity = open_jaccard(open_joints_of(o.metrics, v.name), open_joints_of(other->metrics, other->variant().name));
        closed_diff = number(o, "invaded_closed_natural_m") - number(*other, "invaded_closed_natural_m");
      }
      o.metrics.numbers["open_similarity"] = similarity;
      o.metrics.numbers["closed_invasion_over_reference_m"] = closed_diff;
      o.metrics.json["open_similarity"] = finite_or_null(similarity);
      o.metrics.json["closed_invasion_over_reference_m"] = finite_or_null(closed_diff);
    }
  }
  st.metrics.files["patterns.csv"] = table.str();
}

}  // namespace

CaseDefinition case_definition() { return {validate, variant_metrics, study_metrics}; }

}  // namespace hfdda::verification
