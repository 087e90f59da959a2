// `breakable_patterns`: expansion into line features, the joints they select once the
// model is built, the propagation cases written with them (seed 3.4, 3.5), and the
// errors of every key and cross check.

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "simulation/model.hpp"
#include "test_case_support.hpp"

namespace hfdda::io {
namespace {

using namespace case_test;

const std::string kPropagationCases =
    std::string(HFDDA_TEST_DATA_DIR) + "/../../../verification/propagation/";

void expect_feature(const FractureConfig& f, const std::string& name, Vec2 from, Vec2 to) {
  EXPECT_EQ(f.name, name);
  EXPECT_EQ(f.from, from) << name;
  EXPECT_EQ(f.to, to) << name;
}

// ---------------------------------------------------------------------------
// Expansion

TEST(BreakablePatterns, GridLinesFollowTheWrittenFracturesAndSkipTheirJoints) {
  const CaseConfig c = load_case_text(
      "fractures:\n"
      "  - {name: crack, from: [-1, 0], to: [1, 0], initially_open: true}\n"
      "breakable_patterns:\n"
      "  - name: grid\n"
      "    region: {xmin: -4, xmax: 4, ymin: -2, ymax: 2}\n"
      "    cell_size: 2\n"
      "    lines: [horizontal, vertical]\n"
      "    tensile_strength: 5e5\n",
      "grid.yaml");
  ASSERT_EQ(c.breakable_patterns.size(), 1u);
  EXPECT_EQ(c.breakable_patterns[0].line, 4);
  // The written fracture first; y = 0 is the only horizontal line strictly inside the
  // region, cut where the crack lies; then x = -2, 0, 2. Edges y = +-2, x = +-4 excluded.
  ASSERT_EQ(c.fractures.size(), 6u);
  expect_feature(c.fractures[0], "crack", {-1, 0}, {1, 0});
  expect_feature(c.fractures[1], "grid.horizontal", {-4, 0}, {-1, 0});
  expect_feature(c.fractures[2], "grid.horizontal", {1, 0}, {4, 0});
  expect_feature(c.fractures[3], "grid.vertical", {-2, -2}, {-2, 2});
  expect_feature(c.fractures[4], "grid.vertical", {0, -2}, {0, 2});
  expect_feature(c.fractures[5], "grid.vertical", {2, -2}, {2, 2});
  for (std::size_t i = 1; i < c.fractures.size(); ++i) {
    const FractureConfig& f = c.fractures[i];
    EXPECT_EQ(f.breakable, std::optional<bool>(true));
    EXPECT_EQ(f.tensile_strength_Pa, std::optional<double>(5e5));
    EXPECT_FALSE(f.cohesion_Pa.has_value());
    EXPECT_FALSE(f.friction_angle_deg.has_value());
    EXPECT_FALSE(f.initially_open);
    EXPECT_EQ(f.line, 4);
  }
}

TEST(BreakablePatterns, DiagonalsAreClippedToTheRegion) {
  const CaseConfig c = load_case_text(
      "mesh: {split: four}\n"
      "breakable_patterns:\n"
      "  - {name: d, region: {xmin: 0, xmax: 4, ymin: 0, ymax: 2}, cell_size: 2,\n"
      "     lines: [plus_45, minus_45], breakable: false, cohesion: 1e6, friction_angle: 40}\n",
      "diagonals.yaml");
  // y = x + c for c = -2, 0; y = -x + c for c = 2, 4 (c = 0 and 6 only touch a corner).
  ASSERT_EQ(c.fractures.size(), 4u);
  expect_feature(c.fractures[0], "d.plus_45", {2, 0}, {4, 2});
  expect_feature(c.fractures[1], "d.plus_45", {0, 0}, {2, 2});
  expect_feature(c.fractures[2], "d.minus_45", {0, 2}, {2, 0});
  expect_feature(c.fractures[3], "d.minus_45", {2, 2}, {4, 0});
  EXPECT_EQ(c.fractures[0].breakable, std::optional<bool>(false));
  EXPECT_EQ(c.fractures[0].cohesion_Pa, std::optional<double>(1e6));
  EXPECT_EQ(c.fractures[0].friction_angle_deg, std::optional<double>(40));
}

TEST(BreakablePatterns, OriginShiftsTheGrid) {
  const CaseConfig c = load_case_text(
      "breakable_patterns:\n"
      "  - {region: {xmin: 0, xmax: 3, ymin: 0, ymax: 1}, cell_size: 1, origin: [0.5, 0],\n"
      "     lines: [vertical]}\n",
      "origin.yaml");
  ASSERT_EQ(c.fractures.size(), 3u);
  expect_feature(c.fractures[0], "pattern.vertical", {0.5, 0}, {0.5, 1});
  expect_feature(c.fractures[2], "pattern.vertical", {2.5, 0}, {2.5, 1});
}

TEST(BreakablePatterns, ExtendsReplacesOrKeepsTheList) {
  const CaseConfig kept = load_case_text("extends: patterns_base.yaml\n", kCases + "v.yaml");
  EXPECT_EQ(kept.breakable_patterns.size(), 1u);
  EXPECT_EQ(kept.fractures.size(), 1u + 6u);  // the crack, then y = -4, -2, 2, 4 and y = 0 cut twice
  const CaseConfig cleared =
      load_case_text("extends: patterns_base.yaml\nbreakable_patterns: []\n", kCases + "v.yaml");
  EXPECT_TRUE(cleared.breakable_patterns.empty());
  EXPECT_EQ(cleared.fractures.size(), 1u);
  // A child's fractures are what the inherited pattern leaves out.
  const CaseConfig moved = load_case_text(
      "extends: patterns_base.yaml\nfractures: [{from: [-6, 4], to: [6, 4]}]\n", kCases + "v.yaml");
  EXPECT_EQ(moved.fractures.size(), 1u + 4u);
}

// ---------------------------------------------------------------------------
// Joints selected once the model is built

TEST(BreakablePatterns, FracturesWinAndLaterPatternsOverrideEarlierOnes) {
  const char* text = R"(
domain: {outer: {xmin: -4, xmax: 4, ymin: -4, ymax: 4}}
mesh: {type: structured, cell_size: 2, split: four}
joints: {tensile_strength: 1e6, breakable: false}
fractures:
  - {name: crack, from: [-2, 0], to: [2, 0], initially_open: true}
breakable_patterns:
  - {name: all, region: {xmin: -4, xmax: 4, ymin: -4, ymax: 4}, cell_size: 2,
     lines: [horizontal, vertical, plus_45, minus_45]}
  - {name: weak, region: {xmin: -4, xmax: 4, ymin: -4, ymax: 4}, cell_size: 2,
     lines: [minus_45], tensile_strength: 1e5}
time: {dt: 1, end_time: 1}
)";
  const simulation::Model model = simulation::build_model(load_case_text(text, "override.yaml"));
  const mesh::Mesh& m = model.system->mesh();
  int breakable = 0, weak = 0, open = 0;
  for (const auto& joint : m.joints) {
    const Vec2 d = m.points[joint.point_q] - m.points[joint.point_p];
    const Vec2 mid = 0.5 * (m.points[joint.point_p] + m.points[joint.point_q]);
    const bool falling = d.x() * d.y() < 0;  // on a -45 degree diagonal
    const bool boundary = std::abs(std::abs(mid.x()) - 4) < 1e-9 || std::abs(std::abs(mid.y()) - 4) < 1e-9;
    const bool crack = std::abs(mid.y()) < 1e-9 && std::abs(mid.x()) < 2;
    const mesh::JointProperties& p = joint.properties;
    EXPECT_EQ(p.breakable, !boundary && !crack);  // the crack keeps joints.breakable
    EXPECT_EQ(p.tensile_strength_Pa, falling ? 1e5 : 1e6);
    EXPECT_EQ(p.initially_open, crack);
    breakable += p.breakable;
    weak += falling;
    open += p.initially_open;
  }
  // 16 cells: 16 x 4 half-diagonals, 24 inner grid-line joints of which 2 are the crack.
  EXPECT_EQ(breakable, 64 + 24 - 2);
  EXPECT_EQ(weak, 32);
  EXPECT_EQ(open, 2);
}

TEST(BreakablePatterns, LineOffTheMeshIsReportedAtThePatternLine) {
  const char* text =
      "domain: {outer: {xmin: -4, xmax: 4, ymin: -4, ymax: 4}}\n"
      "mesh: {type: structured, cell_size: 2, split: four}\n"
      "breakable_patterns:\n"
      "  - {region: {xmin: -4, xmax: 4, ymin: -4, ymax: 4}, cell_size: 3, lines: [vertical]}\n";
  try {
    simulation::build_model(load_case_text(text, "off.yaml"));
    FAIL() << "no InputError thrown";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 4) << e.what();
    EXPECT_EQ(e.key(), "fractures[0]") << e.what();
    EXPECT_NE(e.rule().find("does not follow mesh edges"), std::string::npos) << e.what();
  }
}

