#include <gtest/gtest.h>

#include "core/geometry.hpp"

namespace hfdda {
namespace {

TEST(PolygonMoments, UnitSquareAboutCentroid) {
  const std::vector<Vec2> square{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  const PolygonMoments m = polygon_moments(square);
  EXPECT_DOUBLE_EQ(m.area, 4.0);
  EXPECT_DOUBLE_EQ(m.centroid.x(), 1.0);
  EXPECT_DOUBLE_EQ(m.centroid.y(), 1.0);
  EXPECT_NEAR(m.sxx, 2.0 * 8.0 / 12.0, 1e-12);  // b h^3 / 12
  EXPECT_NEAR(m.syy, 2.0 * 8.0 / 12.0, 1e-12);
  EXPECT_NEAR(m.sxy, 0.0, 1e-12);
}

TEST(PolygonMoments, TriangleProductMoment) {
  // Right triangle (0,0),(1,0),(0,1): central Ixy = -A/36 * b*h ... = -1/72.
  const std::vector<Vec2> tri{{0, 0}, {1, 0}, {0, 1}};
  const PolygonMoments m = polygon_moments(tri);
  EXPECT_NEAR(m.area, 0.5, 1e-15);
  EXPECT_NEAR(m.sxx, 1.0 / 36.0, 1e-14);
  EXPECT_NEAR(m.sxy, -1.0 / 72.0, 1e-14);
}

}  // namespace
}  // namespace hfdda
