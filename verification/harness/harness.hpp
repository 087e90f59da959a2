#pragma once
// The verification harness: one runner for every case folder (verification/README.md).
//
//   verify_<case> --tier quick|full|ensemble --case-dir DIR --out RESULT_DIR
//
// reads DIR/study.yaml (variants, thresholds, checks, figures, notes, reference data),
// builds and runs each variant of the tier through the library (build_model + run),
// hands each finished run (model state and its RunRecord, in memory) to the case's
// metrics function, evaluates the declared checks and writes RESULT_DIR/result.json.
// A case folder provides study.yaml and metrics.cpp, which defines case_definition().

#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"
#include "simulation/run_record.hpp"

namespace hfdda::verification {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A number as result files and check names write it (%.10g).
std::string number(double v);

/// JSON null for a value that is not finite (NaN, inf), else the number.
nlohmann::json finite_or_null(double v);

/// One variant of study.yaml: `name`, `case` (file in the case folder), `label`,
/// `tiers`, `vtu` (tiers that write VTU files), and any other scalar keys as attributes.
struct VariantSpec {
  std::string name, case_file, label;
  /// `set:` of the variant, as YAML text: case-file keys that override the case file (the
  /// runner writes runs/<variant>/case.yaml, which `extends` it, and runs that file).
  std::string overrides_yaml;
  std::vector<std::string> tiers, vtu_tiers;
  std::map<std::string, std::string> attributes;

  bool has(const std::string& key) const { return attributes.count(key) != 0; }
  /// The attribute as text; throws std::runtime_error naming the variant if it is missing.
  const std::string& text(const std::string& key) const;
  /// The attribute as a number or a boolean (true/false); throw if missing or not one.
  double number(const std::string& key) const;
  bool flag(const std::string& key) const;
};

/// A variant after its run: what the case's metrics function reads.
struct VariantRun {
  const VariantSpec* variant = nullptr;
  std::string tier;
  std::string out_dir;                        ///< the result directory
  std::optional<io::CaseConfig> config;       ///< the case file, if it could be read
  const simulation::Model* model = nullptr;   ///< the model after the run; null if not built
  simulation::RunResult run;                  ///< statistics and the RunRecord of the run
  bool built = false;                         ///< case read and model built
  bool completed = false;                     ///< run reached its end time
  std::string message;                        ///< why something failed ("" if nothing did)

  const simulation::RunRecord& record() const { return run.record; }
  void note(const std::string& text) { message += (message.empty() ? "" : "; ") + text; }
};

/// What a case computes from a run (or, in study_metrics, from all runs).
struct Metrics {
  std::map<std::string, double> numbers;            ///< named numbers the checks refer to
  nlohmann::json json = nlohmann::json::object();   ///< merged into result.json "metrics"
  std::map<std::string, std::string> files;         ///< file in the result directory -> text (plots)
  std::string summary;                              ///< one line for the log
  /// Study level only: tables for the report (result.json "tables": title, header, rows
  /// of text), e.g. a case's outcomes beside the experiment's and the seed's.
  nlohmann::json tables = nlohmann::json::array();
};

struct VariantOutcome {
  VariantRun run;
  Metrics metrics;
  const VariantSpec& variant() const { return *run.variant; }
};

/// Every run of the tier, in study order, with the study-level metrics.
struct StudyOutcome {
  std::string tier;
  std::vector<VariantOutcome> variants;
  Metrics metrics;  ///< numbers for `scope: study` checks; json merged at the top of "metrics"
  std::map<std::string, std::string> references;  ///< study.yaml `reference:` name -> absolute path

  const VariantOutcome* find(const std::string& name) const;
  VariantOutcome* find(const std::string& name);
};

/// What a case folder's metrics.cpp provides.
struct CaseDefinition {
  /// Optional: rejects an unsuitable case file before the model is built (throw; the
  /// variant is reported as "case not built" and its checks fail).
  std::function<void(const io::CaseConfig&, const VariantSpec&)> validate;
  /// Required: metrics of one variant, called for every variant of the tier, built or
  /// not (VariantRun::model is null when the model could not be built).
  std::function<Metrics(const VariantRun&)> metrics;
  /// Optional: numbers that compare variants (added to a variant's or the study's
  /// Metrics), study-level JSON and files.
  std::function<void(StudyOutcome&)> study_metrics;
  /// Optional: runs a variant in place of build_model + run (an ensemble of realisations,
  /// verification/ensembles): given the case file to run and the run directory (created
  /// empty), it sets VariantRun::completed and notes what failed. VariantRun::model stays
  /// null; the metrics read what the run wrote.
  std::function<void(VariantRun&, const std::string& case_path, const std::string& run_dir)> run{};
  /// Whether its variants may run side by side (HFDDA_VERIFY_JOBS > 1). False where a
  /// variant uses the cores itself (MPI ranks) or measures its own speed-up.
  bool variants_share_cores = true;
};

/// Defined by the case folder's metrics.cpp.
CaseDefinition case_definition();

/// The runner: command line, study.yaml, runs, checks, result.json. Exit code: 0 when
/// every gating check matches its expectation, 1 otherwise, 2 on a usage or study error.
int run_harness(int argc, char** argv, const CaseDefinition& definition);

}  // namespace hfdda::verification
