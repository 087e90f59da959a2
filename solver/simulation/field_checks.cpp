// Finite-field checks after each step (field_checks.hpp).

#include "simulation/field_checks.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/errors.hpp"
#include "dda/block_system.hpp"
#include "fluid/flow_network.hpp"

namespace hfdda::simulation {

namespace {

std::string number_text(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

std::string at_text(const Vec2& p) {
  std::string text = "(";  // appended: `"(" + std::string` trips a false -Wrestrict in GCC 12
  text += number_text(p.x()) + ", " + number_text(p.y()) + ") m";
  return text;
}

[[noreturn]] void fail(int step, const std::string& what, const std::string& where, double value) {
  throw ConvergenceError(what + " is not a finite number (" + number_text(value) + ") at " + where +
                         " after step " + std::to_string(step) + "; the run is stopped (a load, stiffness or time step too large for the model?)");
}

}  // namespace

void check_fields_finite(const dda::BlockSystem& system, const fluid::FlowNetwork* flow, int step) {
  const mesh::Mesh& mesh = system.mesh();
  for (int b = 0; b < system.n_blocks(); ++b) {
    const std::string block = "block " + std::to_string(b) + " (first corner initially at " +
                              at_text(system.initial_corner(b, 0)) + ")";
    for (int k = 0; k < system.n_corners(b); ++k) {
      const Vec2 c = system.corner(b, k);
      if (!std::isfinite(c.x()) || !std::isfinite(c.y()))
        fail(step, "the displaced position of corner " + std::to_string(k), block,
             std::isfinite(c.x()) ? c.y() : c.x());
    }
    const auto& s = system.stress(b);
    static const char* names[] = {"sxx", "syy", "sxy"};
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(s[i])) fail(step, std::string("the stress ") + names[i], block, s[i]);
  }
  for (std::size_t j = 0; j < mesh.joints.size(); ++j) {
    const mesh::Joint& joint = mesh.joints[j];
    for (int end = 0; end < 2; ++end) {
      const double gap = system.joint_gap(static_cast<int>(j), end);
      if (std::isfinite(gap)) continue;
      const int point = end == 0 ? joint.point_p : joint.point_q;
      fail(step, "the aperture", "joint " + std::to_string(j) + ", end " + std::to_string(end) +
                                     " (point " + std::to_string(point) + " at " +
                                     at_text(mesh.points[point]) + ")",
           gap);
    }
  }
  if (flow == nullptr) return;
  for (int p = 0; p < flow->n_points() && p < static_cast<int>(mesh.points.size()); ++p) {
    const double pressure = flow->pressure(p);
    if (!std::isfinite(pressure))
      fail(step, "the fluid pressure", "node " + std::to_string(p) + " at " + at_text(mesh.points[p]), pressure);
  }
}

}  // namespace hfdda::simulation
