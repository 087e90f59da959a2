// Unit tests of the verification runner (verification/harness/): which variants run in a
// tier, completion checks, gating, expected failures that must be real failures, and the
// flags result.json carries for the report. Each test writes a small study folder with
// tiny case files (a few blocks, one step) and runs the harness on it.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "dda/thread_policy.hpp"
#include "harness.hpp"

namespace hfdda::verification {
namespace {

namespace fs = std::filesystem;

/// Four cells of 2 m, fixed corners, one step: builds and runs in milliseconds.
const char* kTinyCase = R"(title: "tiny"
domain:
  outer: {xmin: -2, xmax: 2, ymin: -2, ymax: 2}
mesh: {type: structured, cell_size: 2.0, split: two}
fixed_points: [[-2, -2], [2, -2], [2, 2], [-2, 2]]
time: {dt: 1.0, end_time: 1.0}
)";

/// Pumps into a fluid-filled crack but allows one open-close iteration and no step cut:
/// builds, then stops at the first step ("open-close iterations did not converge").
const char* kStoppingCase = R"(title: "stops"
domain:
  outer: {xmin: -2, xmax: 2, ymin: -2, ymax: 2}
mesh: {type: structured, cell_size: 1.0, split: two}
fixed_points: [[-2, -2], [2, -2], [2, 2], [-2, 2]]
fractures:
  - {name: well, from: [-1, 0], to: [1, 0], initially_open: true, fluid_filled: true}
fluid: {density: 1000, bulk_modulus: 2.2e9, viscosity: 1e-3}
injections:
  - {name: well, at: [0, 0], mass_rate: 10}
numerics: {max_open_close_iterations: 1, max_step_cuts: 0}
time: {dt: 1.0, end_time: 1.0}
)";

class HarnessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(HFDDA_TEST_OUTPUT_DIR) / ("harness_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "case");
    write("case/tiny.yaml", kTinyCase);
    write("case/stops.yaml", kStoppingCase);
  }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }

  /// Runs the harness on case/study.yaml with `definition`; returns its exit code.
  int run(const std::string& study, const std::string& tier, const CaseDefinition& definition) {
    write("case/study.yaml", study);
    const std::string case_dir = (dir_ / "case").string(), out = (dir_ / ("out-" + tier)).string();
    std::vector<std::string> args{"verify_test", "--tier", tier, "--case-dir", case_dir, "--out", out};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    const int code = run_harness(static_cast<int>(argv.size()), argv.data(), definition);
    std::ifstream in(out + "/result.json");
    result_ = in ? nlohmann::json::parse(in) : nlohmann::json();
    return code;
  }
  const nlohmann::json& check(const std::string& name) const {
    for (const auto& c : result_["checks"])
      if (c["name"] == name) return c;
    throw std::runtime_error("no check named '" + name + "' in " + result_["checks"].dump());
  }

  fs::path dir_;
  nlohmann::json result_;
};

/// Metrics: `value` for every built variant (or the variant's `value` attribute).
CaseDefinition constant_metrics(double value) {
  return {nullptr,
          [value](const VariantRun& r) {
            Metrics m;
            if (r.built) m.numbers["value"] = r.variant->has("value") ? r.variant->number("value") : value;
            return m;
          },
          nullptr};
}

const std::string kHeader = "case: test\ntitle: t\nseed_section: '0'\n";

TEST_F(HarnessTest, TiersSelectVariantsAndEveryVariantGetsACompletionCheck) {
  const std::string study = kHeader + R"(variants:
  - {name: q, case: tiny.yaml, label: "quick one", tiers: [quick]}
  - {name: f, case: tiny.yaml, label: "full one", tiers: [full]}
checks:
  - {name: "{label}: value", metric: value, comparison: "<=", threshold: 1.0, gating: true}
)";
  EXPECT_EQ(run(study, "quick", constant_metrics(0.5)), 0);
  ASSERT_EQ(result_["checks"].size(), 2u);  // the runner's completion check + the value
  EXPECT_EQ(check("quick one: run completed")["value"], 1.0);
  EXPECT_TRUE(check("quick one: run completed")["gating"].get<bool>());
  EXPECT_FALSE(result_["metrics"].contains("f"));
  EXPECT_EQ(run(study, "full", constant_metrics(0.5)), 0);
  EXPECT_TRUE(result_["metrics"].contains("f"));
}

TEST_F(HarnessTest, ResultRecordsTheThreadsAndTheBlasKernels) {
  // A report made from results of several machines must be able to say which kernels
  // each result ran on (docs/design_notes.md section 32).
  const std::string study = kHeader + R"(variants:
  - {name: a, case: tiny.yaml, label: "a"}
checks:
  - {name: "value", metric: value, comparison: "<=", threshold: 1.0, gating: true}
)";
  EXPECT_EQ(run(study, "quick", constant_metrics(0.5)), 0);
  ASSERT_TRUE(result_.contains("environment")) << result_.dump();
  EXPECT_EQ(result_["environment"]["threads"], dda::applied_threads());
  EXPECT_GE(result_["environment"]["threads"].get<int>(), 1);
  const std::string kernels = dda::blas_kernels();
  EXPECT_EQ(result_["environment"]["blas_kernels"], kernels.empty() ? "unknown" : kernels);
}

