// The output schema (simulation/run_record.hpp): the column registry, the in-memory
// RunRecord and its agreement with history.csv, and the README's column table.

#include <gtest/gtest.h>

#include <cmath>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"
#include "simulation/run_record.hpp"

namespace hfdda::simulation {
namespace {
namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string field;
  while (std::getline(s, field, ',')) out.push_back(field);
  return out;
}

TEST(RunRecord, LooksUpColumnsAndRows) {
  RunRecord r({"step", "time_s", "x_m"});
  r.append({1, 0.5, 10});
  r.append({2, 1.0, 20});
  EXPECT_EQ(r.rows(), 2u);
  EXPECT_TRUE(r.has("x_m"));
  EXPECT_FALSE(r.has("y_m"));
  EXPECT_EQ(r.column("time_s"), 1u);
  EXPECT_EQ(r.value(1, "x_m"), 20.0);
  EXPECT_EQ(r.series("time_s"), (std::vector<double>{0.5, 1.0}));
  EXPECT_THROW(r.append({3, 1.5}), std::invalid_argument);
  EXPECT_THROW(r.value(2, "x_m"), std::out_of_range);
  EXPECT_THROW(RunRecord({"a", "a"}), std::invalid_argument);
}

TEST(RunRecord, UnknownColumnListsTheKnownOnes) {
  RunRecord r({"step", "time_s"});
  r.append({1, 0.5});
  try {
    r.series("pressure");
    FAIL() << "no exception";
  } catch (const std::out_of_range& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'pressure'"), std::string::npos) << what;
    EXPECT_NE(what.find("known columns: step, time_s"), std::string::npos) << what;
  }
  EXPECT_THROW(r.value(0, "pressure"), std::out_of_range);
}

TEST(OutputColumns, NamesAreUniqueAndDocumented) {
  std::set<std::string> names;
  for (const OutputColumn& c : fixed_history_columns()) {
    EXPECT_TRUE(names.insert(c.name).second) << c.name;
    EXPECT_FALSE(c.unit.empty()) << c.name;
    EXPECT_FALSE(c.description.empty()) << c.name;
    EXPECT_TRUE(c.value) << c.name;
    EXPECT_EQ(c.name.find_first_of(",\n\r\" "), std::string::npos) << c.name;
  }
  const auto probe = probe_columns("tip", 0);
  ASSERT_EQ(probe.size(), 2u);
  EXPECT_EQ(probe[0].name, "probe_tip_pressure_Pa");
  EXPECT_EQ(probe[1].name, "probe_tip_aperture_m");
  std::set<std::string> summary;
  for (const SummaryField& f : summary_solver_fields()) EXPECT_TRUE(summary.insert(f.name).second) << f.name;
}

// README.md's run-directory section documents the columns with the table the registry
// generates. On a mismatch the expected table is written into the build tree.
TEST(OutputColumns, ReadmeHasTheGeneratedTable) {
  const fs::path readme = fs::path(HFDDA_TEST_DATA_DIR) / ".." / ".." / ".." / "README.md";
  const std::string text = read_text(readme);
  ASSERT_FALSE(text.empty()) << readme;
  const std::string table = history_columns_markdown();
  if (text.find(table) == std::string::npos) {
    const fs::path expected = fs::current_path() / "history_columns.md";
    std::ofstream(expected) << table;
    ADD_FAILURE() << "README.md does not contain the history.csv column table generated from "
                     "simulation/run_record.cpp; the expected table is in "
                  << expected;
  }
  for (const OutputColumn& c : fixed_history_columns())
    EXPECT_NE(text.find("`" + c.name + "`"), std::string::npos) << c.name;
}

// A short coupled run: the record holds exactly what history.csv holds (same columns,
// same order, the same doubles after a round trip through the text), probes included.
TEST(RunRecord, MatchesHistoryCsv) {
  const char* text = R"(
title: "record"
domain:
  outer: {xmin: -8, xmax: 8, ymin: -8, ymax: 8}
mesh: {type: structured, cell_size: 2.0, split: four}
materials:
  - {name: rock, region: all, youngs_modulus: 25.0e9, poissons_ratio: 0.25, density: 2650}
joints: {tensile_strength: 0.0, breakable: false}
fractures:
  - {name: start, from: [-2, 0], to: [2, 0], initially_open: true, fluid_filled: true}
  - {name: path_right, from: [2, 0], to: [6, 0], breakable: true}
fluid: {density: 1000, bulk_modulus: 2.2e9, viscosity: 1.0e-3, reference_pressure: 0, leak_off_coefficient: 0}
injections:
  - {name: well, at: [0, 0], mass_rate: 1.0, start_time: 0}
probes:
  - {name: inlet, at: [0, 0]}
  - {name: tip, at: [4, 0]}
fixed_points: [[-8, -8], [8, -8], [8, 8], [-8, 8]]
time: {dt: 0.5, end_time: 1.0}
output: {every_steps: 0, vtu: false}
)";
  Model model = build_model(io::load_case_text(text, "record.yaml"));
  const fs::path dir = fs::temp_directory_path() / ("hfdda_run_record_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const RunResult result = run(model, {dir.string(), true, false});
  ASSERT_TRUE(result.completed) << result.message;
  const RunRecord& record = result.record;
  EXPECT_EQ(record.rows(), 2u);
  EXPECT_EQ(record.columns().size(), fixed_history_columns().size() + 4);
  EXPECT_EQ(record.columns().back(), "probe_tip_aperture_m");

  std::ifstream csv(dir / "history.csv");
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(split(line), record.columns());
  std::size_t row = 0;
  for (; std::getline(csv, line); ++row) {
    const auto fields = split(line);
    ASSERT_EQ(fields.size(), record.columns().size());
    ASSERT_LT(row, record.rows());
    for (std::size_t c = 0; c < fields.size(); ++c)
      EXPECT_EQ(std::stod(fields[c]), record.row(row)[c]) << record.columns()[c] << " row " << row;
  }
  EXPECT_EQ(row, record.rows());
  EXPECT_EQ(record.value(1, "step"), 2.0);
  EXPECT_EQ(record.value(1, "time_s"), 1.0);
  EXPECT_GT(record.value(1, "mass_injected_kg"), 0.0);
  EXPECT_EQ(record.series("probe_inlet_pressure_Pa"), record.series("injection_pressure_Pa"));
  fs::remove_all(dir);
}

// Lengths per joint kind and extents (seed 5.2-5.4) on a mesh whose joint states are set
// by the case: an open natural fracture and an open rock fracture of known lengths.
TEST(RunRecord, LengthsPerJointKind) {
  const char* text = R"(
title: "kinds"
domain:
  outer: {xmin: -8, xmax: 8, ymin: -8, ymax: 8}
mesh: {type: structured, cell_size: 2.0, split: four}
joints: {tensile_strength: 1.0e6, breakable: false}
fractures:
  - {name: rock, from: [-2, 0], to: [2, 0], initially_open: true, fluid_filled: true}
  - {name: natural, from: [4, -4], to: [4, 2], natural: true, initially_open: true, hydraulic_width: 1.0e-6}
fluid: {}
injections:
  - {name: well, at: [0, 0], mass_rate: 1.0}
fixed_points: [[-8, -8], [8, -8], [8, 8], [-8, 8]]
time: {dt: 1.0, end_time: 1.0}
)";
  const Model model = build_model(io::load_case_text(text, "kinds.yaml"));
  const StepStatistics stats;
  const StepContext c = make_step_context(model, 0, 0.0, stats, 0.0);
  EXPECT_NEAR(c.opened_m[0], 4.0, 1e-12);   // the rock fracture, 4 m
  EXPECT_NEAR(c.opened_m[1], 6.0, 1e-12);   // the natural one, 6 m
  EXPECT_NEAR(c.invaded_m[0], 4.0, 1e-12);  // only the fluid-filled one holds fluid
  EXPECT_EQ(c.invaded_m[1], 0.0);
  EXPECT_EQ(c.slipped_m[0] + c.slipped_m[1], 0.0);
  EXPECT_NEAR(c.open_extent_m, std::hypot(4.0, 4.0), 1e-12);  // (4, -4) from the injection point
  EXPECT_NEAR(c.invaded_extent_m, 2.0, 1e-12);
}

}  // namespace
}  // namespace hfdda::simulation
