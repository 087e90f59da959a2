#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <set>
#include <vector>

#include "core/errors.hpp"
#include "core/geometry.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::mesh {
namespace {

std::vector<Vec2> corners(const Mesh& m, const Block& b) {
  std::vector<Vec2> c;
  for (int id : b.points) c.push_back(m.points[id]);
  return c;
}

double block_area(const Mesh& m, const Block& b) { return polygon_moments(corners(m, b)).area; }

double total_area(const Mesh& m) {
  double a = 0.0;
  for (const Block& b : m.blocks) a += block_area(m, b);
  return a;
}

double smallest_block_area(const Mesh& m) {
  double a = INFINITY;
  for (const Block& b : m.blocks) a = std::min(a, block_area(m, b));
  return a;
}

/// Sorted distinct x coordinates of the mesh points on y = y0.
std::vector<double> grid_lines_x(const Mesh& m, double y0) {
  std::set<double> xs;
  for (const Vec2& p : m.points)
    if (p.y() == y0) xs.insert(p.x());
  return {xs.begin(), xs.end()};
}

bool has_point(const Mesh& m, const Vec2& p) {
  return std::any_of(m.points.begin(), m.points.end(), [&](const Vec2& q) { return q == p; });
}

double joints_length(const Mesh& m, const std::vector<int>& ids) {
  double l = 0.0;
  for (int j : ids) l += (m.points[m.joints[j].point_q] - m.points[m.joints[j].point_p]).norm();
  return l;
}

StructuredMeshSpec uniform_spec(int nx, int ny, CellSplit split) {
  StructuredMeshSpec s;
  s.outer = {0.0, 0.5 * nx, -0.25 * ny, 0.25 * ny};  // 0.5 m cells
  s.cell_size_m = 0.5;
  s.split = split;
  return s;
}

TEST(MeshStructured, QuadCountsAreaAndJoints) {
  const int nx = 7, ny = 5;
  Mesh m = build_structured_mesh(uniform_spec(nx, ny, CellSplit::none));
  EXPECT_EQ(m.blocks.size(), std::size_t(nx * ny));
  EXPECT_EQ(m.points.size(), std::size_t((nx + 1) * (ny + 1)));
  EXPECT_TRUE(m.joints.empty());  // topology is the caller's job
  EXPECT_NEAR(total_area(m), 3.5 * 2.5, 1e-12);
  EXPECT_NEAR(smallest_block_area(m), 0.25, 1e-12);  // every block CCW and full size
  build_topology(m, JointProperties{});
  EXPECT_EQ(m.joints.size(), std::size_t((nx - 1) * ny + nx * (ny - 1)));
  EXPECT_EQ(m.boundary_edges.size(), std::size_t(2 * (nx + ny)));
}

TEST(MeshStructured, TwoTrianglesPerCellUnionJack) {
  const int nx = 6, ny = 4;
  Mesh m = build_structured_mesh(uniform_spec(nx, ny, CellSplit::two));
  EXPECT_EQ(m.blocks.size(), std::size_t(2 * nx * ny));
  EXPECT_EQ(m.points.size(), std::size_t((nx + 1) * (ny + 1)));
  EXPECT_NEAR(total_area(m), 3.0 * 2.0, 1e-12);
  EXPECT_NEAR(smallest_block_area(m), 0.125, 1e-12);
  build_topology(m, JointProperties{});
  // Grid joints plus one diagonal per cell.
  EXPECT_EQ(m.joints.size(), std::size_t((nx - 1) * ny + nx * (ny - 1) + nx * ny));
  // Neighbouring cells use opposite diagonals: count rising ones (corner 0 -> corner 2 of a cell).
  int rising = 0;
  for (std::size_t b = 0; b < m.blocks.size(); b += 2) {
    const Vec2 c0 = m.points[m.blocks[b].points[0]], c1 = m.points[m.blocks[b].points[2]];
    rising += (c1 - c0).x() > 0 && (c1 - c0).y() > 0;
  }
  EXPECT_EQ(rising, nx * ny / 2);
  // The domain's centre vertex is a star: 8 edges meet there.
  const int centre = nearest_point(m, Vec2(1.5, 0.0));
  ASSERT_EQ(m.points[centre], Vec2(1.5, 0.0));
  int degree = 0;
  for (const Joint& j : m.joints) degree += j.point_p == centre || j.point_q == centre;
  EXPECT_EQ(degree, 8);
}

TEST(MeshStructured, FourTrianglesPerCell) {
  const int nx = 3, ny = 4;
  Mesh m = build_structured_mesh(uniform_spec(nx, ny, CellSplit::four));
  EXPECT_EQ(m.blocks.size(), std::size_t(4 * nx * ny));
  EXPECT_EQ(m.points.size(), std::size_t((nx + 1) * (ny + 1) + nx * ny));
  EXPECT_NEAR(total_area(m), 1.5 * 2.0, 1e-12);
  EXPECT_NEAR(smallest_block_area(m), 0.0625, 1e-12);
  build_topology(m, JointProperties{});
  EXPECT_EQ(m.joints.size(), std::size_t((nx - 1) * ny + nx * (ny - 1) + 4 * nx * ny));
}

TEST(MeshStructured, RejectsSizeNotMultipleOfCell) {
  StructuredMeshSpec s = uniform_spec(4, 4, CellSplit::two);
  s.outer.xmax += 0.2;
  EXPECT_THROW(build_structured_mesh(s), ModelError);
  s = uniform_spec(4, 4, CellSplit::two);
  s.has_inner = true;
  s.inner = {0.5, 1.25, -0.5, 0.5};  // 0.75 m wide
  EXPECT_THROW(build_structured_mesh(s), ModelError);
  s.inner = {0.5, 1.5, -0.5, 0.5};
  EXPECT_NO_THROW(build_structured_mesh(s));
  s.outer_growth = 0.9;
  EXPECT_THROW(build_structured_mesh(s), ModelError);
}

TEST(MeshStructured, GradedGridThroughOriginAndInnerCorners) {
  StructuredMeshSpec s;
  s.outer = {-100.0, 100.0, -60.0, 60.0};
  s.has_inner = true;
  s.inner = {-10.0, 10.0, -4.0, 4.0};
  s.cell_size_m = 0.1;
  s.outer_growth = 1.2;
  s.split = CellSplit::two;
  Mesh m = build_structured_mesh(s);
  EXPECT_NEAR(total_area(m), 200.0 * 120.0, 1e-9 * 200.0 * 120.0);
  EXPECT_GT(smallest_block_area(m), 0.0);
  for (const Vec2& c : {Vec2(-10, -4), Vec2(10, -4), Vec2(10, 4), Vec2(-10, 4), Vec2(0, 0), Vec2(0, -60),
                        Vec2(-100, 0), Vec2(100, 60)})
    EXPECT_TRUE(has_point(m, c)) << c.transpose();

  const std::vector<double> xs = grid_lines_x(m, 0.0);
  ASSERT_EQ(xs.front(), -100.0);
  ASSERT_EQ(xs.back(), 100.0);
  // Mirror symmetry about x = 0, exactly.
  for (std::size_t i = 0; i < xs.size(); ++i) EXPECT_EQ(xs[i], -xs[xs.size() - 1 - i]);
  // Uniform inside, growing by 1.2 outside (the last cell may absorb a sliver).
  std::vector<double> right;
  for (double x : xs)
    if (x >= 10.0) right.push_back(x);
  ASSERT_GE(right.size(), 4u);
  EXPECT_NEAR(right[1] - right[0], 0.12, 1e-12);
  for (std::size_t k = 1; k + 2 < right.size(); ++k)
    EXPECT_NEAR((right[k + 1] - right[k]) / (right[k] - right[k - 1]), 1.2, 1e-9);
  const std::size_t n = right.size();
  EXPECT_GT(right[n - 1] - right[n - 2], 0.5 * (right[n - 2] - right[n - 3]));
  int inner_lines = 0;
  for (double x : xs)
    if (x > -10.0 && x < 10.0) {
      ++inner_lines;
      EXPECT_NEAR(x / 0.1, std::round(x / 0.1), 1e-9);
    }
  EXPECT_EQ(inner_lines, 199);

  build_topology(m, JointProperties{});
  // The x axis is made of joints: 200 inner ones of 0.1 m between x = -10 and 10.
  const std::vector<int> on_axis = joints_on_segment(m, Vec2(-10, 0), Vec2(10, 0), 1e-9);
  EXPECT_EQ(on_axis.size(), 200u);
  EXPECT_NEAR(joints_length(m, on_axis), 20.0, 1e-9);
}

TEST(MeshStructured, OneSidedInnerAndSliverMerge) {
  StructuredMeshSpec s;
  s.outer = {0.0, 3.05, 0.0, 2.0};  // 1.05 m beyond the inner rectangle on the right only
  s.has_inner = true;
  s.inner = {0.0, 2.0, 0.0, 2.0};
  s.cell_size_m = 0.5;
  s.outer_growth = 1.0;
  s.split = CellSplit::none;
  Mesh m = build_structured_mesh(s);
  // Right of x = 2: 0.5, 0.5 and a 0.05 sliver merged -> 0.5, 0.55.
  EXPECT_EQ(grid_lines_x(m, 0.0), (std::vector<double>{0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.05}));
  EXPECT_NEAR(total_area(m), 3.05 * 2.0, 1e-12);
}

TEST(MeshStructured, LargeBuildIsFast) {
  StructuredMeshSpec s;
  s.outer = {-50.0, 50.0, -50.0, 50.0};
  s.cell_size_m = 0.25;  // 400 x 400 cells, 320k triangles
  s.split = CellSplit::two;
  const auto t0 = std::chrono::steady_clock::now();
  Mesh m = build_structured_mesh(s);
  build_topology(m, JointProperties{});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(m.blocks.size(), 320000u);
  EXPECT_EQ(m.joints.size(), std::size_t(2 * 399 * 400 + 400 * 400));
  // Generous bound: a debug or sanitizer build is several times slower than Release.
  EXPECT_LT(seconds, 10.0);
}

DelaunayMeshSpec delaunay_spec() {
  DelaunayMeshSpec s;
  s.outer = {-40.0, 40.0, -30.0, 30.0};
  s.has_inner = true;
  s.inner = {-12.0, 12.0, -6.0, 6.0};
  s.max_area_inner_m2 = 0.5;
  s.max_area_outer_m2 = 20.0;
  s.min_angle_deg = 25.0;
  s.constraints.push_back({"initial fracture", Vec2(-10, 0), Vec2(10, 0), 1.0});
  return s;
}

TEST(MeshDelaunay, AreaRegionsAngleAndFracture) {
  const DelaunayMeshSpec s = delaunay_spec();
  Mesh m = build_delaunay_mesh(s);
  EXPECT_NEAR(total_area(m), 80.0 * 60.0, 1e-9 * 80.0 * 60.0);
  double worst_sine = 1.0;
  for (const Block& b : m.blocks) {
    ASSERT_EQ(b.points.size(), 3u);
    const std::vector<Vec2> c = corners(m, b);
    const PolygonMoments pm = polygon_moments(c);
    ASSERT_GT(pm.area, 0.0);  // counter-clockwise
    const bool inside = s.inner.contains(pm.centroid);
    EXPECT_LE(pm.area, (inside ? s.max_area_inner_m2 : s.max_area_outer_m2) * (1 + 1e-12));
    for (int i = 0; i < 3; ++i) {
      const Vec2 u = c[(i + 1) % 3] - c[i], v = c[(i + 2) % 3] - c[i];
      worst_sine = std::min(worst_sine, std::abs(u.x() * v.y() - u.y() * v.x()) / (u.norm() * v.norm()));
    }
  }
  EXPECT_GE(worst_sine, std::sin(25.0 * std::numbers::pi / 180.0) - 1e-9);
  // The fracture's split points are mesh points.
  for (int k = -10; k <= 10; ++k) EXPECT_TRUE(has_point(m, Vec2(k, 0.0))) << k;

  build_topology(m, JointProperties{});
  const std::vector<int> fracture = joints_on_segment(m, Vec2(-10, 0), Vec2(10, 0), 1e-9);
  EXPECT_GE(fracture.size(), 20u);
  EXPECT_NEAR(joints_length(m, fracture), 20.0, 1e-9);
}

TEST(MeshDelaunay, CrossingFeaturesAndUniformDomain) {
  DelaunayMeshSpec s;
  s.outer = {0.0, 10.0, 0.0, 10.0};
  s.max_area_outer_m2 = 0.5;
  s.min_angle_deg = 20.0;
  s.constraints.push_back({"a", Vec2(1, 5), Vec2(9, 5), 0.5});
  s.constraints.push_back({"b", Vec2(2, 2), Vec2(8, 8), 0.0});  // crosses a at (5, 5)
  Mesh m = build_delaunay_mesh(s);
  EXPECT_NEAR(total_area(m), 100.0, 1e-9 * 100.0);
  for (const Block& b : m.blocks) EXPECT_LE(block_area(m, b), 0.5 * (1 + 1e-12));
  EXPECT_TRUE(has_point(m, Vec2(5, 5)));
  build_topology(m, JointProperties{});
  EXPECT_NEAR(joints_length(m, joints_on_segment(m, Vec2(1, 5), Vec2(9, 5), 1e-9)), 8.0, 1e-9);
  EXPECT_NEAR(joints_length(m, joints_on_segment(m, Vec2(2, 2), Vec2(8, 8), 1e-9)), 6.0 * std::sqrt(2.0),
              1e-9);
}

TEST(MeshDelaunay, FeaturesARoundingErrorApartAreJoinedAtOnePoint) {
  // Found by the case-file fuzzer (CGAL's refinement crashed on it, then it was refused):
  // a crack a rounding error off a crossing natural fracture now shares one mesh point
  // with it, where the two cross.
  DelaunayMeshSpec s;
  s.outer = {-8.0, 8.0, -8.0, 8.0};
  s.max_area_outer_m2 = 2.0;
  s.constraints.push_back({"crack", Vec2(-1.5, 1e-16), Vec2(1.5, 0), 0.5});
  s.constraints.push_back({"natural", Vec2(0, -1.5), Vec2(2, 1.5), 0.75});
  Mesh m = build_delaunay_mesh(s);
  build_topology(m, JointProperties{});
  const Vec2 crossing(1.0, 0.0);  // y = 0 meets the line through (0, -1.5) and (2, 1.5)
  EXPECT_LT((m.points[nearest_point(m, crossing)] - crossing).norm(), 1e-12);
  double crack = 0.0, natural = 0.0;
  for (int j : joints_on_segment(m, Vec2(-1.5, 0), Vec2(1.5, 0), 1e-9))
    crack += (m.points[m.joints[j].point_q] - m.points[m.joints[j].point_p]).norm();
  for (int j : joints_on_segment(m, Vec2(0, -1.5), Vec2(2, 1.5), 1e-9))
    natural += (m.points[m.joints[j].point_q] - m.points[m.joints[j].point_p]).norm();
  EXPECT_NEAR(crack, 3.0, 1e-9);
  EXPECT_NEAR(natural, std::hypot(2.0, 3.0), 1e-9);
  // A point exactly on the other feature, a shared end point and a clear gap all mesh.
  s.constraints = {{"crack", Vec2(-1.5, 0), Vec2(1.5, 0), 0.5}, {"natural", Vec2(0, -1.5), Vec2(2, 1.5), 0.75}};
  EXPECT_NO_THROW(build_delaunay_mesh(s));
  s.constraints = {{"a", Vec2(-2, 0), Vec2(0, 0), 0.5}, {"b", Vec2(0, 0), Vec2(1, 2), 0.5}};
  EXPECT_NO_THROW(build_delaunay_mesh(s));
  s.constraints = {{"a", Vec2(-2, 0), Vec2(0, 0), 0.5}, {"b", Vec2(0, 1e-3), Vec2(0, 2), 0.5}};
  EXPECT_TRUE(build_delaunay_mesh(s).feature_snaps.empty());  // 1 mm apart: left apart
  // With a stated tolerance of 2 mm the same 1 mm gap is a near-miss: a's end moves onto
  // b's, and the move is reported with a's name.
  s.snap_tolerance_m = 2e-3;
  const Mesh joined = build_delaunay_mesh(s);
  ASSERT_EQ(joined.feature_snaps.size(), 1u);
  EXPECT_EQ(joined.feature_snaps[0].feature, "a");
  EXPECT_EQ(joined.feature_snaps[0].end, 1);
  EXPECT_EQ(joined.feature_snaps[0].to, Vec2(0, 1e-3));
  EXPECT_NEAR(joined.feature_snaps[0].moved_m, 1e-3, 1e-15);
  // A tolerance longer than a feature would collapse it (both ends onto b's end): refused,
  // naming it.
  s.constraints.push_back({"stub", Vec2(0.3, 0.3), Vec2(0.3, 0.31), 0.5});
  s.snap_tolerance_m = 0.6;
  try {
    build_delaunay_mesh(s);
    ADD_FAILURE() << "a feature snapped to a point was meshed";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("'stub' shrinks to a point"), std::string::npos) << e.what();
  }
}

