// Mesh topology: joints (edges shared by two blocks) and free boundary edges.
//
// The DDA contact list is built once from this topology (seed section 2.3 iv), so every
// defect that would silently disconnect blocks (inverted or degenerate blocks, hanging
// nodes, coincident points) is rejected here rather than found as a wrong answer later.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "core/errors.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::mesh {
namespace {

std::string num(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

std::string point_text(const Mesh& mesh, int id) {
  const Vec2& p = mesh.points[id];
  return "point " + std::to_string(id) + " (" + num(p.x()) + ", " + num(p.y()) + ")";
}

void check_block(const Mesh& mesh, int b) {
  const Block& block = mesh.blocks[b];
  const std::string name = "block " + std::to_string(b);
  const int n = static_cast<int>(block.points.size());
  if (n < 3) throw ModelError(name + " has " + std::to_string(n) + " corners (at least 3 needed)");
  std::vector<Vec2> corners;
  corners.reserve(n);
  for (int id : block.points) {
    if (id < 0 || id >= static_cast<int>(mesh.points.size()))
      throw ModelError(name + " refers to point " + std::to_string(id) + ", but the mesh has " +
                       std::to_string(mesh.points.size()) + " points");
    corners.push_back(mesh.points[id]);
  }
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (block.points[i] == block.points[j])
        throw ModelError(name + " is degenerate: it uses " + point_text(mesh, block.points[i]) +
                         " twice");
  Vec2 lo = corners[0], hi = corners[0];
  for (const Vec2& c : corners) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const double diagonal2 = (hi - lo).squaredNorm();
  const double area = polygon_moments(corners).area;
  // Relative to its own size, so that tiny but well-shaped blocks are accepted.
  if (!(std::abs(area) > 1e-12 * diagonal2))
    throw ModelError(name + " is degenerate: area " + num(area) +
                     " m^2 for a bounding-box diagonal of " + num(std::sqrt(diagonal2)) +
                     " m (first corner " + point_text(mesh, block.points[0]) + ")");
  if (area < 0.0)
    throw ModelError(name + " is inverted (clockwise corners, area " + num(area) +
                     " m^2); corners must be counter-clockwise (first corner " +
                     point_text(mesh, block.points[0]) + ")");
}

/// One block's view of an edge: from points[corner] to points[corner + 1].
struct HalfEdge {
  int lo, hi;  ///< point ids, lo < hi
  int block, corner;
  bool forward;  ///< the block runs the edge lo -> hi
};

std::vector<HalfEdge> half_edges(const Mesh& mesh) {
  std::vector<HalfEdge> edges;
  std::size_t count = 0;
  for (const Block& b : mesh.blocks) count += b.points.size();
  edges.reserve(count);
  for (int b = 0; b < static_cast<int>(mesh.blocks.size()); ++b) {
    const std::vector<int>& pts = mesh.blocks[b].points;
    const int n = static_cast<int>(pts.size());
    for (int c = 0; c < n; ++c) {
      const int p = pts[c], q = pts[(c + 1) % n];
      edges.push_back({std::min(p, q), std::max(p, q), b, c, p < q});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.lo, x.hi, x.block, x.corner) < std::tie(y.lo, y.hi, y.block, y.corner);
  });
  return edges;
}

std::string edge_text(const Mesh& mesh, const HalfEdge& e) {
  return "edge " + point_text(mesh, e.lo) + " - " + point_text(mesh, e.hi);
}

/// Pairs the half edges of each undirected edge into a joint or a boundary edge.
void pair_edges(const Mesh& mesh, const std::vector<HalfEdge>& edges, const JointProperties& defaults,
                std::vector<Joint>& joints, std::vector<BoundaryEdge>& boundary) {
  const auto start = [&mesh](const HalfEdge& e) { return mesh.blocks[e.block].points[e.corner]; };
  const auto end = [&mesh](const HalfEdge& e) {
    const std::vector<int>& pts = mesh.blocks[e.block].points;
    return pts[(e.corner + 1) % pts.size()];
  };
  std::size_t first = 0;
  while (first < edges.size()) {
    std::size_t last = first + 1;
    while (last < edges.size() && edges[last].lo == edges[first].lo && edges[last].hi == edges[first].hi)
      ++last;
    const HalfEdge& a = edges[first];
    if (last - first == 1) {
      boundary.push_back({a.block, a.corner, start(a), end(a)});
    } else if (last - first == 2) {
      const HalfEdge& b = edges[first + 1];  // sorted, so a.block <= b.block
      if (a.forward == b.forward)
        throw ModelError("blocks " + std::to_string(a.block) + " and " + std::to_string(b.block) +
                         " both run " + edge_text(mesh, a) + " in the same direction: they overlap");
      Joint j;
      j.block_a = a.block;
      j.corner_a = a.corner;
      j.block_b = b.block;
      j.corner_b = b.corner;
      j.point_p = start(a);
      j.point_q = end(a);
      j.properties = defaults;
      joints.push_back(j);
    } else {
      std::string owners = std::to_string(a.block);
      for (std::size_t k = first + 1; k < last; ++k)
        owners.append(", ").append(std::to_string(edges[k].block));
      throw ModelError(edge_text(mesh, a) + " is shared by " + std::to_string(last - first) +
                       " blocks (" + owners + "); at most two blocks may share an edge");
    }
    first = last;
  }
}

using CellKey = std::pair<std::int64_t, std::int64_t>;

CellKey cell_of(const Vec2& p, const Vec2& origin, double cell) {
  return {static_cast<std::int64_t>(std::floor((p.x() - origin.x()) / cell)),
          static_cast<std::int64_t>(std::floor((p.y() - origin.y()) / cell))};
}

/// Distance below which a point counts as lying on edge [p, q]: round-off level, since
/// a real hanging node sits on the edge up to the coordinates' round-off.
double on_edge_tolerance(const Vec2& p, const Vec2& q, double cell) {
  return std::min(1e-9 * (q - p).norm(), 0.25 * cell);
}

/// Appends every cell holding a point within on_edge_tolerance of edge k.
void register_edge(const Vec2& p, const Vec2& q, int k, const Vec2& origin, double cell,
                   std::vector<std::pair<CellKey, int>>& registry) {
  const Vec2 pad = Vec2::Constant(on_edge_tolerance(p, q, cell));
  const CellKey lo = cell_of(p.cwiseMin(q) - pad, origin, cell);
  const CellKey hi = cell_of(p.cwiseMax(q) + pad, origin, cell);
  const std::int64_t nx = hi.first - lo.first + 1, ny = hi.second - lo.second + 1;
  if (nx * ny <= 9) {  // short edges (the rule: cell = mean length): the bounding box
    for (std::int64_t i = lo.first; i <= hi.first; ++i)
      for (std::int64_t j = lo.second; j <= hi.second; ++j) registry.push_back({{i, j}, k});
    return;
  }
  // Long oblique edges would cover a quadratic number of bounding-box cells. Samples
  // at most one cell apart instead: a point within tol <= cell/4 of the edge is within
  // cell/2 + cell/4 < cell of a sample, hence in the 3 x 3 cells around its cell.
  const int samples = static_cast<int>(std::ceil((q - p).norm() / cell));
  const std::size_t first = registry.size();
  for (int s = 0; s <= samples; ++s) {
    const CellKey c = cell_of(p + (q - p) * (static_cast<double>(s) / samples), origin, cell);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy) registry.push_back({{c.first + dx, c.second + dy}, k});
  }
  std::sort(registry.begin() + first, registry.end());
  registry.erase(std::unique(registry.begin() + first, registry.end()), registry.end());
}

