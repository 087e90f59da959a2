// The fuzz corpus as regression tests: every file of fuzz/regressions/ states on its
// first line what the reader must do with it, and is run through the fuzz target;
// every seed of fuzz/corpus/ must be accepted. Inputs too large to keep as files are
// made here.
//
// First line of a regression file, one of:
//   # expect: accepted
//   # expect: accepted known_problem~"PART OF THE PROBLEM"   (model not built: known_problem())
//   # expect: error key=KEY [line=N] [stage=read|model] rule~"PART OF THE RULE"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "case_mutator.hpp"
#include "case_reader_target.hpp"
#include "io/case_config.hpp"
#include "simulation/model.hpp"

namespace hfdda::fuzz {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = HFDDA_FUZZ_DIR;

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> yaml_files(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

struct Expectation {
  bool accepted = false;
  std::string key, stage, rule_part, known_problem_part;
  std::optional<int> line;
};

/// The expectation of a regression file's first line; nullopt when it has none.
std::optional<Expectation> expectation_of(const std::string& text) {
  const std::string first = text.substr(0, text.find_first_of("\r\n"));
  const std::string prefix = "# expect: ";
  if (!first.starts_with(prefix)) return std::nullopt;
  const std::string rest = first.substr(prefix.size());
  Expectation e;
  if (rest == "accepted") {
    e.accepted = true;
    return e;
  }
  const std::string known = "accepted known_problem~\"";
  if (rest.starts_with(known) && rest.size() > known.size() + 1 && rest.back() == '"') {
    e.accepted = true;
    e.known_problem_part = rest.substr(known.size(), rest.size() - known.size() - 1);
    return e;
  }
  if (!rest.starts_with("error ")) return std::nullopt;
  std::istringstream words(rest.substr(6));
  std::string word;
  while (words >> word) {
    if (word.starts_with("key=")) {
      e.key = word.substr(4);
    } else if (word.starts_with("line=")) {
      e.line = std::stoi(word.substr(5));
    } else if (word.starts_with("stage=")) {
      e.stage = word.substr(6);
    } else if (word.starts_with("rule~\"")) {
      const std::size_t open = rest.find("rule~\"") + 6, close = rest.rfind('"');
      if (close <= open) return std::nullopt;
      e.rule_part = rest.substr(open, close - open);
      break;  // the quoted part is the last
    } else {
      return std::nullopt;
    }
  }
  if (e.key.empty() || e.rule_part.empty()) return std::nullopt;
  return e;
}

/// Test names from file names: letters, digits and `_` only.
std::string test_name(const std::string& file) {
  std::string name = fs::path(file).stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

class Regression : public testing::TestWithParam<std::string> {};

TEST_P(Regression, GivesTheStatedOutcome) {
  const std::string text = read_file(kFuzzDir / "regressions" / GetParam());
  const auto expected = expectation_of(text);
  ASSERT_TRUE(expected) << "first line must be '# expect: accepted', '# expect: accepted known_problem~\"...\"' "
                           "or '# expect: error key=KEY [line=N] [stage=read|model] rule~\"...\"'";
  const TargetResult r = run_case_reader(text);
  ASSERT_NE(r.outcome, Outcome::finding) << describe(r);
  if (expected->accepted) {
    EXPECT_EQ(r.outcome, Outcome::accepted) << describe(r);
    if (expected->known_problem_part.empty()) {
      EXPECT_EQ(r.known_problem, "") << describe(r);
    } else {
      EXPECT_NE(r.known_problem.find(expected->known_problem_part), std::string::npos) << describe(r);
    }
    return;
  }
  ASSERT_EQ(r.outcome, Outcome::refused) << describe(r);
  EXPECT_EQ(r.key, expected->key) << describe(r);
  EXPECT_NE(r.rule.find(expected->rule_part), std::string::npos) << describe(r);
  if (expected->line) {
    EXPECT_EQ(r.line, *expected->line) << describe(r);
  }
  if (!expected->stage.empty()) {
    EXPECT_EQ(r.stage, expected->stage) << describe(r);
  }
}

INSTANTIATE_TEST_SUITE_P(Files, Regression, testing::ValuesIn(yaml_files(kFuzzDir / "regressions")),
                         [](const testing::TestParamInfo<std::string>& info) { return test_name(info.param); });

class CorpusSeed : public testing::TestWithParam<std::string> {};

TEST_P(CorpusSeed, IsAccepted) {
  const TargetResult r = run_case_reader(read_file(kFuzzDir / "corpus" / GetParam()));
  EXPECT_EQ(r.outcome, Outcome::accepted) << describe(r);
}

INSTANTIATE_TEST_SUITE_P(Files, CorpusSeed, testing::ValuesIn(yaml_files(kFuzzDir / "corpus")),
                         [](const testing::TestParamInfo<std::string>& info) { return test_name(info.param); });

TEST(FuzzCorpus, SomeSeedsBuildTheirModel) {
  // Otherwise mutated inputs would never reach the model builder.
  int built = 0;
  for (const auto& file : yaml_files(kFuzzDir / "corpus"))
    built += run_case_reader(read_file(kFuzzDir / "corpus" / file)).model_built ? 1 : 0;
  EXPECT_GE(built, 3);
}

// --- Inputs too large to keep as files ------------------------------------------

void expect_refused(const std::string& text, const std::string& key, const std::string& rule_part) {
  const TargetResult r = run_case_reader(text);
  ASSERT_EQ(r.outcome, Outcome::refused) << describe(r);
  EXPECT_EQ(r.key, key) << describe(r);
  EXPECT_NE(r.rule.find(rule_part), std::string::npos) << describe(r);
}

TEST(FuzzGenerated, FileOverFourMebibytes) {
  expect_refused("title: x\n# " + std::string(4u << 20, 'x') + "\n", "(file)", "at most 4194304 bytes");
}

TEST(FuzzGenerated, MillionBracketsDeep) {
  expect_refused("title: " + std::string(1000000, '[') + std::string(1000000, ']') + "\n", "(document)",
                 "nesting too deep");
}

TEST(FuzzGenerated, FixedPointListOverTheItemLimit) {
  std::string points = "title: x\nfixed_points: [";
  for (int i = 0; i < 100000; ++i) points += "0,";
  expect_refused(points + "0]\n", "fixed_points", "a list of 100001 items; at most 100000");
}

TEST(FuzzGenerated, FixedPointListOfAMillionItems) {
  // Refused by the text scan before parsing: yaml-cpp would first spend about half a
  // gigabyte and seconds on the million nodes (several times that under sanitizers).
  std::string points = "title: x\nfixed_points: [";
  for (int i = 0; i < 1000000; ++i) points += "0,";
  const auto start = std::chrono::steady_clock::now();
  expect_refused(points + "0]\n", "(file)", "YAML values");
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(s, 5.0) << "refusing the list took " << s << " s";
}

// --- The pieces of the fuzzer ----------------------------------------------------

TEST(FuzzTarget, BrokenInvariantsAreNamed) {
  io::CaseConfig config = io::load_case_text("title: x\n", "case.yaml");
  EXPECT_EQ(broken_invariant(config), "");
  config.time.dt_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(broken_invariant(config), "");
  config = io::load_case_text("title: x\n", "case.yaml");
  config.domain.outer.xmax = config.domain.outer.xmin;
  EXPECT_NE(broken_invariant(config), "");
  config = io::load_case_text("title: x\n", "case.yaml");
  config.materials[0].poissons_ratio = 0.5;
  EXPECT_NE(broken_invariant(config), "");
}

TEST(FuzzTarget, BlockEstimateFollowsTheMesh) {
  const io::CaseConfig structured = io::load_case_text(
      "domain: {outer: {xmin: 0, xmax: 10, ymin: 0, ymax: 4}}\nmesh: {cell_size: 1, split: four}\n", "case.yaml");
  EXPECT_DOUBLE_EQ(estimated_block_count(structured), 160.0);
  const io::CaseConfig defaults = io::load_case_text("title: x\n", "case.yaml");
  EXPECT_GT(estimated_block_count(defaults), 10000.0);  // 100 m x 100 m of 1 m cells
}

TEST(FuzzMutator, InputsDependOnSeedAndIndexOnly) {
  const CaseMutator mutator({"title: a\ntime: {dt: 1, end_time: 2}\n", "mesh:\n  cell_size: 2\n"});
  for (std::uint64_t i = 0; i < 50; ++i) {
    Rng a = input_rng(7, i), b = input_rng(7, i);
    EXPECT_EQ(mutator.make_input(a), mutator.make_input(b));
  }
  int differ = 0;
  for (std::uint64_t i = 0; i < 50; ++i) {
    Rng a = input_rng(7, i), b = input_rng(8, i);
    differ += mutator.make_input(a) != mutator.make_input(b) ? 1 : 0;
  }
  EXPECT_GT(differ, 40);
}

TEST(FuzzMutator, EveryMutationIsUsed) {
  const CaseMutator mutator({"title: a\ntime: {dt: 1, end_time: 2}\nmesh:\n  cell_size: 2\n"});
  std::vector<std::string> names;
  for (std::uint64_t i = 0; i < 2000; ++i) {
    Rng rng = input_rng(1, i);
    std::string text = mutator.seeds()[0];
    names.push_back(mutator.mutate_once(text, rng));
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  EXPECT_GE(names.size(), 13u);
}

}  // namespace
}  // namespace hfdda::fuzz
