#pragma once
// First-order DDA block kinematics (Shi 1988; seed section 2.2 with erratum 1 in docs/seed_errata.md).
//
// A block moves with the six unknowns D = (u0, v0, r0, ex, ey, gxy) at its centroid
// (x0, y0); the displacement of a point (x, y) of the block is U = T(x, y) D with
//   u = u0 - r0 (y - y0) + ex (x - x0) + gxy (y - y0) / 2
//   v = v0 + r0 (x - x0) + ey (y - y0) + gxy (x - x0) / 2
// (the seed's eq. 2.10 has sign typos; this is Shi's form).

#include <Eigen/Core>

#include "core/geometry.hpp"

namespace hfdda::dda {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat26 = Eigen::Matrix<double, 2, 6>;
using Row6 = Eigen::Matrix<double, 1, 6>;

/// Shi's displacement matrix T(x, y) about the block centroid (erratum 1 in docs/seed_errata.md).
inline Mat26 displacement_matrix(const Vec2& point, const Vec2& centroid) {
  const double dx = point.x() - centroid.x();
  const double dy = point.y() - centroid.y();
  Mat26 t;
  t << 1.0, 0.0, -dy, dx, 0.0, 0.5 * dy,
       0.0, 1.0, dx, 0.0, dy, 0.5 * dx;
  return t;
}

/// Outward (right-hand) unit normal of an edge of a counter-clockwise polygon.
inline Vec2 outward_normal(const Vec2& from, const Vec2& to) {
  const Vec2 t = (to - from).normalized();
  return Vec2(t.y(), -t.x());
}

/// Plane-strain elasticity matrix relating (sxx, syy, sxy) to (ex, ey, gxy), unit thickness.
Eigen::Matrix3d plane_strain_elasticity(double youngs_modulus_Pa, double poissons_ratio);

/// Integral of T^T T over a polygon with the given moments (DDA inertia term,
/// multiplied by the density it gives the block mass matrix of Shi's eq. 2.56).
Mat6 displacement_matrix_gram(const PolygonMoments& moments);

}  // namespace hfdda::dda