/// Rejects a boundary point that lies on another boundary edge: a hanging node (point
/// inside the edge) or a duplicate point (on an end point). Either leaves blocks that
/// should be bonded unjoined. Only boundary edges can be involved, because a point
/// inside a block's edge makes that edge and the neighbour's sub-edges unpaired.
///
/// Spatial hashing: each edge is registered in every cell (size ~ mean edge length)
/// near it, each point looks up its own cell: O(n log n) overall.
void check_boundary_conformity(const Mesh& mesh, const std::vector<BoundaryEdge>& boundary) {
  if (boundary.empty()) return;
  double total_length = 0.0;
  Vec2 origin = mesh.points[boundary[0].point_p];
  for (const BoundaryEdge& e : boundary) {
    total_length += (mesh.points[e.point_q] - mesh.points[e.point_p]).norm();
    origin = origin.cwiseMin(mesh.points[e.point_p]);
  }
  const double cell = total_length / static_cast<double>(boundary.size());

  std::vector<std::pair<CellKey, int>> registry;
  for (int k = 0; k < static_cast<int>(boundary.size()); ++k)
    register_edge(mesh.points[boundary[k].point_p], mesh.points[boundary[k].point_q], k, origin, cell,
                  registry);
  std::sort(registry.begin(), registry.end());

  std::vector<int> boundary_points;
  for (const BoundaryEdge& e : boundary) boundary_points.push_back(e.point_p);
  std::sort(boundary_points.begin(), boundary_points.end());
  boundary_points.erase(std::unique(boundary_points.begin(), boundary_points.end()),
                        boundary_points.end());

  for (int id : boundary_points) {
    const Vec2& x = mesh.points[id];
    const CellKey c = cell_of(x, origin, cell);
    auto it = std::lower_bound(registry.begin(), registry.end(),
                               std::make_pair(c, std::numeric_limits<int>::min()));
    for (; it != registry.end() && it->first == c; ++it) {
      const BoundaryEdge& e = boundary[it->second];
      if (id == e.point_p || id == e.point_q) continue;
      const Vec2& p = mesh.points[e.point_p];
      const Vec2& q = mesh.points[e.point_q];
      const double tol = on_edge_tolerance(p, q, cell);
      if (point_segment_distance(x, p, q) > tol) continue;
      const std::string where = "boundary edge of block " + std::to_string(e.block) + " from " +
                                point_text(mesh, e.point_p) + " to " + point_text(mesh, e.point_q);
      if ((x - p).norm() <= tol || (x - q).norm() <= tol)
        throw ModelError(point_text(mesh, id) + " coincides with an end point of the " + where +
                         ": duplicate points leave the blocks meeting there unjoined");
      throw ModelError("hanging node: " + point_text(mesh, id) + " lies inside the " + where +
                       " (non-conforming mesh; split the edge at that point)");
    }
  }
}

}  // namespace

