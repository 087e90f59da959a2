// Case-file errors: the file, line, dotted key and rule of every kind of bad input.

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "test_case_support.hpp"

namespace hfdda::io {
namespace {

using namespace case_test;

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

TEST(CaseFileErrors, StopAtTheEdgeNeedsAnInnerDomainAndFluid) {
  expect_text_error("time: {dt: 1, end_time: 2, stop_when: fluid_at_edge}\nfluid: {}\n", 1, "time.stop_when",
                    "needs domain.inner");
  expect_text_error("domain: {inner: {xmin: -1, xmax: 1, ymin: -1, ymax: 1}}\n"
                    "time: {dt: 1, end_time: 2, stop_when: fluid_at_edge}\n",
                    2, "time.stop_when", "needs a `fluid` section");
  expect_text_error("time: {dt: 1, end_time: 2, stop_when: at_edge}\n", 1, "time.stop_when", "fluid_at_edge");
}

TEST(CaseFileErrors, VentedEdgeNeedsAnInnerDomain) {
  expect_text_error("fluid: {viscosity: 0.02,\n  edge: vented}\n", 2, "fluid.edge", "needs domain.inner");
  expect_text_error("fluid: {edge: open}\n", 1, "fluid.edge", "sealed");
}

TEST(CaseFileErrors, IntactStiffnessRatioKeepsTheMatrixDigits) {
  expect_text_error("contact: {two_tier: true,\n  intact_stiffness_ratio: 0.5}\n", 2, "contact.intact_stiffness_ratio",
                    "in [1, 10000]");
  expect_text_error("contact: {two_tier: true, normal_stiffness: 30,\n  intact_stiffness_ratio: 1e5}\n", 2,
                    "contact.intact_stiffness_ratio", "in [1, 10000]");
  expect_text_error("contact: {two_tier: true, shear_stiffness: 1000,\n  intact_stiffness_ratio: 2000}\n", 2,
                    "contact.intact_stiffness_ratio", "at most 1e6");
  EXPECT_NO_THROW(load_case_text("contact: {two_tier: true, normal_stiffness: 100, intact_stiffness_ratio: 1e4}\n",
                                 "ratio.yaml"));
  EXPECT_NO_THROW(load_case_text("contact: {two_tier: false, normal_stiffness: 1000, intact_stiffness_ratio: 1e4}\n",
                                 "ratio.yaml"));
}

TEST(CaseFileErrors, ConvergedContactResponseNeedsTheAugmentedLagrangian) {
  expect_text_error("contact: {method: penalty}\nnumerics: {aperture_response: converged_contacts}\n", 2,
                    "numerics.aperture_response", "needs contact.method: alm");
  expect_text_error("contact: {two_tier: true, normal_stiffness: 30, intact_stiffness_ratio: 1000}\n"
                    "numerics: {aperture_response: converged_contacts}\n",
                    2, "numerics.aperture_response", "at most 1e6");
  expect_text_error("numerics: {aperture_response: converged}\n", 1, "numerics.aperture_response",
                    "fixed_multipliers");
  expect_text_error("numerics: {flow_jacobian: krylov,\n  aperture_response: converged_contacts}\n", 2,
                    "numerics.aperture_response", "dense flow Jacobian only");
  // auto (the default) stays dense with the converged contacts' response.
  EXPECT_NO_THROW(load_case_text("numerics: {flow_jacobian: auto, aperture_response: converged_contacts}\n",
                                 "response.yaml"));
  EXPECT_NO_THROW(load_case_text("contact: {two_tier: true, normal_stiffness: 30}\n"
                                 "numerics: {aperture_response: converged_contacts, fluid_load: lumped}\n",
                                 "response.yaml"));
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
                    "must be in [1000, 1e13] (got 0)");
  expect_text_error("materials:\n  - name: a\n  - name: b\n    youngs_modulus: -1\n", 4,
                    "materials[1].youngs_modulus", "must be in [1000, 1e13] (got -1)");
}

TEST(CaseFileErrors, PoissonsRatioInHalfOpenInterval) {
  expect_text_error("materials:\n  - {poissons_ratio: 0.5}\n", 2, "materials[0].poissons_ratio",
                    "must be in [0, 0.5) (got 0.5)");
  expect_text_error("materials:\n  - {poissons_ratio: -0.1}\n", 2,
                    "materials[0].poissons_ratio", "must be in [0, 0.5) (got -0.1)");
}

TEST(CaseFileErrors, OtherRanges) {
  expect_text_error("materials:\n  - {density: 0}\n", 2, "materials[0].density", "in (0, 1e5]");
  expect_text_error("time:\n  dt: 0\n", 2, "time.dt", "must be in (0, 1e10] (got 0)");
  expect_text_error("time:\n  dt: -1\n", 2, "time.dt", "must be in (0, 1e10] (got -1)");
  expect_text_error("mesh: {cell_size: -1}\n", 1, "mesh.cell_size", "must be > 0 (got -1)");
  expect_text_error("mesh: {outer_growth: 0.9}\n", 1, "mesh.outer_growth", "in [1, 10]");
  expect_text_error("mesh: {min_angle: 35}\n", 1, "mesh.min_angle", "in (0, 30]");
  expect_text_error("mesh: {max_area_outer: 0}\n", 1, "mesh.max_area_outer", "> 0");
  expect_text_error("joints: {friction_angle: 90}\n", 1, "joints.friction_angle", "[0, 90)");
  expect_text_error("joints: {tensile_strength: -1}\n", 1, "joints.tensile_strength", "in [0, 1e13]");
  expect_text_error("contact: {normal_stiffness: 0}\n", 1, "contact.normal_stiffness", "in [1, 1e6]");
  expect_text_error("contact: {vertex_vertex_activation: -1e-6}\n", 1,
                    "contact.vertex_vertex_activation", ">= 0");
  expect_text_error("numerics: {alm_tolerance: 0}\n", 1, "numerics.alm_tolerance", "in (0, 1]");
  expect_text_error("numerics: {max_open_close_iterations: 0}\n", 1,
                    "numerics.max_open_close_iterations", "in [1, 1e6]");
  expect_text_error("output: {every_steps: -1}\n", 1, "output.every_steps", "in [0, 1e7]");
  expect_text_error("fractures:\n  - {from: [0, 0], to: [1, 0], pressure: -1}\n", 2,
                    "fractures[0].pressure", "in [0, 1e10]");
  expect_text_error("fractures:\n  - {from: [0, 0], to: [1, 0], segment_length: -1}\n", 2,
                    "fractures[0].segment_length", ">= 0");
}

TEST(CaseFileErrors, EndTimeBelowDt) {
  expect_text_error("time:\n  dt: 2\n  end_time: 1\n", 3, "time.end_time",
                    "must be >= time.dt (got end_time 1, dt 2)");
  // end_time left at its default of 1 s: the dt that was written is at fault.
  expect_text_error("title: x\ntime: {dt: 5}\n", 2, "time.dt", "must be <= time.end_time");
}

TEST(CaseFileErrors, FractureCriterionAndItsToughness) {
  expect_text_error("fracture:\n  criterion: toughness\n", 2, "fracture.criterion",
                    "must be one of: strength, energy_release_rate (got 'toughness')");
  expect_text_error("fracture: {criterion: energy_release_rate}\n", 1, "fracture.fracture_toughness",
                    "is required with criterion: energy_release_rate");
  expect_text_error("fracture:\n  fracture_toughness: 1.0e6\n", 2, "fracture.fracture_toughness",
                    "is only used with criterion: energy_release_rate");
  expect_text_error("fracture: {criterion: strength,\n  mode2_toughness: 1.0e6}\n", 2, "fracture.mode2_toughness",
                    "is only used with criterion: energy_release_rate");
  expect_text_error("fracture: {criterion: energy_release_rate, fracture_toughness: 0}\n", 1,
                    "fracture.fracture_toughness", "must be in (0, 1e13]");
  expect_text_error("fracture: {criterion: energy_release_rate, fracture_toughness: 1e6, toughness2: 1e6}\n", 1,
                    "fracture.toughness2", "mode2_toughness");
  const CaseConfig c =
      load_case_text("fracture: {criterion: energy_release_rate, fracture_toughness: 0.886e6}\n", "erc.yaml");
  EXPECT_EQ(c.fracture.criterion, FailureCriterionKind::energy_release_rate);
  EXPECT_EQ(c.fracture.fracture_toughness_Pa_sqrt_m, std::optional<double>(0.886e6));
  EXPECT_FALSE(c.fracture.mode2_toughness_Pa_sqrt_m.has_value());
  EXPECT_EQ(load_case_text("title: default\n", "default.yaml").fracture.criterion, FailureCriterionKind::strength);
  // The crack closure: a choice of the toughness criterion only, extrapolated by default.
  EXPECT_EQ(c.fracture.crack_closure, CrackClosureKind::extrapolated);
  expect_text_error("fracture: {criterion: energy_release_rate, fracture_toughness: 1e6,\n  crack_closure: two_joints}\n",
                    2, "fracture.crack_closure", "must be one of: one_joint, extrapolated (got 'two_joints')");
  expect_text_error("fracture:\n  crack_closure: one_joint\n", 2, "fracture.crack_closure",
                    "is only used with criterion: energy_release_rate");
  EXPECT_EQ(load_case_text("fracture: {criterion: energy_release_rate, fracture_toughness: 1e6, crack_closure: one_joint}\n",
                           "one.yaml")
                .fracture.crack_closure,
            CrackClosureKind::one_joint);
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

}  // namespace
}  // namespace hfdda::io