TEST(MeshDelaunay, CrossingFracturesCutIntoJointsMeetExactly) {
  // A 100 m fracture and a crossing 50 m one, both cut into 0.5 m joints: refused before
  // (a cut point of the first lay 3.6e-15 m off the second); now both are made of their
  // own joints and share the mesh point (-22.5, 0).
  DelaunayMeshSpec s;
  s.outer = {-60.0, 60.0, -60.0, 60.0};
  s.max_area_outer_m2 = 20.0;
  s.constraints = {{"long", Vec2(-50, 0), Vec2(50, 0), 0.5}, {"cross", Vec2(-22.5, -25), Vec2(-22.5, 25), 0.5}};
  Mesh m = build_delaunay_mesh(s);
  build_topology(m, JointProperties{});
  const Vec2 crossing(-22.5, 0.0);
  EXPECT_EQ((m.points[nearest_point(m, crossing)] - crossing).norm(), 0.0);
  double lengths[2] = {0.0, 0.0};
  for (int j : joints_on_segment(m, Vec2(-50, 0), Vec2(50, 0), 1e-9))
    lengths[0] += (m.points[m.joints[j].point_q] - m.points[m.joints[j].point_p]).norm();
  for (int j : joints_on_segment(m, Vec2(-22.5, -25), Vec2(-22.5, 25), 1e-9))
    lengths[1] += (m.points[m.joints[j].point_q] - m.points[m.joints[j].point_p]).norm();
  EXPECT_NEAR(lengths[0], 100.0, 1e-9);
  EXPECT_NEAR(lengths[1], 50.0, 1e-9);
  // The triangulation says which edges came from which feature: each feature's edges lie
  // on it, cover it, and both features own an edge at the crossing point.
  ASSERT_TRUE(m.has_feature_edges);
  double owned[2] = {0.0, 0.0};
  bool at_crossing[2] = {false, false};
  const Vec2 ends[2][2] = {{Vec2(-50, 0), Vec2(50, 0)}, {Vec2(-22.5, -25), Vec2(-22.5, 25)}};
  for (const FeatureEdge& e : m.feature_edges) {
    ASSERT_TRUE(e.feature == 0 || e.feature == 1);
    const Vec2 &p = m.points[e.point_p], &q = m.points[e.point_q];
    const Vec2 d = ends[e.feature][1] - ends[e.feature][0];
    for (const Vec2& x : {p, q}) EXPECT_LT(std::abs(d.x() * (x - ends[e.feature][0]).y() - d.y() * (x - ends[e.feature][0]).x()) / d.norm(), 1e-9);
    owned[e.feature] += (q - p).norm();
    at_crossing[e.feature] = at_crossing[e.feature] || p == crossing || q == crossing;
  }
  EXPECT_NEAR(owned[0], 100.0, 1e-9);
  EXPECT_NEAR(owned[1], 50.0, 1e-9);
  EXPECT_TRUE(at_crossing[0] && at_crossing[1]);
  // A digitised end 2e-5 m short of the long fracture is snapped onto it and reported.
  s.constraints[1].to = Vec2(-22.5, -2e-5);
  s.constraints[1].from = Vec2(-22.5, -25);
  const Mesh snapped = build_delaunay_mesh(s);
  ASSERT_EQ(snapped.feature_snaps.size(), 1u);
  EXPECT_EQ(snapped.feature_snaps[0].feature, "cross");
  EXPECT_EQ(snapped.feature_snaps[0].end, 1);
  EXPECT_NEAR(snapped.feature_snaps[0].moved_m, 2e-5, 1e-12);
  EXPECT_EQ((snapped.points[nearest_point(snapped, crossing)] - crossing).norm(), 0.0);
}

