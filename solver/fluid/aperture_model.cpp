#include "fluid/aperture_model.hpp"

#include "core/errors.hpp"

extern "C" {
// LAPACK (Fortran interface): LU with partial pivoting and the solve with its factors.
void dgetrf_(const int* m, const int* n, double* a, const int* lda, int* ipiv, int* info);
void dgetrs_(const char* trans, const int* n, const int* nrhs, const double* a, const int* lda, const int* ipiv,
             double* b, const int* ldb, int* info);
}

namespace hfdda::fluid {

void DenseApertureModel::factorize(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e,
                                   const Eigen::VectorXd& d) {
  jacobian_ = Eigen::MatrixXd(a);
  jacobian_.noalias() += (e * s_) * d.asDiagonal();
  const int n = static_cast<int>(jacobian_.rows());
  lapack_ = n >= kLapackLuMinNodes;
  if (!lapack_) {
    lu_.compute(jacobian_);
    return;
  }
  pivots_.resize(n);
  dgetrf_(&n, &n, jacobian_.data(), &n, pivots_.data(), &lapack_info_);
}

Eigen::VectorXd DenseApertureModel::solve(const Eigen::VectorXd& r, double /*forcing: solved exactly*/) {
  Eigen::VectorXd x;
  if (lapack_) {
    if (lapack_info_ != 0) throw ConvergenceError("fluid flow: singular mass-balance Jacobian");
    x = r;
    const int n = static_cast<int>(x.size()), one = 1;
    int info = 0;
    dgetrs_("N", &n, &one, jacobian_.data(), &n, pivots_.data(), x.data(), &n, &info);
  } else {
    x = lu_.solve(r);
  }
  if (!x.allFinite()) throw ConvergenceError("fluid flow: singular mass-balance Jacobian");
  return x;
}

}  // namespace hfdda::fluid
