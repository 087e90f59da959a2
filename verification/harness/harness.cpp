#include "harness.hpp"

#include "core/memory_policy.hpp"
#include "dda/thread_policy.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "io/output.hpp"
#include "variant_pool.hpp"

#ifndef HFDDA_REFERENCE_DATA_DIR
#error "HFDDA_REFERENCE_DATA_DIR must point at the repository's reference_data/ (set by verification/CMakeLists.txt)"
#endif

namespace hfdda::verification {

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.10g", v);
  return buffer;
}

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

const std::string& VariantSpec::text(const std::string& key) const {
  const auto it = attributes.find(key);
  if (it == attributes.end()) throw std::runtime_error("variant '" + name + "' has no attribute '" + key + "'");
  return it->second;
}

double VariantSpec::number(const std::string& key) const {
  const std::string& t = text(key);
  if (t == "true") return 1.0;
  if (t == "false") return 0.0;
  std::size_t used = 0;
  double v = kNaN;
  try {
    v = std::stod(t, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != t.size())
    throw std::runtime_error("variant '" + name + "': attribute '" + key + "' = '" + t + "' is not a number");
  return v;
}

bool VariantSpec::flag(const std::string& key) const { return number(key) != 0.0; }

const VariantOutcome* StudyOutcome::find(const std::string& name) const {
  for (const VariantOutcome& v : variants)
    if (v.variant().name == name) return &v;
  return nullptr;
}

VariantOutcome* StudyOutcome::find(const std::string& name) {
  for (VariantOutcome& v : variants)
    if (v.variant().name == name) return &v;
  return nullptr;
}

namespace {

namespace fs = std::filesystem;

// ----------------------------------------------------------------------- study.yaml

struct Threshold {
  nlohmann::json value;  ///< a number, or [lo, hi]
  std::string reason;
};

struct Study {
  std::string file;
  std::string case_name, title, seed_section, notes;
  std::map<std::string, std::vector<std::string>> figures;  ///< tier -> files
  std::vector<std::string> metric_fields;                    ///< written for every variant
  std::vector<VariantSpec> variants;
  std::map<std::string, Threshold> thresholds;
  std::map<std::string, std::string> references;             ///< name -> absolute path
  /// Groups of checks; each group is expanded variant by variant (or once, scope: study).
  std::vector<std::vector<YAML::Node>> groups;
};

[[noreturn]] void study_error(const Study& s, const YAML::Node& node, const std::string& what) {
  const auto mark = node.Mark();
  throw std::runtime_error(s.file + (mark.line >= 0 ? ":" + std::to_string(mark.line + 1) : "") + ": " + what);
}

std::vector<std::string> strings(const YAML::Node& node) {
  std::vector<std::string> out;
  if (!node) return out;
  if (node.IsScalar()) return {node.as<std::string>()};
  for (const auto& item : node) out.push_back(item.as<std::string>());
  return out;
}

std::optional<double> as_number(const YAML::Node& node) {
  if (!node || !node.IsScalar()) return std::nullopt;
  try {
    return node.as<double>();
  } catch (const YAML::BadConversion&) {
    return std::nullopt;
  }
}

nlohmann::json threshold_value(const Study& s, const YAML::Node& node) {
  if (node.IsSequence() && node.size() == 2) {
    const auto lo = as_number(node[0]), hi = as_number(node[1]);
    if (lo && hi) return nlohmann::json{*lo, *hi};
  }
  if (const auto v = as_number(node)) return *v;
  study_error(s, node, "a threshold value is a number or [lo, hi]");
}

Study load_study(const std::string& path) {
  Study s;
  s.file = path;
  const YAML::Node root = YAML::LoadFile(path);
  auto required = [&](const YAML::Node& n, const char* key) {
    if (!n[key]) study_error(s, n, std::string("missing key '") + key + "'");
    return n[key];
  };
  s.case_name = required(root, "case").as<std::string>();
  s.title = required(root, "title").as<std::string>();
  s.seed_section = required(root, "seed_section").as<std::string>();
  s.notes = root["notes"] ? root["notes"].as<std::string>() : "";
  if (const YAML::Node f = root["figures"])
    for (const auto& tier : f) s.figures[tier.first.as<std::string>()] = strings(tier.second);
  s.metric_fields = strings(root["variant_metrics"]);
  const std::vector<std::string> default_vtu = strings(root["vtu"]);
  for (const auto& v : required(root, "variants")) {
    VariantSpec spec;
    spec.name = required(v, "name").as<std::string>();
    spec.case_file = required(v, "case").as<std::string>();
    spec.label = required(v, "label").as<std::string>();
    spec.tiers = v["tiers"] ? strings(v["tiers"]) : std::vector<std::string>{"quick", "full"};
    spec.vtu_tiers = v["vtu"] ? strings(v["vtu"]) : default_vtu;
    for (const auto& kv : v) {
      const std::string key = kv.first.as<std::string>();
      if (key == "name" || key == "case" || key == "label" || key == "tiers" || key == "vtu") continue;
      if (key == "set") {
        if (!kv.second.IsMap()) study_error(s, kv.second, "variant key 'set' must be a map of case-file keys");
        YAML::Emitter text;
        text << YAML::BeginMap;
        for (const auto& entry : kv.second) text << YAML::Key << entry.first << YAML::Value << entry.second;
        text << YAML::EndMap;
        spec.overrides_yaml = std::string(text.c_str()) + "\n";
        continue;
      }
      if (!kv.second.IsScalar()) study_error(s, kv.second, "variant attribute '" + key + "' must be a scalar");
      spec.attributes[key] = kv.second.as<std::string>();
    }
    for (const VariantSpec& other : s.variants)
      if (other.name == spec.name) study_error(s, v, "variant '" + spec.name + "' appears twice");
    s.variants.push_back(std::move(spec));
  }
  if (const YAML::Node t = root["thresholds"])
    for (const auto& kv : t) {
      const std::string key = kv.first.as<std::string>();
      s.thresholds[key] = {threshold_value(s, required(kv.second, "value")),
                           kv.second["reason"] ? kv.second["reason"].as<std::string>() : ""};
      if (s.thresholds[key].reason.empty()) study_error(s, kv.second, "threshold '" + key + "' needs a reason");
    }
  if (const YAML::Node refs = root["reference"])
    for (const auto& r : refs) {
      const std::string name = required(r, "name").as<std::string>();
      const fs::path file = fs::path(HFDDA_REFERENCE_DATA_DIR) / required(r, "file").as<std::string>();
      if (!fs::exists(file)) study_error(s, r, "reference '" + name + "': no file " + file.string());
      s.references[name] = file.string();
    }
  for (const auto& entry : required(root, "checks")) {
    if (entry["for_each_variant"]) {
      std::vector<YAML::Node> group;
      for (const auto& c : entry["for_each_variant"]) group.push_back(c);
      s.groups.push_back(group);
    } else {
      s.groups.push_back({entry});
    }
  }
  return s;
}

// ----------------------------------------------------------------------- checks

/// One comparison of a measured value with its threshold. A value that is not finite
/// (a run that did not produce it) never passes, and never counts as an expected
/// failure either: a crash, a NaN or a missing output is a failed check whatever was
/// expected.
struct Check {
  std::string name;
  double value;
  nlohmann::json threshold;  // a number, or [lo, hi] for "in"
  std::string comparison;    // "<=", "<", ">=", ">", "==" or "in"
  std::string expected;      // "pass" or "fail" (a known, documented failure)
  std::string note;
  bool gating;
  /// The run the value comes from reached its end time (true for a study-level check,
  /// whose variants have completion checks of their own).
  bool run_completed = true;
  /// An expected failure that is a stop: the run stopped with this error (the check's
  /// `expected_stop`, found in the variant's message).
  bool stopped_as_expected = false;

  bool passed() const {
    if (!std::isfinite(value)) return false;
    if (comparison == "in") return value >= threshold[0].get<double>() && value <= threshold[1].get<double>();
    const double t = threshold.get<double>();
    if (comparison == "<=") return value <= t;
    if (comparison == "<") return value < t;
    if (comparison == ">=") return value >= t;
    if (comparison == ">") return value > t;
    return value == t;  // "=="
  }
  /// Whether the outcome is the expected one. An expected failure is either a
  /// completed run whose finite value misses the threshold, or a stop with the named
  /// error; nothing else.
  bool matches() const {
    if (expected == "pass") return passed();
    if (stopped_as_expected) return true;
    return run_completed && std::isfinite(value) && !passed();
  }
};

bool listed(const YAML::Node& node, const std::string& value) {
  if (!node) return true;
  const auto items = strings(node);
  return std::find(items.begin(), items.end(), value) != items.end() ||
         std::find(items.begin(), items.end(), "all") != items.end();
}

/// `{key}` in a check's name or note: name, label, message, a variant attribute, or a
/// number of the variant's (else the study's) metrics, written with %.10g.
std::string expand(const Study& s, const std::string& text, const VariantOutcome* v, const StudyOutcome& study) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '{') {
      out += text[i];
      continue;
    }
    const std::size_t end = text.find('}', i);
    if (end == std::string::npos) throw std::runtime_error(s.file + ": unclosed '{' in '" + text + "'");
    const std::string key = text.substr(i + 1, end - i - 1);
    i = end;
    if (v && key == "name") out += v->variant().name;
    else if (v && key == "label") out += v->variant().label;
    else if (v && key == "message") out += v->run.message;
    else if (v && v->variant().has(key)) out += v->variant().text(key);
    else if (v && v->metrics.numbers.count(key)) out += number(v->metrics.numbers.at(key));
    else if (study.metrics.numbers.count(key)) out += number(study.metrics.numbers.at(key));
    else if (v && !v->run.built) out += "nan";
    else throw std::runtime_error(s.file + ": unknown placeholder {" + key + "} in '" + text + "'");
  }
  return out;
}