TEST(MeshDelaunay, RejectsBadSpecs) {
  DelaunayMeshSpec s = delaunay_spec();
  s.constraints.push_back({"outside", Vec2(0, 0), Vec2(50, 0), 1.0});
  EXPECT_THROW(build_delaunay_mesh(s), ModelError);
  s = delaunay_spec();
  s.min_angle_deg = 40.0;
  EXPECT_THROW(build_delaunay_mesh(s), ModelError);
  s = delaunay_spec();
  s.max_area_inner_m2 = 0.0;
  EXPECT_THROW(build_delaunay_mesh(s), ModelError);
}

Mesh two_triangles() {
  Mesh m;
  m.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.blocks.resize(2);
  m.blocks[0].points = {0, 1, 2};
  m.blocks[1].points = {0, 2, 3};
  return m;
}

TEST(Topology, JointOrientationAndBoundary) {
  Mesh m = two_triangles();
  JointProperties props;
  props.tensile_strength_Pa = 3e6;
  build_topology(m, props);
  ASSERT_EQ(m.joints.size(), 1u);
  const Joint& j = m.joints[0];
  EXPECT_EQ(j.block_a, 0);
  EXPECT_EQ(j.corner_a, 2);  // block 0 runs 2 -> 0
  EXPECT_EQ(j.block_b, 1);
  EXPECT_EQ(j.corner_b, 0);  // block 1 runs 0 -> 2
  EXPECT_EQ(j.point_p, 2);
  EXPECT_EQ(j.point_q, 0);
  EXPECT_EQ(j.properties.tensile_strength_Pa, 3e6);
  ASSERT_EQ(m.boundary_edges.size(), 4u);
  for (const BoundaryEdge& e : m.boundary_edges) {
    const std::vector<int>& pts = m.blocks[e.block].points;
    EXPECT_EQ(e.point_p, pts[e.corner]);
    EXPECT_EQ(e.point_q, pts[(e.corner + 1) % pts.size()]);
  }
}