/// Counts of the joints of a propagation case (seed 3.4, 3.5).
struct JointCounts {
  int breakable = 0, weak = 0, open = 0, fluid_filled = 0;
};

JointCounts propagation_case_joints(const std::string& name) {
  const CaseConfig c = load_case_file(kPropagationCases + name);
  const simulation::Model model = simulation::build_model(c);
  JointCounts n;
  const mesh::Mesh& m = model.system->mesh();
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const mesh::JointProperties& p = m.joints[j].properties;
    n.breakable += p.breakable;
    n.weak += p.tensile_strength_Pa < c.joints.tensile_strength_Pa;
    n.open += p.initially_open;
    const int f = model.fracture_of_joint[j];
    n.fluid_filled += f >= 0 && model.fractures[f].config_index >= 0 && c.fractures[model.fractures[f].config_index].fluid_filled;
  }
  return n;
}

TEST(BreakablePatterns, PropagationCasesSelectTheJointsOfTheSeedRuns) {
  // 20 x 20 inner cells of 2 m: 800 half-diagonals per direction; 19 inner grid lines
  // per direction of 20 joints each. The counts are those of the case files that listed
  // one fracture per grid line and diagonal.
  const JointCounts free = propagation_case_joints("base.yaml");
  EXPECT_EQ(free.breakable, 2 * 380 - 2 + 2 * 800);  // every inner joint but the open ones
  EXPECT_EQ(free.open, 2);
  EXPECT_EQ(free.fluid_filled, 2);
  const JointCounts weak = propagation_case_joints("weak_diagonal.yaml");
  EXPECT_EQ(weak.breakable, 1600);  // the diagonals only
  EXPECT_EQ(weak.weak, 800);        // the -45 degree ones, T0 = 0.1 MPa (seed 3.5)
  EXPECT_EQ(weak.open, 2);
  EXPECT_EQ(weak.fluid_filled, 2);
}

