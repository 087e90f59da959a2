// Case file -> model: choices made when the model is built from a case.

#include <gtest/gtest.h>

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
