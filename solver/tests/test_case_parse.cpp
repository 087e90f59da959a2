// Case-file loader on valid files: every value read, defaults kept where a key is absent.

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "test_case_support.hpp"

namespace hfdda::io {
namespace {

using namespace case_test;

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

TEST(CaseFileParse, TitleOnlyGivesStructDefaults) {
  const CaseConfig c = load_case_text("title: defaults\n", "empty.yaml");
  const CaseConfig d;
  EXPECT_EQ(c.file, "empty.yaml");
  EXPECT_EQ(c.mesh_file, "empty.yaml");
  EXPECT_EQ(c.mesh.line, 0);
  EXPECT_EQ(c.title, "defaults");
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

}  // namespace
}  // namespace hfdda::io