std::string known_numbers(const Metrics& m) {
  std::string known;
  for (const auto& [k, value] : m.numbers) known += (known.empty() ? "" : ", ") + k;
  return known.empty() ? "(none)" : known;
}

/// The check as it applies to variant v: the first `by_variant` entry naming v (and the
/// tier) overrides its fields. Never assigns to a YAML::Node (yaml-cpp's assignment
/// rewrites the shared node, i.e. the study itself): copies and clones only.
YAML::Node effective_check(const Study& s, const YAML::Node& node, const VariantOutcome& v, const std::string& tier) {
  if (const YAML::Node overrides = node["by_variant"]) {
    for (const auto& o : overrides) {
      if (!o["variants"]) study_error(s, o, "a by_variant entry needs 'variants'");
      if (!listed(o["variants"], v.variant().name) || !listed(o["tiers"], tier)) continue;
      YAML::Node merged = YAML::Clone(node);
      for (const auto& kv : o) {
        const std::string key = kv.first.as<std::string>();
        if (key != "variants" && key != "tiers") merged[key] = YAML::Clone(kv.second);
      }
      return merged;
    }
  }
  return node;
}

/// The variant was built and its run stopped with an error whose message contains
/// `stop` (an expected_stop; never true for an empty one).
bool stopped_with(const VariantOutcome& v, const std::string& stop) {
  return !stop.empty() && v.run.built && !v.run.completed && v.run.message.find(stop) != std::string::npos;
}