TEST_F(HarnessTest, OnlyGatingChecksDecideTheExitCodeAndTheFlagIsWritten) {
  const std::string study = kHeader + R"(variants:
  - {name: a, case: tiny.yaml, label: "a"}
checks:
  - {name: "reported", metric: value, comparison: "<=", threshold: 1.0, gating: false}
  - {name: "gating in full", metric: value, comparison: "<=", threshold: 1.0, gating: full}
)";
  EXPECT_EQ(run(study, "quick", constant_metrics(2.0)), 0);  // both miss, neither gates in quick
  EXPECT_FALSE(check("reported")["gating"].get<bool>());
  EXPECT_FALSE(check("gating in full")["gating"].get<bool>());
  EXPECT_FALSE(check("reported")["passed"].get<bool>());
  EXPECT_EQ(result_["status"], "fail");
  EXPECT_EQ(run(study, "full", constant_metrics(2.0)), 1);
  EXPECT_TRUE(check("gating in full")["gating"].get<bool>());
  EXPECT_FALSE(check("gating in full")["as_expected"].get<bool>());
}

TEST_F(HarnessTest, ExpectedFailureNeedsACompletedRunWithAFiniteValue) {
  const std::string study = kHeader + R"(variants:
  - {name: misses, case: tiny.yaml, label: "misses", value: 2.0}
  - {name: nan, case: tiny.yaml, label: "nan", value: nan}
  - {name: unbuilt, case: no_such_file.yaml, label: "unbuilt"}
checks:
  - {name: "{label}: value", metric: value, comparison: "<=", threshold: 1.0, expected: fail, gating: true,
     if_built: false}
)";
  EXPECT_EQ(run(study, "quick", constant_metrics(0.0)), 1);
  EXPECT_TRUE(check("misses: value")["as_expected"].get<bool>());
  EXPECT_FALSE(check("nan: value")["as_expected"].get<bool>()) << "a NaN is not an expected failure";
  EXPECT_FALSE(check("unbuilt: value")["as_expected"].get<bool>()) << "a missing run is not an expected failure";
  EXPECT_FALSE(check("unbuilt: run completed")["as_expected"].get<bool>());
}

TEST_F(HarnessTest, ExpectedStopMustBeTheNamedError) {
  const std::string study = kHeader + R"(variants:
  - {name: named, case: stops.yaml, label: "named", expected_stop: "open-close iterations did not converge"}
  - {name: other, case: stops.yaml, label: "other", expected_stop: "some other error"}
  - {name: unexpected, case: stops.yaml, label: "unexpected"}
checks: []
)";
  EXPECT_EQ(run(study, "quick", constant_metrics(0.0)), 1);
  EXPECT_TRUE(check("named: run completed")["as_expected"].get<bool>());
  EXPECT_EQ(check("named: run completed")["expected"], "fail");
  EXPECT_FALSE(check("other: run completed")["as_expected"].get<bool>());
  EXPECT_FALSE(check("unexpected: run completed")["as_expected"].get<bool>());
}

TEST_F(HarnessTest, StudyErrorsNameTheFileAndExitWithTwo) {
  const std::string study = kHeader + R"(variants:
  - {name: a, case: tiny.yaml, label: "a"}
checks:
  - {name: "x", metric: value, comparison: "~", threshold: 1.0}
)";
  EXPECT_EQ(run(study, "quick", constant_metrics(0.0)), 2);
}

/// Sets HFDDA_VERIFY_JOBS for one scope.
struct VerifyJobs {
  explicit VerifyJobs(const char* value) { setenv("HFDDA_VERIFY_JOBS", value, 1); }
  ~VerifyJobs() { unsetenv("HFDDA_VERIFY_JOBS"); }
};

/// Metrics that record how many variants were in their metrics at once (each stays 50 ms).
CaseDefinition overlap_metrics(std::atomic<int>& inside, std::atomic<int>& most) {
  return {nullptr,
          [&inside, &most](const VariantRun& r) {
            const int now = ++inside;
            for (int seen = most; now > seen && !most.compare_exchange_weak(seen, now);) {
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
            --inside;
            Metrics m;
            if (r.built) m.numbers["value"] = r.variant->number("value");
            return m;
          },
          nullptr};
}

TEST_F(HarnessTest, VariantsRunTwoAtATimeWithTheResultsOfOneAtATime) {
  const std::string study = kHeader + R"(variants:
  - {name: a, case: tiny.yaml, label: "a", value: 1}
  - {name: b, case: tiny.yaml, label: "b", value: 2}
  - {name: c, case: stops.yaml, label: "c", value: 3}
  - {name: d, case: tiny.yaml, label: "d", value: 4}
checks:
  - {name: "{label}: value", metric: value, comparison: "<=", threshold: 3.0, gating: false}
)";
  auto without_times = [](nlohmann::json r) {
    r.erase("wall_s");
    for (auto& [name, m] : r["metrics"].items()) m.erase("wall_s");
    return r;
  };
  std::atomic<int> inside{0}, most{0};
  nlohmann::json one_at_a_time;
  {
    const VerifyJobs jobs("1");
    ASSERT_EQ(run(study, "quick", overlap_metrics(inside, most)), 1);  // c does not complete
    EXPECT_EQ(most, 1);
    one_at_a_time = without_times(result_);
  }
  {
    const VerifyJobs jobs("2");
    most = 0;
    ASSERT_EQ(run(study, "quick", overlap_metrics(inside, most)), 1);
    EXPECT_EQ(most, 2) << "two variants at a time";
    EXPECT_EQ(without_times(result_), one_at_a_time) << "same checks, in study order, and metrics";
    // A study whose variants use the cores themselves runs them one at a time.
    CaseDefinition exclusive = overlap_metrics(inside, most);
    exclusive.variants_share_cores = false;
    most = 0;
    run(study, "quick", exclusive);
    EXPECT_EQ(most, 1);
  }
  {
    const VerifyJobs jobs("two");
    testing::internal::CaptureStderr();
    EXPECT_EQ(run(study, "quick", constant_metrics(0.0)), 2);
    EXPECT_NE(testing::internal::GetCapturedStderr().find("HFDDA_VERIFY_JOBS must be a whole number from 1 to 64 (got 'two')"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace hfdda::verification