// ---------------------------------------------------------------------------
// Errors

TEST(BreakablePatterns, KeyErrors) {
  const std::string head = "mesh: {split: four}\nbreakable_patterns:\n";
  const std::string region = "region: {xmin: -4, xmax: 4, ymin: -4, ymax: 4}";
  expect_text_error(head + "  - {cell_size: 2, lines: [horizontal]}\n", 3,
                    "breakable_patterns[0].region", "is required");
  expect_text_error(head + "  - {" + region + ", lines: [horizontal]}\n", 3,
                    "breakable_patterns[0].cell_size", "is required");
  expect_text_error(head + "  - {" + region + ", cell_size: 2}\n", 3,
                    "breakable_patterns[0].lines", "is required");
  expect_text_error(head + "  - {" + region + ", cell_size: 0, lines: [vertical]}\n", 3,
                    "breakable_patterns[0].cell_size", "must be > 0 (got 0)");
  expect_text_error(head + "  - {" + region + ", cell_size: 2, lines: [diagonal]}\n", 3,
                    "breakable_patterns[0].lines[0]",
                    "must be one of: horizontal, vertical, plus_45, minus_45 (got 'diagonal')");
  expect_text_error(head + "  - {" + region + ", cell_size: 2, lines: [vertical, vertical]}\n",
                    3, "breakable_patterns[0].lines[1]", "duplicate entry 'vertical'");
  expect_text_error(head + "  - " + region + "\n    cell_size: 2\n    lines: []\n", 5,
                    "breakable_patterns[0].lines", "must name at least one family of lines");
  expect_text_error(head + "  - {" + region + ", cell_size: 2, lines: [vertical], breakable: no}\n",
                    3, "breakable_patterns[0].breakable", "expected a boolean");
  expect_text_error(
      head + "  - {" + region + ", cell_size: 2, lines: [vertical], tensile_strength: -1}\n", 3,
      "breakable_patterns[0].tensile_strength", "must be in [0, 1e13] (got -1)");
  expect_text_error(
      head + "  - {" + region + ", cell_size: 2, lines: [vertical], friction_angle: 90}\n", 3,
      "breakable_patterns[0].friction_angle", "[0, 90)");
  expect_text_error(head + "  - {" + region + ", spacing: 2}\n", 3,
                    "breakable_patterns[0].spacing",
                    "unknown key; allowed keys: name, region, cell_size, origin, lines, "
                    "breakable, tensile_strength, fracture_toughness, cohesion, friction_angle");
  expect_text_error(head + "  - {region: {xmin: 4, xmax: -4, ymin: 0, ymax: 1}}\n", 3,
                    "breakable_patterns[0].region.xmax", "must be > xmin");
  expect_text_error("breakable_patterns: {cell_size: 2}\n", 1, "breakable_patterns",
                    "expected a list");
}

