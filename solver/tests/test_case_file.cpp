// Case-file loader: values, defaults, extends merging, and the file/line/key of every
// kind of input error (STYLE.md items 7 and 10).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "core/errors.hpp"
#include "io/case_config.hpp"

namespace hfdda::io {
namespace {

const std::string kCases = std::string(HFDDA_TEST_DATA_DIR) + "/cases/";

std::optional<InputError> error_of_text(const std::string& yaml,
                                        const std::string& label = "case.yaml") {
  try {
    load_case_text(yaml, label);
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

std::optional<InputError> error_of_file(const std::string& path) {
  try {
    load_case_file(path);
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

/// Checks file, line and key exactly, and that the rule contains `rule_part`.
void expect_error(const std::optional<InputError>& error, const std::string& file, int line,
                  const std::string& key, const std::string& rule_part = "") {
  ASSERT_TRUE(error.has_value()) << "no InputError thrown";
  EXPECT_EQ(error->file(), file) << error->what();
  EXPECT_EQ(error->line(), line) << error->what();
  EXPECT_EQ(error->key(), key) << error->what();
  EXPECT_NE(error->rule().find(rule_part), std::string::npos) << error->what();
}

void expect_text_error(const std::string& yaml, int line, const std::string& key,
                       const std::string& rule_part = "") {
  SCOPED_TRACE(yaml);
  expect_error(error_of_text(yaml), "case.yaml", line, key, rule_part);
}

// ---------------------------------------------------------------------------
// Valid files

TEST(CaseFileParse, FullFileHasExpectedValues) {
  const CaseConfig c = load_case_file(kCases + "full.yaml");
  EXPECT_EQ(c.file, kCases + "full.yaml");
  EXPECT_EQ(c.title, "Full case");
  EXPECT_EQ(c.domain.outer.xmin, -40);
  EXPECT_EQ(c.domain.outer.xmax, 60);
  EXPECT_EQ(c.domain.outer.ymin, -30);
  EXPECT_EQ(c.domain.outer.ymax, 70);
  ASSERT_TRUE(c.domain.inner.has_value());
  EXPECT_EQ(c.domain.inner->xmin, -10);
  EXPECT_EQ(c.domain.inner->ymax, 15);

  EXPECT_EQ(c.mesh.kind, MeshKind::delaunay);
  EXPECT_EQ(c.mesh.cell_size_m, 0.5);
  EXPECT_EQ(c.mesh.outer_growth, 1.5);
  EXPECT_EQ(c.mesh.split, mesh::CellSplit::four);
  EXPECT_EQ(c.mesh.max_area_inner_m2, 0.25);
  EXPECT_EQ(c.mesh.max_area_outer_m2, 20);
  EXPECT_EQ(c.mesh.min_angle_deg, 28);
  EXPECT_EQ(c.mesh.line, 6);
  EXPECT_EQ(c.mesh_file, kCases + "full.yaml");

  ASSERT_EQ(c.materials.size(), 3u);
  EXPECT_EQ(c.materials[0].name, "shale");
  EXPECT_EQ(c.materials[0].region, "all");
  EXPECT_EQ(c.materials[0].youngs_modulus_Pa, 10e9);
  EXPECT_EQ(c.materials[0].poissons_ratio, 0.22);
  EXPECT_EQ(c.materials[0].density_kg_m3, 2500);
  EXPECT_EQ(c.materials[1].region, "box");
  EXPECT_EQ(c.materials[1].box.xmin, -40);
  EXPECT_EQ(c.materials[1].box.xmax, -20);
  EXPECT_EQ(c.materials[1].youngs_modulus_Pa, 1e9);
  EXPECT_EQ(c.materials[1].poissons_ratio, 0.0);
  EXPECT_EQ(c.materials[1].density_kg_m3, 1185);
  EXPECT_EQ(c.materials[2].region, "outer");
  EXPECT_EQ(c.materials[0].line, 15);
  EXPECT_EQ(c.materials[1].line, 16);
  EXPECT_EQ(c.materials[2].line, 22);

  EXPECT_EQ(c.joints.tensile_strength_Pa, 6e6);
  EXPECT_EQ(c.joints.cohesion_Pa, 1e6);
  EXPECT_EQ(c.joints.friction_angle_deg, 35);
  EXPECT_FALSE(c.joints.breakable);

  ASSERT_EQ(c.fractures.size(), 2u);
  const FractureConfig& crack = c.fractures[0];
  EXPECT_EQ(crack.name, "crack");
  EXPECT_EQ(crack.from, Vec2(-5, 0));
  EXPECT_EQ(crack.to, Vec2(5, 0));
  EXPECT_EQ(crack.segment_length_m, 0.5);
  EXPECT_TRUE(crack.initially_open);
  EXPECT_FALSE(crack.natural);
  EXPECT_EQ(crack.breakable, std::optional<bool>(true));
  EXPECT_EQ(crack.tensile_strength_Pa, std::optional<double>(0.0));
  EXPECT_EQ(crack.cohesion_Pa, std::optional<double>(0.0));
  EXPECT_EQ(crack.friction_angle_deg, std::optional<double>(30.0));
  EXPECT_EQ(crack.pressure_Pa, std::optional<double>(9.81e6));
  EXPECT_EQ(crack.line, 25);
  const FractureConfig& natural = c.fractures[1];
  EXPECT_TRUE(natural.natural);
  EXPECT_EQ(natural.to, Vec2(10, 12));
  EXPECT_FALSE(natural.breakable.has_value());
  EXPECT_FALSE(natural.pressure_Pa.has_value());
  EXPECT_EQ(natural.line, 26);

  EXPECT_EQ(c.far_field.sxx_Pa, -17e6);
  EXPECT_EQ(c.far_field.syy_Pa, -5e6);
  EXPECT_EQ(c.far_field.sxy_Pa, 1e5);
  EXPECT_EQ(c.far_field.sides, (std::vector<std::string>{"left", "right", "top"}));

  ASSERT_EQ(c.point_loads.size(), 1u);
  EXPECT_EQ(c.point_loads[0].at, Vec2(1, 2));
  EXPECT_EQ(c.point_loads[0].force_N_per_m, Vec2(0, -1e6));
  EXPECT_EQ(c.point_loads[0].line, 32);
  EXPECT_EQ(c.body_force_N_m3, Vec2(0, -25996.5));
  ASSERT_EQ(c.fixed_points.size(), 2u);
  EXPECT_EQ(c.fixed_points[1].at, Vec2(60, -30));
  EXPECT_EQ(c.fixed_points[0].line, 35);
  EXPECT_EQ(c.fixed_points[1].line, 36);

  EXPECT_EQ(c.contact.method, ContactMethod::penalty);
  EXPECT_EQ(c.contact.normal_stiffness_factor, 30);
  EXPECT_EQ(c.contact.shear_stiffness_factor, 20);
  EXPECT_EQ(c.contact.vertex_vertex_activation_m, 1e-5);
  EXPECT_EQ(c.contact.fixed_point_stiffness_factor, 50);

  EXPECT_EQ(c.numerics.analysis, AnalysisKind::dynamic_analysis);
  EXPECT_EQ(c.numerics.alm_force_tolerance, 1e-6);
  EXPECT_EQ(c.numerics.max_alm_iterations, 50);
  EXPECT_EQ(c.numerics.max_open_close_iterations, 40);
  EXPECT_EQ(c.numerics.tie_tolerance, 2e-3);
  EXPECT_TRUE(c.numerics.shear_failure_of_intact_joints);

  EXPECT_EQ(c.time.dt_s, 60);
  EXPECT_EQ(c.time.end_time_s, 3600);
  EXPECT_EQ(c.output.every_steps, 5);
  EXPECT_FALSE(c.output.vtu);
}

TEST(CaseFileParse, SeedGriffithExampleMatchesTable31) {
  const CaseConfig c = load_case_file(kCases + "griffith_seed_3_1.yaml");
  EXPECT_EQ(c.domain.outer.width(), 100);
  ASSERT_TRUE(c.domain.inner.has_value());
  EXPECT_EQ(c.domain.inner->width(), 36);
  EXPECT_EQ(c.domain.inner->height(), 24);
  EXPECT_EQ(c.materials.at(0).youngs_modulus_Pa, 25.0e9);
  EXPECT_EQ(c.materials.at(0).poissons_ratio, 0.25);
  EXPECT_EQ(c.materials.at(0).density_kg_m3, 2650);
  EXPECT_EQ(c.joints.friction_angle_deg, 30);
  EXPECT_EQ(c.contact.normal_stiffness_factor, 100);
  EXPECT_EQ(c.fractures.at(0).pressure_Pa, std::optional<double>(9.81e6));
  EXPECT_EQ((c.fractures.at(0).to - c.fractures.at(0).from).norm(), 20);
  EXPECT_EQ(c.far_field.syy_Pa, -5.0e6);
  EXPECT_EQ(c.time.dt_s, 1.0);
  EXPECT_EQ(c.time.end_time_s, 2.0);
}

TEST(CaseFileParse, EmptyFileGivesStructDefaults) {
  const CaseConfig c = load_case_text("", "empty.yaml");
  const CaseConfig d;
  EXPECT_EQ(c.file, "empty.yaml");
  EXPECT_EQ(c.mesh_file, "empty.yaml");
  EXPECT_EQ(c.mesh.line, 0);
  EXPECT_EQ(c.title, "");
  EXPECT_EQ(c.domain.outer.xmin, d.domain.outer.xmin);
  EXPECT_EQ(c.domain.outer.ymax, d.domain.outer.ymax);
  EXPECT_FALSE(c.domain.inner.has_value());
  EXPECT_EQ(c.mesh.kind, d.mesh.kind);
  EXPECT_EQ(c.mesh.cell_size_m, d.mesh.cell_size_m);
  EXPECT_EQ(c.mesh.split, d.mesh.split);
  ASSERT_EQ(c.materials.size(), 1u);
  EXPECT_EQ(c.materials[0].name, "rock");
  EXPECT_EQ(c.materials[0].youngs_modulus_Pa, 25.0e9);
  EXPECT_EQ(c.joints.friction_angle_deg, d.joints.friction_angle_deg);
  EXPECT_TRUE(c.fractures.empty());
  EXPECT_EQ(c.far_field.sides, d.far_field.sides);
  EXPECT_EQ(c.contact.method, ContactMethod::augmented_lagrangian);
  EXPECT_EQ(c.numerics.max_alm_iterations, d.numerics.max_alm_iterations);
  EXPECT_EQ(c.time.dt_s, d.time.dt_s);
  EXPECT_EQ(c.output.every_steps, d.output.every_steps);
}

TEST(CaseFileParse, PartialItemsAndSectionsKeepDefaults) {
  const CaseConfig c = load_case_text(
      "mesh: {split: none}\n"
      "materials:\n"
      "  - {youngs_modulus: 5e9}\n"
      "fractures:\n"
      "  - {from: [-1, 0], to: [1, 0]}\n",
      "partial.yaml");
  EXPECT_EQ(c.mesh.split, mesh::CellSplit::none);
  EXPECT_EQ(c.mesh.cell_size_m, MeshConfig{}.cell_size_m);
  ASSERT_EQ(c.materials.size(), 1u);
  EXPECT_EQ(c.materials[0].youngs_modulus_Pa, 5e9);
  EXPECT_EQ(c.materials[0].poissons_ratio, 0.25);
  EXPECT_EQ(c.materials[0].region, "all");
  ASSERT_EQ(c.fractures.size(), 1u);
  EXPECT_FALSE(c.fractures[0].initially_open);
  EXPECT_FALSE(c.fractures[0].tensile_strength_Pa.has_value());
  EXPECT_EQ(c.fractures[0].line, 5);
}

TEST(CaseFileParse, FilesOnTheDomainBoundaryAreInside) {
  EXPECT_NO_THROW(load_case_text(
      "fractures: [{from: [-50, 0], to: [50, 0]}]\n"
      "fixed_points: [[-50, -50], [50, 50]]\n",
      "edge.yaml"));
}

// ---------------------------------------------------------------------------
// extends

TEST(CaseFileExtends, ChildOverridesKeyByKey) {
  const CaseConfig c = load_case_file(kCases + "extends_child.yaml");
  EXPECT_EQ(c.file, kCases + "extends_child.yaml");
  EXPECT_EQ(c.title, "child");
  EXPECT_EQ(c.mesh.cell_size_m, 0.5);                   // overridden
  EXPECT_EQ(c.mesh.split, mesh::CellSplit::four);       // kept from the base
  ASSERT_TRUE(c.domain.inner.has_value());              // kept from the base
  EXPECT_EQ(c.domain.inner->xmax, 18);
  EXPECT_EQ(c.time.dt_s, 1);                            // kept
  EXPECT_EQ(c.time.end_time_s, 10);                     // overridden
  ASSERT_EQ(c.materials.size(), 2u);                    // list not in child: kept
  EXPECT_EQ(c.materials[1].name, "outer_rock");
  EXPECT_EQ(c.materials[1].line, 9);                    // line in the base file
  EXPECT_EQ(c.mesh_file, kCases + "extends_child.yaml");  // last file writing `mesh`
  EXPECT_EQ(c.mesh.line, 3);
}

TEST(CaseFileExtends, ListsAreReplacedAsAWhole) {
  const CaseConfig c = load_case_file(kCases + "extends_child.yaml");
  ASSERT_EQ(c.fractures.size(), 1u);
  EXPECT_EQ(c.fractures[0].name, "c");
  EXPECT_EQ(c.fractures[0].from, Vec2(-4, 0));
  EXPECT_EQ(c.fractures[0].pressure_Pa, std::optional<double>(1e6));
  EXPECT_EQ(c.fractures[0].line, 5);  // line in the child file
}

TEST(CaseFileExtends, ChainOfThreeFromAnotherFolder) {
  const CaseConfig c = load_case_file(kCases + "derived/extends_grandchild.yaml");
  EXPECT_EQ(c.title, "grandchild");
  EXPECT_EQ(c.mesh.cell_size_m, 0.5);              // from the child
  EXPECT_EQ(c.mesh.split, mesh::CellSplit::four);  // from the base
  EXPECT_FALSE(c.domain.inner.has_value());        // null removes the inherited one
  ASSERT_EQ(c.materials.size(), 1u);
  EXPECT_EQ(c.materials[0].name, "only");
  EXPECT_EQ(c.materials[0].youngs_modulus_Pa, 5e9);
  ASSERT_EQ(c.fractures.size(), 1u);
  EXPECT_EQ(c.fractures[0].name, "c");
}

TEST(CaseFileExtends, ErrorNamesTheFileOfTheBadKey) {
  expect_error(error_of_file(kCases + "extends_bad_child.yaml"),
               kCases + "extends_bad_base.yaml", 2, "mesh.cel_size", "unknown key");
}

TEST(CaseFileExtends, MergedCheckNamesTheFileWhereTheKeyWasSet) {
  // The child shrinks the domain; fracture 'a' is written in the base, line 11.
  expect_error(error_of_file(kCases + "extends_shrink.yaml"), kCases + "extends_base.yaml", 11,
               "fractures[0].from", "lies outside the domain");
}

TEST(CaseFileExtends, CycleIsAnError) {
  expect_error(error_of_file(kCases + "cycle_a.yaml"), kCases + "cycle_b.yaml", 2, "extends",
               "cycle");
  expect_error(error_of_file(kCases + "cycle_self.yaml"), kCases + "cycle_self.yaml", 1,
               "extends", "cycle");
}

TEST(CaseFileExtends, MissingBaseIsReportedAtTheExtendsLine) {
  const std::string label = kCases + "not_written.yaml";
  expect_error(error_of_text("title: x\nextends: no_such_base.yaml\n", label), label, 2,
               "extends", "cannot be read");
}

TEST(CaseFileExtends, RelativeToTheLabelDirectory) {
  const CaseConfig c = load_case_text("extends: extends_base.yaml\n", kCases + "virtual.yaml");
  EXPECT_EQ(c.title, "base");
  EXPECT_EQ(c.file, kCases + "virtual.yaml");
}

// ---------------------------------------------------------------------------
// Errors: file, line and key

TEST(CaseFileErrors, MissingFile) {
  const std::string path = kCases + "does_not_exist.yaml";
  expect_error(error_of_file(path), path, 0, "(file)", "cannot be read");
  expect_error(error_of_file(kCases), kCases, 0, "(file)", "cannot be read");  // a folder
}

TEST(CaseFileErrors, SyntaxError) {
  expect_text_error("title: x\nmesh: {cell_size: 1\ntime: {dt: 1}\n", 3, "(syntax)");
  expect_text_error("title: x\n  dt: 1\n", 2, "(syntax)", "YAML syntax error");
}

TEST(CaseFileErrors, UnknownKeyListsAllowedKeys) {
  expect_text_error("title: x\nmeshh: {}\n", 2, "meshh", "unknown key; allowed keys: title,");
  expect_text_error("mesh:\n  type: structured\n  cellsize: 1\n", 3, "mesh.cellsize",
                    "allowed keys: type, cell_size, outer_growth, split, max_area_inner, "
                    "max_area_outer, min_angle");
  expect_text_error("materials:\n  - {name: a}\n  - {name: b, E: 1}\n", 3, "materials[1].E",
                    "unknown key");
  expect_text_error("domain:\n  outer: {xmin: 0, xmax: 1, ymin: 0, ymax: 1, zmax: 1}\n", 2,
                    "domain.outer.zmax", "unknown key");
}

TEST(CaseFileErrors, DuplicateKey) {
  expect_text_error("time: {dt: 1}\ntitle: a\ntime: {dt: 2}\n", 3, "time", "duplicate key");
}

TEST(CaseFileErrors, WrongTypes) {
  expect_text_error("materials:\n  - {youngs_modulus: stiff}\n", 2,
                    "materials[0].youngs_modulus", "expected a finite number (got 'stiff')");
  expect_text_error("materials:\n  - {youngs_modulus: \"25e9\"}\n", 2,
                    "materials[0].youngs_modulus",
                    "expected a finite number (got the quoted string '25e9')");
  expect_text_error("mesh: fine\n", 1, "mesh", "expected a map");
  expect_text_error("fractures: {from: [0, 0]}\n", 1, "fractures", "expected a list");
  expect_text_error("materials: [rock]\n", 1, "materials[0]", "expected a map");
  expect_text_error("fixed_points: [[0, 0, 0]]\n", 1, "fixed_points[0]",
                    "expected a point [x, y], a list of 2 numbers (got a list of 3 items)");
  expect_text_error("body_force: 9.81\n", 1, "body_force", "expected a point");
  expect_text_error("numerics:\n  max_alm_iterations: 2.5\n", 2,
                    "numerics.max_alm_iterations", "expected an integer");
  expect_text_error("output: {vtu: maybe}\n", 1, "output.vtu", "expected a boolean");
  expect_text_error("title: [a, b]\n", 1, "title", "expected a string");
  expect_text_error("- a\n- b\n", 1, "(document)", "expected a map");
  expect_text_error("time: {dt: .inf}\n", 1, "time.dt", "finite");
}

TEST(CaseFileErrors, EmptyValueIsReportedAtItsKey) {
  expect_text_error("time:\n  dt:\n  end_time: 2\n", 2, "time.dt", "got null");
}

TEST(CaseFileErrors, YoungsModulusMustBePositive) {
  expect_text_error("materials:\n  - {youngs_modulus: 0}\n", 2, "materials[0].youngs_modulus",
                    "must be > 0 (got 0)");
  expect_text_error("materials:\n  - name: a\n  - name: b\n    youngs_modulus: -1\n", 4,
                    "materials[1].youngs_modulus", "must be > 0 (got -1)");
}

TEST(CaseFileErrors, PoissonsRatioInHalfOpenInterval) {
  expect_text_error("materials:\n  - {poissons_ratio: 0.5}\n", 2, "materials[0].poissons_ratio",
                    "must be in [0, 0.5) (got 0.5)");
  expect_text_error("materials:\n  - {poissons_ratio: -0.1}\n", 2,
                    "materials[0].poissons_ratio", "must be in [0, 0.5) (got -0.1)");
}

TEST(CaseFileErrors, OtherRanges) {
  expect_text_error("materials:\n  - {density: 0}\n", 2, "materials[0].density", "> 0");
  expect_text_error("time:\n  dt: 0\n", 2, "time.dt", "must be > 0 (got 0)");
  expect_text_error("time:\n  dt: -1\n", 2, "time.dt", "must be > 0 (got -1)");
  expect_text_error("mesh: {cell_size: -1}\n", 1, "mesh.cell_size", "must be > 0 (got -1)");
  expect_text_error("mesh: {outer_growth: 0.9}\n", 1, "mesh.outer_growth", ">= 1");
  expect_text_error("mesh: {min_angle: 35}\n", 1, "mesh.min_angle", "in (0, 30]");
  expect_text_error("mesh: {max_area_outer: 0}\n", 1, "mesh.max_area_outer", "> 0");
  expect_text_error("joints: {friction_angle: 90}\n", 1, "joints.friction_angle", "[0, 90)");
  expect_text_error("joints: {tensile_strength: -1}\n", 1, "joints.tensile_strength", ">= 0");
  expect_text_error("contact: {normal_stiffness: 0}\n", 1, "contact.normal_stiffness", "> 0");
  expect_text_error("contact: {vertex_vertex_activation: -1e-6}\n", 1,
                    "contact.vertex_vertex_activation", ">= 0");
  expect_text_error("numerics: {alm_tolerance: 0}\n", 1, "numerics.alm_tolerance", "> 0");
  expect_text_error("numerics: {max_open_close_iterations: 0}\n", 1,
                    "numerics.max_open_close_iterations", ">= 1");
  expect_text_error("output: {every_steps: -1}\n", 1, "output.every_steps", ">= 0");
  expect_text_error("fractures:\n  - {from: [0, 0], to: [1, 0], pressure: -1}\n", 2,
                    "fractures[0].pressure", ">= 0");
  expect_text_error("fractures:\n  - {from: [0, 0], to: [1, 0], segment_length: -1}\n", 2,
                    "fractures[0].segment_length", ">= 0");
}

TEST(CaseFileErrors, EndTimeBelowDt) {
  expect_text_error("time:\n  dt: 2\n  end_time: 1\n", 3, "time.end_time",
                    "must be >= time.dt (got end_time 1, dt 2)");
  // end_time left at its default of 1 s: the dt that was written is at fault.
  expect_text_error("title: x\ntime: {dt: 5}\n", 2, "time.dt", "must be <= time.end_time");
}

TEST(CaseFileErrors, BadEnumListsAllowedValues) {
  expect_text_error("mesh:\n  type: voronoi\n", 2, "mesh.type",
                    "must be one of: structured, delaunay (got 'voronoi')");
  expect_text_error("contact: {method: lagrange}\n", 1, "contact.method", "alm, penalty");
  expect_text_error("materials:\n  - {region: middle}\n", 2, "materials[0].region",
                    "all, inner, outer, box");
  expect_text_error("far_field:\n  sides: [top, front]\n", 2, "far_field.sides[1]",
                    "left, right, bottom, top (got 'front')");
  expect_text_error("far_field:\n  sides: [top, top]\n", 2, "far_field.sides[1]", "duplicate");
}

TEST(CaseFileErrors, RectanglesAndInnerDomain) {
  expect_text_error("domain:\n  outer: {xmin: 1, xmax: 1, ymin: 0, ymax: 1}\n", 2,
                    "domain.outer.xmax", "must be > xmin");
  expect_text_error("domain:\n  outer: {xmin: 0, xmax: 1, ymin: 0}\n", 2, "domain.outer.ymax",
                    "is required");
  // Inner touching the outer boundary is not strictly inside.
  expect_text_error("domain:\n  outer: {xmin: -10, xmax: 10, ymin: -10, ymax: 10}\n"
                    "  inner: {xmin: -10, xmax: 5, ymin: -5, ymax: 5}\n",
                    3, "domain.inner", "must lie strictly inside domain.outer");
  expect_text_error("domain:\n  inner: {xmin: -60, xmax: 5, ymin: -5, ymax: 5}\n", 2,
                    "domain.inner", "strictly inside");
}

TEST(CaseFileErrors, FractureOutsideTheDomain) {
  expect_text_error("fractures:\n  - name: far\n    from: [0, 0]\n    to: [60, 0]\n", 4,
                    "fractures[0].to",
                    "lies outside the domain [-50, 50] x [-50, 50] (got [60, 0])");
  expect_text_error("fractures:\n  - {from: [0, -51], to: [0, 0]}\n", 2, "fractures[0].from",
                    "lies outside the domain");
}

TEST(CaseFileErrors, FractureNeedsTwoDistinctEnds) {
  expect_text_error("fractures:\n  - {name: half, from: [0, 0]}\n", 2, "fractures[0].to",
                    "is required");
  expect_text_error("fractures:\n  - {from: [1, 2], to: [1, 2]}\n", 2, "fractures[0].to",
                    "must differ from 'from'");
}

TEST(CaseFileErrors, PointsOutsideTheDomain) {
  expect_text_error("fixed_points:\n  - [0, 0]\n  - [-50, -50.5]\n", 3, "fixed_points[1]",
                    "lies outside the domain");
  expect_text_error("point_loads:\n  - {at: [70, 0], force: [1, 0]}\n", 2, "point_loads[0].at",
                    "lies outside the domain");
}

TEST(CaseFileErrors, MaterialZones) {
  expect_text_error("materials: []\n", 1, "materials", "at least 1");
  expect_text_error("materials:\n  - {name: a}\n  - {name: b, region: box}\n", 3,
                    "materials[1].region", "needs a 'box'");
  expect_text_error("materials:\n  - {name: a, box: {xmin: 0, xmax: 1, ymin: 0, ymax: 1}}\n", 2,
                    "materials[0].box", "only used with region 'box'");
  expect_text_error("materials:\n  - {name: a, region: inner}\n", 2, "materials[0].region",
                    "needs domain.inner");
  expect_text_error("joints: {breakable_region: inner}\n", 1, "joints.breakable_region", "needs domain.inner");
  expect_text_error("joints: {breakable_region: outer}\n", 1, "joints.breakable_region", "");
  expect_text_error(
      "materials:\n  - name: a\n    region: box\n    box: {xmin: 60, xmax: 70, ymin: 0, ymax: 1}\n",
      4, "materials[0].box", "must overlap the domain");
}

// ---------------------------------------------------------------------------
// Fluid, injections, probes and the coupling numerics

/// A minimal fluid case (one fluid-filled fracture and one injection) with `extra` appended.
std::string fluid_case(const std::string& extra = "") {
  return "fractures:\n"
         "  - {from: [-1, 0], to: [1, 0], initially_open: true, fluid_filled: true}\n"
         "fluid: {}\n"
         "injections:\n"
         "  - {at: [0, 0], mass_rate: 1}\n" +
         extra;
}

TEST(CaseFileFluid, FullFileHasExpectedValues) {
  const CaseConfig c = load_case_file(kCases + "fluid_full.yaml");
  ASSERT_EQ(c.fractures.size(), 3u);
  EXPECT_TRUE(c.fractures[0].initially_open);
  EXPECT_TRUE(c.fractures[0].fluid_filled);
  EXPECT_EQ(c.fractures[0].initial_width_m, 2e-6);
  EXPECT_EQ(c.fractures[0].line, 4);
  EXPECT_TRUE(c.fractures[1].fluid_filled);
  EXPECT_EQ(c.fractures[1].initial_width_m, 0.0);
  EXPECT_EQ(c.fractures[1].line, 5);
  EXPECT_FALSE(c.fractures[2].fluid_filled);

  ASSERT_TRUE(c.fluid.has_value());
  EXPECT_EQ(c.fluid->density_kg_m3, 1050);
  EXPECT_EQ(c.fluid->bulk_modulus_Pa, 2.0e9);
  EXPECT_EQ(c.fluid->viscosity_Pa_s, 0.02);
  EXPECT_EQ(c.fluid->reference_pressure_Pa, 1e5);
  EXPECT_EQ(c.fluid->leak_off_coefficient_m_sqrt_s, 2e-5);

  ASSERT_EQ(c.injections.size(), 2u);
  EXPECT_EQ(c.injections[0].name, "well");
  EXPECT_EQ(c.injections[0].at, Vec2(0, 0));
  EXPECT_EQ(c.injections[0].mass_rate_kg_s, 4.0);
  EXPECT_EQ(c.injections[0].start_time_s, 5);
  EXPECT_EQ(c.injections[0].line, 18);
  EXPECT_EQ(c.injections[1].name, "injection");  // item default
  EXPECT_EQ(c.injections[1].at, Vec2(10, -2));
  EXPECT_EQ(c.injections[1].mass_rate_kg_s, 0.5);
  EXPECT_EQ(c.injections[1].start_time_s, 0);
  EXPECT_EQ(c.injections[1].line, 19);

  ASSERT_EQ(c.probes.size(), 2u);
  EXPECT_EQ(c.probes[0].name, "inlet");
  EXPECT_EQ(c.probes[0].at, Vec2(0, 0));
  EXPECT_EQ(c.probes[0].line, 22);
  EXPECT_EQ(c.probes[1].name, "Tip_2");
  EXPECT_EQ(c.probes[1].at, Vec2(8, 0.5));
  EXPECT_EQ(c.probes[1].line, 23);

  EXPECT_EQ(c.numerics.min_width_main_m, 1e-6);
  EXPECT_EQ(c.numerics.min_width_tip_m, 2e-7);
  EXPECT_EQ(c.numerics.max_closing_fraction, 0.1);
  EXPECT_EQ(c.numerics.coupling_tolerance, 1e-8);
  EXPECT_EQ(c.numerics.max_coupling_iterations, 30);
  EXPECT_EQ(c.numerics.max_step_cuts, 6);
}

TEST(CaseFileFluid, DefaultsWithoutAndWithAFluidSection) {
  const CaseConfig none = load_case_text("", "empty.yaml");
  EXPECT_FALSE(none.fluid.has_value());
  EXPECT_TRUE(none.injections.empty());
  EXPECT_TRUE(none.probes.empty());
  const NumericsConfig n;
  EXPECT_EQ(n.min_width_main_m, 0.5e-6);
  EXPECT_EQ(n.min_width_tip_m, 0.1e-6);
  EXPECT_EQ(n.max_closing_fraction, 0.05);
  EXPECT_EQ(n.coupling_tolerance, 1e-9);
  EXPECT_EQ(n.max_coupling_iterations, 60);
  EXPECT_EQ(n.max_step_cuts, 4);
  EXPECT_EQ(none.numerics.min_width_main_m, n.min_width_main_m);
  EXPECT_EQ(none.numerics.min_width_tip_m, n.min_width_tip_m);
  EXPECT_EQ(none.numerics.max_closing_fraction, n.max_closing_fraction);
  EXPECT_EQ(none.numerics.coupling_tolerance, n.coupling_tolerance);
  EXPECT_EQ(none.numerics.max_coupling_iterations, n.max_coupling_iterations);
  EXPECT_EQ(none.numerics.max_step_cuts, n.max_step_cuts);

  const CaseConfig c = load_case_text(fluid_case(), "fluid.yaml");
  ASSERT_TRUE(c.fluid.has_value());  // `fluid: {}` switches the flow network on
  EXPECT_EQ(c.fluid->density_kg_m3, 1000);
  EXPECT_EQ(c.fluid->bulk_modulus_Pa, 2.2e9);
  EXPECT_EQ(c.fluid->viscosity_Pa_s, 1e-3);
  EXPECT_EQ(c.fluid->reference_pressure_Pa, 0);
  EXPECT_EQ(c.fluid->leak_off_coefficient_m_sqrt_s, 0);
  ASSERT_EQ(c.injections.size(), 1u);
  EXPECT_EQ(c.injections[0].name, "injection");
  EXPECT_EQ(c.injections[0].start_time_s, 0);
  EXPECT_EQ(c.injections[0].line, 5);
  ASSERT_EQ(c.fractures.size(), 1u);
  EXPECT_EQ(c.fractures[0].initial_width_m, 0);
  EXPECT_FALSE(c.fractures[0].pressure_Pa.has_value());

  // A fluid section with only an injection (no fluid-filled fracture) is enough.
  const CaseConfig injected_only = load_case_text(
      "fluid: {viscosity: 0.01}\ninjections: [{at: [0, 0], mass_rate: 2}]\n", "inj.yaml");
  ASSERT_TRUE(injected_only.fluid.has_value());
  EXPECT_EQ(injected_only.fluid->viscosity_Pa_s, 0.01);
  EXPECT_EQ(injected_only.fluid->density_kg_m3, 1000);
}

TEST(CaseFileFluid, ExtendsMergesFluidKeyByKeyAndReplacesLists) {
  const CaseConfig c = load_case_file(kCases + "fluid_child.yaml");
  EXPECT_EQ(c.title, "fluid child");
  ASSERT_TRUE(c.fluid.has_value());
  EXPECT_EQ(c.fluid->viscosity_Pa_s, 0.1);                   // overridden
  EXPECT_EQ(c.fluid->density_kg_m3, 1020);                   // kept from the base
  EXPECT_EQ(c.fluid->bulk_modulus_Pa, 2.5e9);                // kept
  EXPECT_EQ(c.fluid->leak_off_coefficient_m_sqrt_s, 1e-5);   // kept
  EXPECT_EQ(c.fluid->reference_pressure_Pa, 0);              // default, never written
  ASSERT_EQ(c.injections.size(), 1u);                        // list replaced as a whole
  EXPECT_EQ(c.injections[0].name, "c");
  EXPECT_EQ(c.injections[0].mass_rate_kg_s, 3);
  EXPECT_EQ(c.injections[0].line, 6);                        // line in the child file
  ASSERT_EQ(c.probes.size(), 1u);                            // list not in child: kept
  EXPECT_EQ(c.probes[0].name, "p1");
  EXPECT_EQ(c.probes[0].line, 10);                           // line in the base file
  ASSERT_EQ(c.fractures.size(), 1u);
  EXPECT_TRUE(c.fractures[0].fluid_filled);
}

TEST(CaseFileFluid, ExtendsNullRemovesTheInheritedFluid) {
  // Removing the fluid leaves the base's injections without one: the error points at
  // the base file, where `injections` was written.
  const std::string label = kCases + "fluid_virtual.yaml";
  expect_error(error_of_text("extends: fluid_base.yaml\nfluid: null\n", label),
               kCases + "fluid_base.yaml", 6, "injections", "'fluid: null' removed it");
  // With everything fluid removed too, the case is valid and has no fluid.
  const CaseConfig c = load_case_text(
      "extends: fluid_base.yaml\nfluid:\ninjections: []\nprobes: []\n"
      "fractures: [{from: [-1, 0], to: [1, 0], initially_open: true}]\n",
      label);
  EXPECT_FALSE(c.fluid.has_value());
  EXPECT_TRUE(c.injections.empty());
}

TEST(CaseFileFluid, FluidFilledNeedsInitiallyOpen) {
  expect_text_error(
      "fractures:\n  - from: [0, 0]\n    to: [1, 0]\n    fluid_filled: true\n", 4,
      "fractures[0].fluid_filled", "needs initially_open: true");
  expect_text_error(
      "fractures:\n  - {from: [0, 0], to: [1, 0], initially_open: false, fluid_filled: true}\n",
      2, "fractures[0].fluid_filled", "needs initially_open: true");
}

TEST(CaseFileFluid, FluidFilledExcludesPrescribedPressure) {
  expect_text_error(
      "fractures:\n  - from: [0, 0]\n    to: [1, 0]\n    initially_open: true\n"
      "    fluid_filled: true\n    pressure: 1e6\n",
      6, "fractures[0].pressure", "fluid_filled");
}

TEST(CaseFileFluid, InitialWidthNeedsFluidFilled) {
  expect_text_error(
      "fractures:\n  - from: [0, 0]\n    to: [1, 0]\n    initially_open: true\n"
      "    initial_width: 1e-6\n",
      5, "fractures[0].initial_width", "only used with fluid_filled: true (got 1e-6)");
  // initial_width 0 (the default) is allowed on any fracture.
  EXPECT_NO_THROW(load_case_text("fractures: [{from: [0, 0], to: [1, 0], initial_width: 0}]\n",
                                 "ok.yaml"));
}

TEST(CaseFileFluid, FlowNetworkPartsNeedAFluidSection) {
  expect_text_error("title: x\ninjections:\n  - {at: [0, 0], mass_rate: 1}\n", 2, "injections",
                    "needs a 'fluid' section");
  expect_text_error("title: x\nprobes:\n  - {name: a, at: [0, 0]}\n", 2, "probes",
                    "needs a 'fluid' section");
  expect_text_error(
      "fractures:\n  - {from: [0, 0], to: [1, 0]}\n  - from: [0, 1]\n    to: [1, 1]\n"
      "    initially_open: true\n    fluid_filled: true\n",
      6, "fractures[1].fluid_filled", "needs a 'fluid' section");
}

TEST(CaseFileFluid, FluidSectionNeedsASourceOrAFilledFracture) {
  expect_text_error("title: x\nfluid:\n  viscosity: 0.01\n", 2, "fluid",
                    "at least one item in 'injections' or one fracture with fluid_filled");
  // Probes and a prescribed-pressure fracture are not sources.
  expect_text_error(
      "fluid: {}\nprobes: [{name: a, at: [0, 0]}]\n"
      "fractures: [{from: [0, 0], to: [1, 0], initially_open: true, pressure: 1e6}]\n",
      1, "fluid", "at least one item");
}

TEST(CaseFileFluid, MinWidthAtTheTipNotAboveTheMainWidth) {
  expect_text_error(fluid_case("numerics:\n  min_width_tip: 1e-6\n"), 7,
                    "numerics.min_width_tip",
                    "must be <= numerics.min_width_main (got min_width_tip 1e-6, "
                    "min_width_main 5e-7)");
  expect_text_error(fluid_case("numerics: {min_width_main: 2e-6, min_width_tip: 3e-6}\n"), 6,
                    "numerics.min_width_tip", "must be <= numerics.min_width_main");
  // Only the main width written, below the default tip width: the written key is at fault.
  expect_text_error(fluid_case("numerics:\n  min_width_main: 5e-8\n"), 7,
                    "numerics.min_width_main", "min_width_tip was not set");
  EXPECT_NO_THROW(load_case_text(fluid_case("numerics: {min_width_main: 1e-7}\n"), "eq.yaml"));
}

TEST(CaseFileFluid, ProbeNames) {
  expect_text_error(fluid_case("probes:\n  - {name: \"inlet gauge\", at: [0, 0]}\n"), 7,
                    "probes[0].name",
                    "may contain only letters, digits and '_' (got 'inlet gauge')");
  expect_text_error(fluid_case("probes:\n  - {name: p-1, at: [0, 0]}\n"), 7, "probes[0].name",
                    "letters, digits");
  expect_text_error(fluid_case("probes:\n  - {name: \"\", at: [0, 0]}\n"), 7, "probes[0].name",
                    "must not be empty");
  expect_text_error(fluid_case("probes:\n  - {at: [0, 0]}\n"), 7, "probes[0].name",
                    "is required");
  expect_text_error(fluid_case("probes:\n  - {name: a}\n"), 7, "probes[0].at", "is required");
  expect_text_error(fluid_case("probes:\n  - {name: inlet, at: [0, 0]}\n  - name: tip\n"
                               "    at: [1, 0]\n  - name: inlet\n    at: [2, 0]\n"),
                    10, "probes[2].name", "duplicate probe name 'inlet' (also probes[0])");
}

TEST(CaseFileFluid, InjectionItems) {
  expect_text_error(fluid_case("injections: []\n"), 6, "injections", "duplicate key");
  expect_text_error("fluid: {}\ninjections:\n  - {at: [0, 0]}\n", 3, "injections[0].mass_rate",
                    "is required");
  expect_text_error("fluid: {}\ninjections:\n  - {mass_rate: 1}\n", 3, "injections[0].at",
                    "is required");
  expect_text_error("fluid: {}\ninjections:\n  - {at: [0, 0], mass_rate: 0}\n", 3,
                    "injections[0].mass_rate", "must be > 0 (got 0)");
  expect_text_error("fluid: {}\ninjections:\n  - {at: [0, 0], mass_rate: 1, start_time: -1}\n",
                    3, "injections[0].start_time", "must be >= 0 (got -1)");
  expect_text_error("fluid: {}\ninjections:\n  - {at: [0, 0], mass_rate: 1, rate: 1}\n", 3,
                    "injections[0].rate", "unknown key; allowed keys: name, at, mass_rate, "
                                          "start_time");
  expect_text_error("fluid: {}\ninjections:\n  - {at: [0, 0], mass_rate: 1}\n"
                    "  - {at: [0, 60], mass_rate: 1}\n",
                    4, "injections[1].at", "lies outside the domain");
  expect_text_error(fluid_case("probes:\n  - {name: far, at: [-51, 0]}\n"), 7, "probes[0].at",
                    "lies outside the domain");
}

TEST(CaseFileFluid, FluidAndNumericsRanges) {
  expect_text_error("fluid:\n  density: 0\n", 2, "fluid.density", "must be > 0 (got 0)");
  expect_text_error("fluid:\n  bulk_modulus: -1\n", 2, "fluid.bulk_modulus", "> 0");
  expect_text_error("fluid:\n  viscosity: 0\n", 2, "fluid.viscosity", "> 0");
  expect_text_error("fluid:\n  leak_off_coefficient: -2e-5\n", 2, "fluid.leak_off_coefficient",
                    "must be >= 0 (got -2e-5)");
  expect_text_error("fluid:\n  reference_pressure: abc\n", 2, "fluid.reference_pressure",
                    "expected a finite number");
  expect_text_error("fluid:\n  colour: red\n", 2, "fluid.colour",
                    "allowed keys: density, bulk_modulus, viscosity, reference_pressure, "
                    "leak_off_coefficient");
  expect_text_error("fluid: water\n", 1, "fluid", "expected a map");
  expect_text_error("fractures:\n  - {from: [0, 0], to: [1, 0], initial_width: -1}\n", 2,
                    "fractures[0].initial_width", ">= 0");
  expect_text_error("fractures:\n  - {from: [0, 0], to: [1, 0], fluid_filled: yes}\n", 2,
                    "fractures[0].fluid_filled", "expected a boolean");
  expect_text_error("numerics:\n  min_width_main: 0\n", 2, "numerics.min_width_main",
                    "must be > 0 (got 0)");
  expect_text_error("numerics:\n  min_width_tip: -1e-7\n", 2, "numerics.min_width_tip", "> 0");
  expect_text_error("numerics:\n  max_closing_fraction: 0\n", 2,
                    "numerics.max_closing_fraction", "must be in (0, 1) (got 0)");
  expect_text_error("numerics:\n  max_closing_fraction: 1\n", 2,
                    "numerics.max_closing_fraction", "must be in (0, 1) (got 1)");
  expect_text_error("numerics:\n  coupling_tolerance: 0\n", 2, "numerics.coupling_tolerance",
                    "> 0");
  expect_text_error("numerics:\n  max_coupling_iterations: 0\n", 2,
                    "numerics.max_coupling_iterations", ">= 1");
  expect_text_error("numerics:\n  max_coupling_iterations: 1.5\n", 2,
                    "numerics.max_coupling_iterations", "expected an integer");
  expect_text_error("numerics:\n  max_step_cuts: -1\n", 2, "numerics.max_step_cuts", ">= 0");
  EXPECT_NO_THROW(load_case_text("numerics: {max_step_cuts: 0}\n", "cuts.yaml"));
}

TEST(CaseFileFluid, ErrorInAnExtendedFileNamesThatFile) {
  // The child's fluid override is bad: the error names the child, not the base.
  const std::string label = kCases + "fluid_virtual.yaml";
  expect_error(error_of_text("extends: fluid_base.yaml\nfluid:\n  viscosity: -1\n", label),
               label, 3, "fluid.viscosity", "> 0");
}

// ---------------------------------------------------------------------------
// Documentation generated from the key tables

TEST(CaseFileDocs, MatchesGeneratedReference) {
  const std::string path = std::string(HFDDA_TEST_DATA_DIR) + "/../../../docs/case_file.md";
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  const std::string generated = case_file_reference_markdown();
  if (text.str() != generated) {
    std::ofstream("case_file.md.generated") << generated;
    FAIL() << "docs/case_file.md differs from case_file_reference_markdown(); the generated "
              "text is in "
           << (std::filesystem::current_path() / "case_file.md.generated").string()
           << ": copy it to " << path;
  }
}

TEST(CaseFileDocs, ReferenceNamesEveryKeyOfTheExampleFile) {
  const std::string reference = case_file_reference_markdown();
  for (const char* key :
       {"`extends`", "`outer`", "`inner`", "`cell_size`", "`outer_growth`", "`split`",
        "`max_area_inner`", "`max_area_outer`", "`min_angle`", "`region`", "`box`",
        "`youngs_modulus`", "`poissons_ratio`", "`density`", "`tensile_strength`",
        "`cohesion`", "`friction_angle`", "`breakable`", "`segment_length`",
        "`initially_open`", "`natural`", "`pressure`", "`sides`", "`at`", "`force`",
        "`body_force`", "`fixed_points`", "`method`", "`normal_stiffness`",
        "`vertex_vertex_activation`", "`fixed_point_stiffness`", "`analysis`",
        "`alm_tolerance`", "`tie_tolerance`", "`shear_failure_of_intact_joints`", "`dt`",
        "`end_time`", "`every_steps`", "`vtu`"})
    EXPECT_NE(reference.find(key), std::string::npos) << key;
}

TEST(CaseFileDocs, ReferenceNamesEveryFluidKey) {
  const std::string reference = case_file_reference_markdown();
  for (const char* key :
       {"## `fluid`", "## `injections[]` items", "## `probes[]` items", "`fluid_filled`",
        "`initial_width`", "`bulk_modulus`", "`viscosity`", "`reference_pressure`",
        "`leak_off_coefficient`", "`mass_rate`", "`start_time`", "`min_width_main`",
        "`min_width_tip`", "`max_closing_fraction`", "`coupling_tolerance`",
        "`max_coupling_iterations`", "`max_step_cuts`", "NOTES erratum 4",
        "`numerics.min_width_tip` <= `numerics.min_width_main`"})
    EXPECT_NE(reference.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace hfdda::io