/// The check `original` for one variant (v) or for the study (v null), or nothing if it
/// does not apply to this variant or tier.
std::optional<Check> make_check(const Study& s, const YAML::Node& original, const VariantOutcome* v,
                                const StudyOutcome& study) {
  if (!listed(original["tiers"], study.tier)) return std::nullopt;
  if (v) {
    if (!listed(original["variants"], v->variant().name)) return std::nullopt;
    if (original["if_built"] && original["if_built"].as<bool>() && !v->run.built) return std::nullopt;
  }
  const YAML::Node node = v ? effective_check(s, original, *v, study.tier) : original;
  for (const char* key : {"name", "metric", "comparison", "threshold"})
    if (!node[key]) study_error(s, node, std::string("check needs '") + key + "'");
  Check c;
  c.name = expand(s, node["name"].as<std::string>(), v, study);
  c.comparison = node["comparison"].as<std::string>();
  if (c.comparison != "<=" && c.comparison != "<" && c.comparison != ">=" && c.comparison != ">" &&
      c.comparison != "==" && c.comparison != "in")
    study_error(s, node["comparison"], "comparison must be one of <=, <, >=, >, ==, in");
  const YAML::Node t = node["threshold"];
  if (t.IsScalar() && !as_number(t)) {
    const auto it = s.thresholds.find(t.as<std::string>());
    if (it == s.thresholds.end()) study_error(s, t, "no threshold '" + t.as<std::string>() + "' in 'thresholds'");
    c.threshold = it->second.value;
  } else {
    c.threshold = threshold_value(s, t);
  }
  if ((c.comparison == "in") != c.threshold.is_array())
    study_error(s, t, "comparison 'in' takes [lo, hi]; the others a number");
  c.expected = node["expected"] ? node["expected"].as<std::string>() : "pass";
  if (c.expected != "pass" && c.expected != "fail") study_error(s, node["expected"], "expected is pass or fail");
  const std::string expected_stop = node["expected_stop"] ? node["expected_stop"].as<std::string>() : "";
  if (!expected_stop.empty() && c.expected != "fail")
    study_error(s, node["expected_stop"], "expected_stop names the error of an expected failure (expected: fail)");
  if (v) {
    c.run_completed = v->run.completed;
    c.stopped_as_expected = stopped_with(*v, expected_stop);
  }
  const std::string gating = node["gating"] ? node["gating"].as<std::string>() : "false";
  c.gating = gating == "true" || gating == study.tier;
  c.note = node["note"] ? expand(s, node["note"].as<std::string>(), v, study) : "";

  const std::string metric = node["metric"].as<std::string>();
  const Metrics& source = v ? v->metrics : study.metrics;
  if (v && metric == "completed") {
    c.value = v->run.completed ? 1.0 : 0.0;
  } else if (source.numbers.count(metric)) {
    c.value = source.numbers.at(metric);
  } else if (v && !v->run.built) {
    c.value = kNaN;
  } else {
    throw std::runtime_error(s.file + ": check '" + c.name + "': metric '" + metric + "' not computed" +
                             (v ? " for variant '" + v->variant().name + "'" : " for the study") +
                             "; known: " + known_numbers(source));
  }
  if (v && !v->run.built) {
    c.note = v->run.message;
  } else if (v && node["requires_completed"] && node["requires_completed"].as<bool>() && !v->run.completed) {
    // A check on the state at the end time: a run that stopped has no value; what it
    // had reached at its last committed step is kept in the note.
    c.note += "; run did not complete: at its last committed step (t = " + number(v->run.run.time_s) +
              " s) the value was " + number(c.value);
    c.value = kNaN;
  }
  return c;
}

