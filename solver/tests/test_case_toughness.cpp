// Fracture toughness as a case-file input (seed eq. 4.13): the `fracture_toughness` key
// of `joints`, `fractures[]` and `breakable_patterns[]` items, its exclusion of
// `tensile_strength` in the same map, its inheritance, and the T0 each joint of a built
// model gets from its own length.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>

#include "fracture/fracture_criteria.hpp"
#include "io/case_config.hpp"
#include "simulation/model.hpp"
#include "test_case_support.hpp"

namespace hfdda::io {
namespace {

using namespace case_test;

constexpr const char* kBoth = "give tensile_strength or fracture_toughness, not both";

TEST(CaseToughness, ParsedInEveryMapThatSetsAStrength) {
  const CaseConfig c = load_case_text(R"(
mesh: {type: structured, cell_size: 1.0, split: four}
joints: {fracture_toughness: 0.886e6}
fractures:
  - {name: a, from: [-2, 0], to: [2, 0], fracture_toughness: 4.43e6}
  - {name: b, from: [-2, 1], to: [2, 1]}
breakable_patterns:
  - {name: p, region: {xmin: -3, xmax: 3, ymin: -3, ymax: 3}, cell_size: 1, lines: [minus_45],
     fracture_toughness: 2.0e6}
)",
                                      "case.yaml");
  EXPECT_EQ(c.joints.fracture_toughness_Pa_sqrt_m, std::optional<double>(0.886e6));
  ASSERT_GE(c.fractures.size(), 3u);
  EXPECT_EQ(c.fractures[0].fracture_toughness_Pa_sqrt_m, std::optional<double>(4.43e6));
  EXPECT_FALSE(c.fractures[1].fracture_toughness_Pa_sqrt_m.has_value());  // from joints
  EXPECT_EQ(c.breakable_patterns[0].fracture_toughness_Pa_sqrt_m, std::optional<double>(2.0e6));
  EXPECT_EQ(c.fractures[2].fracture_toughness_Pa_sqrt_m, std::optional<double>(2.0e6));  // a pattern line
  EXPECT_FALSE(load_case_text("title: x\n", "case.yaml").joints.fracture_toughness_Pa_sqrt_m.has_value());
}

TEST(CaseToughness, BothInOneMapIsAnError) {
  expect_text_error("joints:\n  tensile_strength: 1.0e6\n  fracture_toughness: 0.886e6\n", 3,
                    "joints.fracture_toughness", kBoth);
  expect_text_error("joints:\n  fracture_toughness: 0.886e6\n  tensile_strength: 1.0e6\n", 2,
                    "joints.fracture_toughness", kBoth);
  expect_text_error("fractures:\n  - {from: [0, 0], to: [1, 0], tensile_strength: 0,\n"
                    "     fracture_toughness: 1.0e6}\n",
                    3, "fractures[0].fracture_toughness", kBoth);
  expect_text_error("mesh: {type: structured}\nbreakable_patterns:\n"
                    "  - {region: {xmin: -1, xmax: 1, ymin: -1, ymax: 1}, cell_size: 1,\n"
                    "     lines: [horizontal], tensile_strength: 0, fracture_toughness: 1.0e6}\n",
                    4, "breakable_patterns[0].fracture_toughness", kBoth);
}

TEST(CaseToughness, NonPositiveIsAnError) {
  expect_text_error("joints: {fracture_toughness: 0}\n", 1, "joints.fracture_toughness", "must be in (0, 1e13]");
  expect_text_error("joints: {fracture_toughness: -1.0e6}\n", 1, "joints.fracture_toughness", "must be in (0, 1e13]");
  expect_text_error("fractures:\n  - {from: [0, 0], to: [1, 0], fracture_toughness: 0}\n", 2,
                    "fractures[0].fracture_toughness", "must be in (0, 1e13]");
  expect_text_error("joints: {fracture_toughness: stiff}\n", 1, "joints.fracture_toughness",
                    "expected a finite number");
}

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = std::string(HFDDA_TEST_OUTPUT_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(CaseToughness, ALaterFileOfTheExtendsChainReplacesTheInheritedChoice) {
  write_file("toughness_base_k.yaml", "joints: {fracture_toughness: 0.886e6, cohesion: 2.0e6}\n");
  write_file("toughness_base_t.yaml", "joints: {tensile_strength: 3.0e6}\n");
  // tensile_strength written below a toughness replaces it ...
  const CaseConfig t = load_case_file(
      write_file("toughness_child_t.yaml", "extends: toughness_base_k.yaml\njoints: {tensile_strength: 1.0e6}\n"));
  EXPECT_FALSE(t.joints.fracture_toughness_Pa_sqrt_m.has_value());
  EXPECT_EQ(t.joints.tensile_strength_Pa, 1.0e6);
  EXPECT_EQ(t.joints.cohesion_Pa, 2.0e6);  // other keys still merge
  // ... and a toughness written below a tensile strength is used instead of it.
  const CaseConfig k = load_case_file(
      write_file("toughness_child_k.yaml", "extends: toughness_base_t.yaml\njoints: {fracture_toughness: 0.5e6}\n"));
  EXPECT_EQ(k.joints.fracture_toughness_Pa_sqrt_m, std::optional<double>(0.5e6));
  // A child that does not write either keeps the base's choice.
  const CaseConfig keep = load_case_file(
      write_file("toughness_child_keep.yaml", "extends: toughness_base_k.yaml\njoints: {cohesion: 1.0}\n"));
  EXPECT_EQ(keep.joints.fracture_toughness_Pa_sqrt_m, std::optional<double>(0.886e6));
}

/// T0 of the bonds of a built model's joints with midpoint on y = `y`, by joint length.
struct StrengthOnLine {
  double length_m = 0.0;
  double tensile_strength_Pa = 0.0;
  int joints = 0;
};

StrengthOnLine strength_on_line(const simulation::Model& model, double y) {
  const mesh::Mesh& m = model.system->mesh();
  StrengthOnLine s;
  for (const auto& joint : m.joints) {
    const Vec2 p = m.points[joint.point_p], q = m.points[joint.point_q];
    if (std::abs(p.y() - y) > 1e-9 || std::abs(q.y() - y) > 1e-9) continue;
    const double length = (q - p).norm();
    const double t0 = fracture::bond_strength(joint.properties, length).tensile_strength_Pa;
    if (s.joints > 0) {
      EXPECT_EQ(length, s.length_m);
      EXPECT_EQ(t0, s.tensile_strength_Pa);
    }
    s = {length, t0, s.joints + 1};
  }
  return s;
}

std::string grid_case(double cell_size_m, const std::string& joints, const std::string& fractures) {
  return "domain: {outer: {xmin: -3, xmax: 3, ymin: -3, ymax: 3}}\n"
         "mesh: {type: structured, cell_size: " + std::to_string(cell_size_m) + ", split: two}\n"
         "joints: " + joints + "\nfractures:\n" + fractures + "time: {dt: 1.0, end_time: 1.0}\n";
}

TEST(CaseToughness, EachJointTakesT0FromItsOwnLength) {
  // Seed eq. 4.13, T0 = K_IC / sqrt(pi L / 2): K_IC = 0.886 MPa m^0.5 gives 1.0 MPa on
  // joints of 0.5 m and 0.707 MPa on joints of 1 m (seed 4.5).
  const char* fracture = "  - {name: f, from: [-3, 0], to: [3, 0], fracture_toughness: 0.886e6}\n";
  for (const auto& [cell, t0] : {std::pair{0.5, 1.0e6}, std::pair{1.0, 0.707e6}}) {
    SCOPED_TRACE(cell);
    const simulation::Model model =
        simulation::build_model(load_case_text(grid_case(cell, "{tensile_strength: 5.0e6}", fracture), "k.yaml"));
    const StrengthOnLine s = strength_on_line(model, 0.0);
    EXPECT_EQ(s.joints, static_cast<int>(std::lround(6.0 / cell)));
    EXPECT_NEAR(s.length_m, cell, 1e-12);
    EXPECT_NEAR(s.tensile_strength_Pa, t0, 1e-3 * t0);
    EXPECT_DOUBLE_EQ(s.tensile_strength_Pa, 0.886e6 / std::sqrt(std::numbers::pi * cell / 2.0));
    EXPECT_EQ(strength_on_line(model, 1.0).tensile_strength_Pa, 5.0e6);  // joints: T0 as given
  }
}

TEST(CaseToughness, AFractureOrPatternChoiceWinsOverTheOneOfJoints) {
  // joints: K_IC; a fracture with its own T0 keeps it, one without takes K_IC.
  const std::string text = grid_case(1.0, "{fracture_toughness: 0.886e6}",
                                     "  - {name: t, from: [-3, 0], to: [3, 0], tensile_strength: 2.0e6}\n"
                                     "  - {name: k, from: [-3, 1], to: [3, 1]}\n");
  const simulation::Model model = simulation::build_model(load_case_text(text, "k.yaml"));
  EXPECT_EQ(strength_on_line(model, 0.0).tensile_strength_Pa, 2.0e6);
  EXPECT_DOUBLE_EQ(strength_on_line(model, 1.0).tensile_strength_Pa, 0.886e6 / std::sqrt(std::numbers::pi / 2.0));
  EXPECT_DOUBLE_EQ(strength_on_line(model, -1.0).tensile_strength_Pa,
                   0.886e6 / std::sqrt(std::numbers::pi / 2.0));  // no fracture: joints

  // A breakable pattern's toughness reaches the joints of its lines.
  const std::string patterned =
      "domain: {outer: {xmin: -3, xmax: 3, ymin: -3, ymax: 3}}\n"
      "mesh: {type: structured, cell_size: 1.0, split: two}\n"
      "joints: {tensile_strength: 5.0e6}\n"
      "breakable_patterns:\n"
      "  - {region: {xmin: -3, xmax: 3, ymin: -2, ymax: 2}, cell_size: 1, lines: [horizontal],\n"
      "     fracture_toughness: 1.2533e6}\n"
      "time: {dt: 1.0, end_time: 1.0}\n";
  const simulation::Model p = simulation::build_model(load_case_text(patterned, "p.yaml"));
  EXPECT_NEAR(strength_on_line(p, 1.0).tensile_strength_Pa, 1.0e6, 1e-4 * 1.0e6);
  EXPECT_EQ(strength_on_line(p, 2.0).tensile_strength_Pa, 5.0e6);  // edge of the region: not a pattern line
}

}  // namespace
}  // namespace hfdda::io