TEST(BreakablePatterns, ChecksAcrossKeys) {
  const std::string item =
      "  - {region: {xmin: -4, xmax: 4, ymin: -4, ymax: 4}, cell_size: 2, lines: [plus_45]}\n";
  expect_text_error("mesh: {type: delaunay}\nbreakable_patterns:\n" + item, 2,
                    "breakable_patterns", "needs mesh.type: structured");
  expect_text_error("mesh: {split: two}\nbreakable_patterns:\n" + item, 3,
                    "breakable_patterns[0].lines", "need mesh.split: four");
  EXPECT_NO_THROW(load_case_text(
      "mesh: {split: none}\nbreakable_patterns:\n"
      "  - {region: {xmin: -4, xmax: 4, ymin: -4, ymax: 4}, cell_size: 2, lines: [vertical]}\n",
      "none.yaml"));
  expect_text_error(
      "breakable_patterns:\n"
      "  - {region: {xmin: -60, xmax: 4, ymin: -4, ymax: 4}, cell_size: 2, lines: [vertical]}\n",
      2, "breakable_patterns[0].region",
      "must lie in the domain [-50, 50] x [-50, 50] (got [-60, 4] x [-4, 4])");
  expect_text_error(
      "breakable_patterns:\n"
      "  - region: {xmin: -4, xmax: 4, ymin: -4, ymax: 4}\n"
      "    cell_size: 2\n    origin: [0, 51]\n    lines: [vertical]\n",
      4, "breakable_patterns[0].origin", "lies outside the domain");
  expect_text_error(
      "breakable_patterns:\n"
      "  - {region: {xmin: 0, xmax: 1, ymin: 0, ymax: 1}, cell_size: 2, lines: [vertical]}\n",
      2, "breakable_patterns[0].region", "holds no line of the pattern");
  expect_text_error(
      "breakable_patterns:\n"
      "  - region: {xmin: -50, xmax: 50, ymin: -50, ymax: 50}\n"
      "    cell_size: 1e-4\n    lines: [vertical, horizontal]\n",
      3, "breakable_patterns[0].cell_size", "gives more than 100000 lines");
}

TEST(BreakablePatterns, MergedCheckNamesTheBaseFile) {
  // The child switches to a Delaunay mesh; the pattern it inherits is in the base, line 8.
  expect_error(error_of_text("extends: patterns_base.yaml\nmesh: {type: delaunay}\n",
                             kCases + "v.yaml"),
               kCases + "patterns_base.yaml", 8, "breakable_patterns", "structured");
}

TEST(BreakablePatterns, ReferenceDocumentsTheKeys) {
  const std::string reference = case_file_reference_markdown();
  for (const char* key :
       {"## `breakable_patterns[]` items", "`cell_size`", "`origin`", "`lines`", "plus_45",
        "minus_45", "`breakable_patterns` need `mesh.type: structured`"})
    EXPECT_NE(reference.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace hfdda::io