/// The completion check of a variant that has none in study.yaml: every variant must
/// reach its end time (gating), unless its `expected_stop` attribute names the error
/// it is known to stop with.
Check completion_check(const VariantOutcome& v) {
  Check c;
  c.name = v.variant().label + ": run completed";
  c.value = v.run.completed ? 1.0 : 0.0;
  c.threshold = 1.0;
  c.comparison = "==";
  c.gating = true;
  c.note = v.run.message;
  c.expected = "pass";
  if (v.variant().has("expected_stop")) {
    const std::string& stop = v.variant().text("expected_stop");
    c.expected = "fail";
    c.run_completed = v.run.completed;
    c.stopped_as_expected = stopped_with(v, stop);
    c.note = "expected to stop with \"" + stop + "\"" + (v.run.message.empty() ? "" : ": " + v.run.message);
  }
  return c;
}

bool has_completion_check(const Study& s, const VariantOutcome& v, const std::string& tier) {
  for (const auto& group : s.groups)
    for (const YAML::Node& node : group) {
      const bool study_scope = node["scope"] && node["scope"].as<std::string>() == "study";
      if (study_scope || !node["metric"] || node["metric"].as<std::string>() != "completed") continue;
      if (listed(node["tiers"], tier) && listed(node["variants"], v.variant().name)) return true;
    }
  return false;
}

