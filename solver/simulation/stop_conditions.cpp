#include "simulation/stop_conditions.hpp"

#include <algorithm>
#include <cmath>

namespace hfdda::simulation {

std::vector<char> inner_boundary_points(const mesh::Mesh& mesh, const io::CaseConfig& config) {
  if (!config.domain.inner) return {};
  const Rect& r = *config.domain.inner;
  const double tol = 1e-9 * std::max(config.domain.outer.width(), config.domain.outer.height());
  std::vector<char> on(mesh.points.size(), 0);
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    const Vec2& p = mesh.points[i];
    const bool inside = p.x() > r.xmin - tol && p.x() < r.xmax + tol && p.y() > r.ymin - tol && p.y() < r.ymax + tol;
    const bool on_side = std::abs(p.x() - r.xmin) < tol || std::abs(p.x() - r.xmax) < tol ||
                         std::abs(p.y() - r.ymin) < tol || std::abs(p.y() - r.ymax) < tol;
    on[i] = inside && on_side;
  }
  return on;
}

bool fluid_at_edge(const fluid::FlowNetwork& flow, const mesh::Mesh& mesh, const std::vector<char>& edge_points) {
  if (edge_points.empty()) return false;
  for (int j = 0; j < static_cast<int>(mesh.joints.size()); ++j)
    if (flow.wetted(j) && (edge_points[mesh.joints[j].point_p] || edge_points[mesh.joints[j].point_q])) return true;
  return false;
}

}  // namespace hfdda::simulation