TEST(Topology, RejectsInvertedTriangle) {
  Mesh m = two_triangles();
  m.blocks[1].points = {0, 3, 2};
  EXPECT_THROW(build_topology(m, JointProperties{}), ModelError);
  try {
    build_topology(m, JointProperties{});
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("block 1 is inverted"), std::string::npos) << e.what();
  }
}

TEST(Topology, RejectsDegenerateTriangle) {
  Mesh m = two_triangles();
  m.points.push_back({2, 0});
  m.blocks.emplace_back().points = {0, 1, 4};  // collinear
  try {
    build_topology(m, JointProperties{});
    ADD_FAILURE() << "no throw";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("block 2 is degenerate"), std::string::npos) << e.what();
  }
  m.blocks.back().points = {0, 1};
  EXPECT_THROW(build_topology(m, JointProperties{}), ModelError);
}

TEST(Topology, RejectsHangingNode) {
  // Two quads below, one quad above spanning both: point (1, 1) hangs on its edge.
  Mesh m;
  m.points = {{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}, {0, 2}, {2, 2}};
  m.blocks.resize(3);
  m.blocks[0].points = {0, 1, 4, 3};
  m.blocks[1].points = {1, 2, 5, 4};
  m.blocks[2].points = {3, 5, 7, 6};
  try {
    build_topology(m, JointProperties{});
    ADD_FAILURE() << "no throw";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("hanging node"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(m.joints.empty());  // unchanged on failure
}

TEST(Topology, RejectsHangingNodesOnLongObliqueEdge) {
  // A big triangle whose hypotenuse (8, 0) -> (0, 8) faces a fan of 64 small
  // triangles: the fan's points hang on the one long oblique edge, which the spatial
  // search registers by sampling rather than by its bounding box.
  const int pieces = 64;
  Mesh m;
  m.points = {{0, 0}, {8, 8}};
  for (int k = 0; k <= pieces; ++k) m.points.emplace_back(8.0 - 8.0 * k / pieces, 8.0 * k / pieces);
  const int first = 2, last = 2 + pieces;
  m.blocks.emplace_back().points = {0, first, last};
  for (int k = 0; k < pieces; ++k) m.blocks.emplace_back().points = {first + k, 1, first + k + 1};
  try {
    build_topology(m, JointProperties{});
    ADD_FAILURE() << "no throw";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("hanging node"), std::string::npos) << e.what();
  }
  // Conforming version (the big triangle split at every fan point) is accepted.
  m.blocks.erase(m.blocks.begin());
  for (int k = 0; k < pieces; ++k) m.blocks.emplace_back().points = {0, first + k, first + k + 1};
  build_topology(m, JointProperties{});
  EXPECT_EQ(m.joints.size(), std::size_t(2 * pieces - 2 + pieces));
}

TEST(Topology, RejectsDuplicatePointAndTripleEdge) {
  Mesh m = two_triangles();
  m.points.push_back({0, 0});  // copy of point 0
  m.blocks[1].points = {4, 2, 3};
  EXPECT_THROW(build_topology(m, JointProperties{}), ModelError);

  m = two_triangles();
  m.points.push_back({2, 0});
  m.blocks.emplace_back().points = {2, 0, 4};  // also on edge 0-2, overlapping
  EXPECT_THROW(build_topology(m, JointProperties{}), ModelError);
}

TEST(Topology, JointsOnGridLine) {
  StructuredMeshSpec s;
  s.outer = {0.0, 4.0, 0.0, 3.0};
  s.cell_size_m = 1.0;
  s.split = CellSplit::two;
  Mesh m = build_structured_mesh(s);
  build_topology(m, JointProperties{});
  // Interior part of the line y = 1 from x = 1 to x = 3: exactly two joints.
  const std::vector<int> ids = joints_on_segment(m, Vec2(1, 1), Vec2(3, 1), 1e-9);
  ASSERT_EQ(ids.size(), 2u);
  for (int j : ids) {
    EXPECT_EQ(m.points[m.joints[j].point_p].y(), 1.0);
    EXPECT_EQ(m.points[m.joints[j].point_q].y(), 1.0);
  }
  // The whole line: four joints (boundary edges are not joints).
  EXPECT_EQ(joints_on_segment(m, Vec2(0, 1), Vec2(4, 1), 1e-9).size(), 4u);
  EXPECT_EQ(nearest_point(m, Vec2(2.1, 0.9)), 1 * 5 + 2);
}

}  // namespace
}  // namespace hfdda::mesh
