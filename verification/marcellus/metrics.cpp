// Metrics of the Marcellus case (seed 5.4, Figure 5.19): the open and invaded joints at
// the end of the run (harness/fracture_pattern.hpp), the open band's aspect and the
// widths of the open and invaded bands along the minimum stress (y), and a round-off
// twin's open set against its base run's. Thresholds and
// checks are in study.yaml. Writes joints_<variant>.csv for plot.py.

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "fracture_pattern.hpp"
#include "harness.hpp"

namespace hfdda::verification {
namespace {

void validate(const io::CaseConfig& c, const VariantSpec&) {
  if (!(c.far_field.sxx_Pa < c.far_field.syy_Pa) || c.far_field.sxy_Pa != 0.0)
    throw std::runtime_error("far_field: the maximum compression must be along x (sxx < syy < 0, sxy = 0): the "
                             "band widths are measured along y");
  if (c.fracture_sets.empty()) throw std::runtime_error("the case has no fracture_sets (no joint sets)");
}

Metrics variant_metrics(const VariantRun& r) {
  Metrics m;
  if (!r.built || !r.model) return m;
  const JointPattern jp = joint_pattern(*r.model);
  measure_pattern(jp, m);
  const double ratio = m.numbers["invaded_y_extent_m"] / m.numbers["open_y_extent_m"];
  m.numbers["invaded_over_open_width"] = ratio;
  m.json["invaded_over_open_width"] = finite_or_null(ratio);
  m.json["blocks"] = r.model->system->n_blocks();
  m.json["time_s"] = r.run.time_s;
  m.json["wall_s_per_step"] = r.run.steps > 0 ? r.run.wall_seconds / r.run.steps : std::numeric_limits<double>::quiet_NaN();
  m.files["joints_" + r.variant->name + ".csv"] = pattern_csv(jp);
  char line[160];
  std::snprintf(line, sizeof line, "open band %.0f x %.0f m, invaded band %.0f x %.0f m", m.numbers["open_x_extent_m"],
                m.numbers["open_y_extent_m"], m.numbers["invaded_x_extent_m"], m.numbers["invaded_y_extent_m"]);
  m.summary = line;
  return m;
}

/// A round-off twin (`compare_with`) against its base run: the length-weighted Jaccard
/// similarity of their open sets (the same mesh: joints compared by their end points).
void study_metrics(StudyOutcome& st) {
  for (VariantOutcome& o : st.variants) {
    const VariantSpec& v = o.variant();
    if (!v.has("compare_with")) continue;
    const VariantOutcome* base = st.find(v.text("compare_with"));
    double similarity = std::numeric_limits<double>::quiet_NaN();
    if (base && o.run.built && base->run.built)
      similarity = open_jaccard(open_joints_of(o.metrics, v.name), open_joints_of(base->metrics, base->variant().name));
    o.metrics.numbers["open_similarity"] = similarity;
    o.metrics.json["open_similarity"] = finite_or_null(similarity);
  }
}

}  // namespace

CaseDefinition case_definition() { return {validate, variant_metrics, study_metrics}; }

}  // namespace hfdda::verification
