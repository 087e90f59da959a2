#include "fluid/aperture_model.hpp"

#include "core/errors.hpp"

namespace hfdda::fluid {

void DenseApertureModel::factorize(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e,
                                   const Eigen::VectorXd& d) {
  jacobian_ = Eigen::MatrixXd(a);
  jacobian_.noalias() += (e * s_) * d.asDiagonal();
  lu_.compute(jacobian_);
}

Eigen::VectorXd DenseApertureModel::solve(const Eigen::VectorXd& r) {
  Eigen::VectorXd x = lu_.solve(r);
  if (!x.allFinite()) throw ConvergenceError("fluid flow: singular mass-balance Jacobian");
  return x;
}

}  // namespace hfdda::fluid
