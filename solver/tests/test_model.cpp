// Case file -> model: choices made when the model is built from a case.

#include <gtest/gtest.h>

#include <cmath>

#include "io/case_config.hpp"
#include "simulation/model.hpp"

namespace hfdda {
namespace {

TEST(ModelSetup, BreakableRegionInnerKeepsOuterAndBoundaryJointsIntact) {
  // 2 m cells; the inner domain is the central 4 x 4 m. Only joints with both blocks
  // inside may break, not those on the inner boundary; a fracture's own
  // `breakable: true` still wins (here on a piece of that boundary).
  const char* text = R"(
title: "breakable region"
domain:
  outer: {xmin: -6, xmax: 6, ymin: -6, ymax: 6}
  inner: {xmin: -2, xmax: 2, ymin: -2, ymax: 2}
mesh: {type: structured, cell_size: 2.0, split: four}
joints: {breakable: true, breakable_region: inner}
fractures:
  - {name: path, from: [-2, 2], to: [0, 2], breakable: true}
time: {dt: 1.0, end_time: 1.0}
)";
  const simulation::Model model = simulation::build_model(io::load_case_text(text, "region.yaml"));
  const mesh::Mesh& m = model.system->mesh();
  int breakable = 0, inner = 0;
  for (const auto& joint : m.joints) {
    const Vec2 mid = 0.5 * (m.points[joint.point_p] + m.points[joint.point_q]);
    const bool strictly_inner = std::abs(mid.x()) < 2.0 - 1e-9 && std::abs(mid.y()) < 2.0 - 1e-9;
    const bool on_path = std::abs(mid.y() - 2.0) < 1e-9 && mid.x() > -2.0 && mid.x() < 0.0;
    if (strictly_inner) ++inner;
    EXPECT_EQ(joint.properties.breakable, strictly_inner || on_path)
        << "joint at (" << mid.x() << ", " << mid.y() << ")";
    breakable += joint.properties.breakable;
  }
  // Four cells of four triangles: 4 x 4 internal joints + 4 shared cell edges.
  EXPECT_EQ(inner, 20);
  EXPECT_EQ(breakable, 21);
}

}  // namespace
}  // namespace hfdda

namespace hfdda {
namespace {

TEST(ModelSetup, DelaunayWithoutInnerRectangleUsesMaxAreaInnerEverywhere) {
  // docs/case_file.md: max_area_inner applies everywhere without an inner rectangle (the
  // mesher used max_area_outer; found by the fuzzer: 16 blocks instead of > 1000).
  const std::string text =
      "domain: {outer: {xmin: 0, xmax: 10, ymin: 0, ymax: 10}}\n"
      "mesh: {type: delaunay, max_area_inner: 0.1, max_area_outer: 50}\n"
      "fixed_points: [[0, 0], [10, 0]]\n";
  const mesh::Mesh m = simulation::build_case_mesh(io::load_case_text(text, "no_inner.yaml"));
  EXPECT_GE(m.blocks.size(), 1000u);
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const auto& p = m.blocks[b].points;
    const Vec2 u = m.points[p[1]] - m.points[p[0]], v = m.points[p[2]] - m.points[p[0]];
    ASSERT_LE(0.5 * std::abs(u.x() * v.y() - u.y() * v.x()), 0.1 * (1 + 1e-12)) << "block " << b;
  }
}

}  // namespace
}  // namespace hfdda