void build_topology(Mesh& mesh, const JointProperties& defaults) {
  for (int b = 0; b < static_cast<int>(mesh.blocks.size()); ++b) check_block(mesh, b);
  std::vector<Joint> joints;
  std::vector<BoundaryEdge> boundary;
  pair_edges(mesh, half_edges(mesh), defaults, joints, boundary);
  std::sort(joints.begin(), joints.end(), [](const Joint& x, const Joint& y) {
    return std::tie(x.block_a, x.corner_a) < std::tie(y.block_a, y.corner_a);
  });
  std::sort(boundary.begin(), boundary.end(), [](const BoundaryEdge& x, const BoundaryEdge& y) {
    return std::tie(x.block, x.corner) < std::tie(y.block, y.corner);
  });
  check_boundary_conformity(mesh, boundary);
  // Assign last: a mesh that fails a check keeps its previous topology.
  mesh.joints = std::move(joints);
  mesh.boundary_edges = std::move(boundary);
}

std::vector<int> joints_on_segment(const Mesh& mesh, const Vec2& a, const Vec2& b, double tol) {
  std::vector<int> ids;
  for (int j = 0; j < static_cast<int>(mesh.joints.size()); ++j) {
    const Joint& joint = mesh.joints[j];
    if (point_segment_distance(mesh.points[joint.point_p], a, b) <= tol &&
        point_segment_distance(mesh.points[joint.point_q], a, b) <= tol)
      ids.push_back(j);
  }
  return ids;
}

int nearest_point(const Mesh& mesh, const Vec2& p) {
  if (mesh.points.empty()) throw ModelError("nearest_point: the mesh has no points");
  int best = 0;
  double best_d2 = (mesh.points[0] - p).squaredNorm();
  for (int i = 1; i < static_cast<int>(mesh.points.size()); ++i) {
    const double d2 = (mesh.points[i] - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = i;
    }
  }
  return best;
}

}  // namespace hfdda::mesh