/// Numbers the runner computes for every run with a flow network, from its record:
/// the largest mass_volume_error over the steps (the stored mass recomputed from the
/// committed apertures, independent of the ledger), the same per flow node (the flow
/// solve bounds each node's residual by its tolerance times the step's mass, so this
/// is bounded by the tolerance), and the ledger's own largest error. A case's metrics
/// may not define these names.
void add_runner_numbers(const VariantRun& r, const simulation::Model& model, Metrics& m) {
  if (!model.flow) return;
  const simulation::RunRecord& record = r.record();
  double volume = record.empty() ? kNaN : 0.0, per_node = volume, ledger = volume;
  for (std::size_t row = 0; row < record.rows(); ++row) {
    const double e = record.value(row, "mass_volume_error"), nodes = record.value(row, "flow_nodes");
    // A NaN propagates (std::max would drop it), so a broken step cannot pass.
    volume = std::isnan(e) || std::isnan(volume) ? kNaN : std::max(volume, e);
    per_node = std::isnan(e) || std::isnan(per_node) ? kNaN : std::max(per_node, nodes > 0 ? e / nodes : e);
    const double l = record.value(row, "mass_balance_error");
    ledger = std::isnan(l) || std::isnan(ledger) ? kNaN : std::max(ledger, l);
  }
  for (const auto& [name, value] : {std::pair<std::string, double>{"max_mass_volume_error", volume},
                                    {"max_mass_volume_error_per_node", per_node},
                                    {"max_ledger_mass_error", ledger}}) {
    if (m.numbers.count(name)) throw std::runtime_error("case metrics define '" + name + "', a name of the runner's");
    m.numbers[name] = value;
    m.json[name] = finite_or_null(value);
  }
}

/// Writes the checks into result["checks"] and result["status"]; returns whether every
/// gating check matches its expectation.
bool record_checks(const std::vector<Check>& checks, nlohmann::json& result) {
  bool all_match = true, gating_match = true;
  result["checks"] = nlohmann::json::array();
  for (const Check& c : checks) {
    all_match = all_match && c.matches();
    if (c.gating) gating_match = gating_match && c.matches();
    result["checks"].push_back({{"name", c.name}, {"value", finite_or_null(c.value)}, {"threshold", c.threshold},
                                {"comparison", c.comparison}, {"expected", c.expected}, {"passed", c.passed()},
                                {"as_expected", c.matches()}, {"gating", c.gating}, {"note", c.note}});
  }
  result["status"] = all_match ? "pass" : "fail";
  return gating_match;
}

// ----------------------------------------------------------------------- runs

nlohmann::json attribute_json(const std::string& text) {
  std::size_t used = 0;
  try {
    const double v = std::stod(text, &used);
    if (used == text.size()) return v;
  } catch (const std::exception&) {
  }
  if (text == "true" || text == "false") return text == "true";
  return text;
}

/// The fields every variant's metrics carry (study.yaml `variant_metrics`).
void standard_metrics(const Study& s, const VariantOutcome& v, nlohmann::json& m) {
  const VariantRun& r = v.run;
  for (const std::string& field : s.metric_fields) {
    if (field == "label") m["label"] = v.variant().label;
    else if (field == "case_file") m["case_file"] = v.variant().case_file;
    else if (field == "completed") m["completed"] = r.completed;
    else if (field == "message") {
      if (!r.message.empty()) m["message"] = r.message;
    } else if (field == "time_reached_s") m["time_reached_s"] = r.run.time_s;
    else if (field == "steps") m["steps"] = r.run.steps;
    else if (field == "wall_s") m["wall_s"] = r.run.wall_seconds;
    else if (field == "factorizations") m["factorizations"] = r.run.totals.factorizations;
    else if (field == "vertex_vertex_activations") m["vertex_vertex_activations"] = r.run.totals.vertex_vertex_activations;
    else if (v.variant().has(field)) m[field] = attribute_json(v.variant().text(field));
    else throw std::runtime_error(s.file + ": variant_metrics: unknown field '" + field + "' (variant '" +
                                  v.variant().name + "')");
  }
}

