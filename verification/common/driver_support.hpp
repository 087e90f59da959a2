#pragma once
// Pieces every verification driver shares: its command line, the checks it records in
// result.json (schema in verification/README.md) and their pass/expectation logic.

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
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
