#include "dda/block_kinematics.hpp"

namespace hfdda::dda {

Eigen::Matrix3d plane_strain_elasticity(double youngs_modulus_Pa, double poissons_ratio) {
  const double nu = poissons_ratio;
  const double c = youngs_modulus_Pa / ((1.0 + nu) * (1.0 - 2.0 * nu));
  Eigen::Matrix3d m;
  m << c * (1.0 - nu), c * nu, 0.0,
       c * nu, c * (1.0 - nu), 0.0,
       0.0, 0.0, c * (1.0 - 2.0 * nu) / 2.0;
  return m;
}

Mat6 displacement_matrix_gram(const PolygonMoments& m) {
  // Columns of T are (1,0), (0,1), (-Y,X), (X,0), (0,Y), (Y/2,X/2) with X = x - x0,
  // Y = y - y0; first moments vanish about the centroid.
  const double a = m.area, sxx = m.sxx, syy = m.syy, sxy = m.sxy;
  Mat6 g = Mat6::Zero();
  g(0, 0) = a;
  g(1, 1) = a;
  g(2, 2) = sxx + syy;
  g(2, 3) = -sxy;
  g(2, 4) = sxy;
  g(2, 5) = 0.5 * (sxx - syy);
  g(3, 3) = sxx;
  g(3, 5) = 0.5 * sxy;
  g(4, 4) = syy;
  g(4, 5) = 0.5 * sxy;
  g(5, 5) = 0.25 * (sxx + syy);
  return g.selfadjointView<Eigen::Upper>();
}

}  // namespace hfdda::dda