void write_files(const std::string& dir, const std::map<std::string, std::string>& files) {
  for (const auto& [name, text] : files) io::write_file_atomically(dir + "/" + name, text);
}

VariantOutcome run_variant(const VariantSpec& spec, const CaseDefinition& def, const std::string& tier,
                           const std::string& case_dir, const std::string& out_dir) {
  VariantOutcome out;
  VariantRun& r = out.run;
  r.variant = &spec;
  r.tier = tier;
  r.out_dir = out_dir;
  const std::string run_dir = out_dir + "/runs/" + spec.name;
  fs::remove_all(run_dir);  // never mix with a previous run's output
  simulation::Model model;
  try {
    std::string case_path = case_dir + "/" + spec.case_file;
    if (!spec.overrides_yaml.empty()) {
      // The variant as a case file of its own, which a user can run with `hfdda run`.
      fs::create_directories(run_dir);
      const std::string generated = run_dir + "/case.yaml";
      io::write_file_atomically(generated, "# Variant '" + spec.name + "' of study.yaml: " + spec.case_file +
                                               " with the variant's `set:` keys.\nextends: " +
                                               fs::absolute(case_path).string() + "\n" + spec.overrides_yaml);
      case_path = generated;
    }
    r.config = io::load_case_file(case_path);
    if (def.validate) def.validate(*r.config, spec);
    if (def.run) {
      fs::create_directories(run_dir);
      def.run(r, case_path, run_dir);
      out.metrics = def.metrics(r);
      write_files(out_dir, out.metrics.files);
      return out;
    }
    model = simulation::build_model(*r.config);
    r.built = true;
    const bool vtu = std::find(spec.vtu_tiers.begin(), spec.vtu_tiers.end(), tier) != spec.vtu_tiers.end();
    r.run = simulation::run(model, {run_dir, true, vtu});
    r.completed = r.run.completed;
    if (!r.completed) r.note("run stopped at t = " + number(r.run.time_s) + " s: " + r.run.message);
  } catch (const std::exception& e) {
    r.note(std::string(r.built ? "run failed: " : "case not built: ") + e.what());
  }
  r.model = r.built ? &model : nullptr;
  out.metrics = def.metrics(r);
  if (r.built) add_runner_numbers(r, model, out.metrics);
  r.model = nullptr;  // the model ends here
  write_files(out_dir, out.metrics.files);
  return out;
}

struct Options {
  std::string tier, case_dir, out_dir;
};

std::optional<Options> parse_options(int argc, char** argv) {
  Options o{"full", "", ""};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--tier") o.tier = argv[i + 1];
    else if (key == "--case-dir") o.case_dir = argv[i + 1];
    else if (key == "--out") o.out_dir = argv[i + 1];
    else return std::nullopt;
  }
  if (argc % 2 == 0 || o.case_dir.empty() || o.out_dir.empty() || (o.tier != "quick" && o.tier != "full" && o.tier != "ensemble"))
    return std::nullopt;
  return o;
}

}  // namespace

