#include "core/geometry.hpp"

#include <algorithm>
#include <cmath>

namespace hfdda {

PolygonMoments polygon_moments(std::span<const Vec2> v) {
  // Raw moments about the origin by Green's theorem, then shifted to the centroid.
  double a2 = 0.0, cx = 0.0, cy = 0.0, ixx = 0.0, iyy = 0.0, ixy = 0.0;
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& p = v[i];
    const Vec2& q = v[(i + 1) % n];
    const double c = p.x() * q.y() - q.x() * p.y();
    a2 += c;
    cx += (p.x() + q.x()) * c;
    cy += (p.y() + q.y()) * c;
    ixx += (p.x() * p.x() + p.x() * q.x() + q.x() * q.x()) * c;  // integral of x^2
    iyy += (p.y() * p.y() + p.y() * q.y() + q.y() * q.y()) * c;  // integral of y^2
    ixy += (p.x() * q.y() + 2.0 * p.x() * p.y() + 2.0 * q.x() * q.y() + q.x() * p.y()) * c;
  }
  PolygonMoments m;
  m.area = 0.5 * a2;
  if (m.area == 0.0) return m;
  m.centroid = Vec2(cx / (3.0 * a2), cy / (3.0 * a2));
  const double raw_xx = ixx / 12.0, raw_yy = iyy / 12.0, raw_xy = ixy / 24.0;
  m.sxx = raw_xx - m.area * m.centroid.x() * m.centroid.x();
  m.syy = raw_yy - m.area * m.centroid.y() * m.centroid.y();
  m.sxy = raw_xy - m.area * m.centroid.x() * m.centroid.y();
  return m;
}

double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

}  // namespace hfdda
