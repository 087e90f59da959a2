#pragma once
// Small plane-geometry helpers shared by the mesh, the DDA mechanics and I/O.
// Units: metres throughout.

#include <Eigen/Core>
#include <span>
#include <vector>

namespace hfdda {

using Vec2 = Eigen::Vector2d;

/// Axis-aligned rectangle [xmin, xmax] x [ymin, ymax] in metres.
struct Rect {
  double xmin = 0.0, xmax = 0.0, ymin = 0.0, ymax = 0.0;

  double width() const { return xmax - xmin; }
  double height() const { return ymax - ymin; }
  bool contains(const Vec2& p, double tol = 0.0) const {
    return p.x() >= xmin - tol && p.x() <= xmax + tol && p.y() >= ymin - tol && p.y() <= ymax + tol;
  }
  bool contains(const Rect& r) const {
    return r.xmin >= xmin && r.xmax <= xmax && r.ymin >= ymin && r.ymax <= ymax;
  }
};

/// Area moments of a simple polygon (vertices counter-clockwise).
struct PolygonMoments {
  double area = 0.0;          ///< signed area, > 0 when counter-clockwise [m^2]
  Vec2 centroid{0.0, 0.0};    ///< [m]
  double sxx = 0.0;           ///< integral of (x - x0)^2 dA [m^4]
  double syy = 0.0;           ///< integral of (y - y0)^2 dA [m^4]
  double sxy = 0.0;           ///< integral of (x - x0)(y - y0) dA [m^4]
};

/// Exact area, centroid and central second moments of a polygon (Green's theorem).
PolygonMoments polygon_moments(std::span<const Vec2> vertices);

/// Twice the signed area of triangle (a, b, c); > 0 when counter-clockwise.
inline double cross2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
}

/// Distance from point p to segment [a, b].
double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b);

}  // namespace hfdda