int run_harness(int argc, char** argv, const CaseDefinition& def) {
  const std::string program = fs::path(argv[0]).filename().string();
  const auto options = parse_options(argc, argv);
  if (!options) {
    std::fprintf(stderr, "usage: %s --tier quick|full|ensemble --case-dir DIR --out RESULT_DIR\n", program.c_str());
    return 2;
  }
  const std::string &tier = options->tier, &out_dir = options->out_dir;
  try {
    const auto runner_start = std::chrono::steady_clock::now();
    if (!def.metrics) throw std::runtime_error("the case defines no metrics function");
    std::fprintf(stderr, "%s; %s\n", dda::apply_thread_policy(dda::threads_from_environment()).c_str(),
                 core::retain_freed_memory().c_str());
    const Study study = load_study(options->case_dir + "/study.yaml");
    fs::create_directories(out_dir);

    StudyOutcome outcome;
    outcome.tier = tier;
    outcome.references = study.references;
    std::vector<const VariantSpec*> selected;
    for (const VariantSpec& spec : study.variants)
      if (std::find(spec.tiers.begin(), spec.tiers.end(), tier) != spec.tiers.end()) selected.push_back(&spec);
    const int jobs = def.variants_share_cores ? variant_jobs_from_environment() : 1;
    if (jobs > 1 && dda::applied_threads() > 1)
      throw std::runtime_error("HFDDA_VERIFY_JOBS = " + std::to_string(jobs) +
                               " runs each variant on one thread; HFDDA_THREADS must then be 1 (got " +
                               std::to_string(dda::applied_threads()) + ")");
    if (jobs > 1) std::fprintf(stderr, "%d variants at a time (HFDDA_VERIFY_JOBS)\n", jobs);
    outcome.variants = run_variants_in_pool(
        selected.size(), jobs,
        [&](std::size_t i) { return run_variant(*selected[i], def, tier, options->case_dir, out_dir); },
        [&](std::size_t i, const VariantOutcome& v) {
          std::fprintf(stderr, "%s %-22s %s  t %g s  %.1f s  %s%s%s\n", study.case_name.c_str(),
                       selected[i]->name.c_str(), v.run.completed ? "completed    " : "NOT COMPLETED",
                       v.run.run.time_s, v.run.run.wall_seconds, v.metrics.summary.c_str(),
                       v.run.message.empty() ? "" : "\n    ", v.run.message.c_str());
        });
    if (def.study_metrics) def.study_metrics(outcome);
    write_files(out_dir, outcome.metrics.files);

    std::vector<Check> checks;
    for (const VariantOutcome& v : outcome.variants)
      if (!has_completion_check(study, v, tier)) checks.push_back(completion_check(v));
    for (const auto& group : study.groups) {
      const bool study_scope = group.size() == 1 && group[0]["scope"] && group[0]["scope"].as<std::string>() == "study";
      if (study_scope) {
        if (auto c = make_check(study, group[0], nullptr, outcome)) checks.push_back(*c);
        continue;
      }
      for (const VariantOutcome& v : outcome.variants)
        for (const YAML::Node& node : group)
          if (auto c = make_check(study, node, &v, outcome)) checks.push_back(*c);
    }

    nlohmann::json result;
    result["case"] = study.case_name;
    result["title"] = study.title;
    result["seed_section"] = study.seed_section;
    result["tier"] = tier;
    result["wall_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - runner_start).count();
    // What the numbers depend on beyond the source: long runs differ in the last bits
    // between OpenBLAS's kernels (docs/design_notes.md section 32).
    const std::string kernels = dda::blas_kernels();
    result["environment"] = {{"threads", dda::applied_threads()}, {"blas_kernels", kernels.empty() ? "unknown" : kernels}};
    const bool gating_match = record_checks(checks, result);
    const bool all_match = result["status"] == "pass";
    nlohmann::json& metrics = result["metrics"] = nlohmann::json::object();
    for (const VariantOutcome& v : outcome.variants) {
      nlohmann::json m = nlohmann::json::object();
      standard_metrics(study, v, m);
      m.update(v.metrics.json);
      metrics[v.variant().name] = m;
    }
    metrics.update(outcome.metrics.json);
    const auto figures = study.figures.find(tier);
    result["figures"] = figures != study.figures.end() ? nlohmann::json(figures->second) : nlohmann::json::array();
    result["notes"] = study.notes;
    result["tables"] = outcome.metrics.tables;
    io::write_file_atomically(out_dir + "/result.json", result.dump(2) + "\n");
    std::fprintf(stderr, "%s: %s (gating checks %s)\n", study.case_name.c_str(),
                 all_match ? "all checks as expected" : "some checks missed", gating_match ? "pass" : "FAIL");
    return gating_match ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program.c_str(), e.what());
    return 2;
  }
}

}  // namespace hfdda::verification
