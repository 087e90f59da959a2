#pragma once
// Pieces every verification driver shares: its command line, its thresholds file, the
// solver's history.csv, the checks it records in result.json (schema in
// verification/README.md) and their pass/expectation logic.

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace hfdda::verification {

/// `--tier quick|full --case-dir DIR --out RESULT_DIR`
struct DriverOptions {
  std::string tier = "full", case_dir, out_dir;
};

/// Parses the driver's command line; prints the usage of `program` and returns
/// std::nullopt when it is incomplete (the driver then exits with 2).
inline std::optional<DriverOptions> parse_driver_options(int argc, char** argv, const char* program) {
  DriverOptions o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--tier") o.tier = argv[i + 1];
    else if (key == "--case-dir") o.case_dir = argv[i + 1];
    else if (key == "--out") o.out_dir = argv[i + 1];
  }
  if (o.case_dir.empty() || o.out_dir.empty() || (o.tier != "quick" && o.tier != "full")) {
    std::fprintf(stderr, "usage: %s --tier quick|full --case-dir DIR --out RESULT_DIR\n", program);
    return std::nullopt;
  }
  return o;
}

/// The case's thresholds.yaml: `key: {value: number or [lo, hi], reason: text}`.
class Thresholds {
 public:
  explicit Thresholds(const std::string& path) : node_(YAML::LoadFile(path)) {}
  double value(const char* key) const { return node_[key]["value"].as<double>(); }
  nlohmann::json range(const char* key) const {
    return nlohmann::json{node_[key]["value"][0].as<double>(), node_[key]["value"][1].as<double>()};
  }

 private:
  YAML::Node node_;
};

/// A number as the drivers write it in their CSV files.
inline std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.10g", v);
  return buffer;
}

/// A CSV file of names and numbers written by the solver (history.csv): read whole,
/// values looked up by column name.
class CsvTable {
 public:
  /// Throws std::runtime_error naming the file: missing or empty, a row whose field
  /// count differs from the header's, or a `required` column it lacks.
  static CsvTable read(const std::string& path, const std::vector<std::string>& required) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("no file " + path);
    CsvTable t;
    std::string line;
    if (!std::getline(in, line)) throw std::runtime_error(path + " is empty");
    const std::vector<std::string> header = split(line);
    for (std::size_t i = 0; i < header.size(); ++i) t.column_[header[i]] = i;
    std::string missing;
    for (const std::string& c : required)
      if (!t.has(c)) missing += (missing.empty() ? "" : ", ") + c;
    if (!missing.empty()) throw std::runtime_error(path + " lacks column(s) " + missing);
    for (int row = 2; std::getline(in, line); ++row) {
      const std::vector<std::string> fields = split(line);
      if (fields.empty()) continue;
      if (fields.size() != header.size())
        throw std::runtime_error(path + ": row " + std::to_string(row) + " has " + std::to_string(fields.size()) +
                                 " fields for " + std::to_string(header.size()) + " columns");
      t.rows_.push_back(fields);
    }
    return t;
  }
  bool has(const std::string& name) const { return column_.count(name) != 0; }
  std::size_t rows() const { return rows_.size(); }
  /// NaN for a column the file lacks or a field that is not a number.
  double value(std::size_t row, const std::string& name) const {
    const auto c = column_.find(name);
    if (c == column_.end()) return std::numeric_limits<double>::quiet_NaN();
    const std::string& text = rows_[row][c->second];
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    return end == text.c_str() ? std::numeric_limits<double>::quiet_NaN() : v;
  }

 private:
  /// One line's fields (no quoting: names and numbers only); a trailing \r is dropped.
  static std::vector<std::string> split(std::string line) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> out;
    std::stringstream s(line);
    std::string field;
    while (std::getline(s, field, ',')) out.push_back(field);
    if (!line.empty() && line.back() == ',') out.emplace_back();
    return out;
  }
  std::map<std::string, std::size_t> column_;
  std::vector<std::vector<std::string>> rows_;
};

inline nlohmann::json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

/// One comparison of a measured value with its threshold. A value that is not finite
/// (a run that did not produce it) never passes.
struct Check {
  std::string name;
  double value;
  nlohmann::json threshold;  // a number, or [lo, hi] for "in"
  std::string comparison;    // "<=", "<", ">=", ">", "==" or "in"
  std::string expected;      // "pass" or "fail" (a known, documented failure)
  std::string note;
  bool gating;

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
  bool matches() const { return passed() == (expected == "pass"); }
};

/// Writes the checks into result["checks"] and result["status"]; returns whether every
/// gating check matches its expectation (the driver's exit code).
inline bool record_checks(const std::vector<Check>& checks, nlohmann::json& result) {
  bool all_match = true, gating_match = true;
  for (const Check& c : checks) {
    all_match = all_match && c.matches();
    if (c.gating) gating_match = gating_match && c.matches();
    result["checks"].push_back({{"name", c.name}, {"value", finite_or_null(c.value)}, {"threshold", c.threshold},
                                {"comparison", c.comparison}, {"expected", c.expected}, {"passed", c.passed()},
                                {"gating", c.gating}, {"note", c.note}});
  }
  result["status"] = all_match ? "pass" : "fail";
  return gating_match;
}

}  // namespace hfdda::verification
