// The flow Newton's dense Jacobian J = A + E S diag(d) (fluid/aperture_model.hpp):
// factorised by Eigen's LU below kLapackLuMinNodes nodes and by LAPACK's from there on;
// both solve J x = r, and a singular J is a ConvergenceError on either path.

#include <gtest/gtest.h>

#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "core/errors.hpp"
#include "fluid/aperture_model.hpp"

namespace hfdda::fluid {
namespace {

/// A network-like Jacobian of n nodes: a chain Laplacian plus storage (A), every node its
/// own two fracture ends (E), and a dense, diagonally dominant S.
struct Problem {
  Eigen::SparseMatrix<double> a, e;
  Eigen::MatrixXd s;
  Eigen::VectorXd d;
  explicit Problem(int n) : a(n, n), e(n, 2 * n), s(2 * n, n), d(Eigen::VectorXd::Ones(n)) {
    std::vector<Eigen::Triplet<double>> ta, te;
    for (int i = 0; i < n; ++i) {
      ta.emplace_back(i, i, 3.0);
      if (i > 0) ta.emplace_back(i, i - 1, -1.0), ta.emplace_back(i - 1, i, -1.0);
      te.emplace_back(i, 2 * i, 0.5), te.emplace_back(i, 2 * i + 1, 0.5);
    }
    a.setFromTriplets(ta.begin(), ta.end());
    e.setFromTriplets(te.begin(), te.end());
    s = 0.01 * Eigen::MatrixXd::Random(2 * n, n);
    for (int i = 0; i < n; ++i) s(2 * i, i) += 1.0, s(2 * i + 1, i) += 1.0;
  }
  Eigen::MatrixXd jacobian() const { return Eigen::MatrixXd(a) + (e * s) * d.asDiagonal(); }
};

TEST(DenseApertureModel, BothLuPathsSolveTheJacobian) {
  for (const int n : {kLapackLuMinNodes - 1, kLapackLuMinNodes, 300}) {
    SCOPED_TRACE(n);
    const Problem p(n);
    DenseApertureModel model(p.s);
    model.factorize(p.a, p.e, p.d);
    const Eigen::VectorXd r = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
    // Solved exactly whatever forcing term the Newton iteration would accept.
    const Eigen::VectorXd x = model.solve(r, 0.1);
    EXPECT_LT((p.jacobian() * x - r).norm(), 1e-12 * r.norm());
    // The factors are kept: a second right-hand side with the same factorisation.
    const Eigen::VectorXd x2 = model.solve(2.0 * r, 1e-10);
    EXPECT_LT((x2 - 2.0 * x).norm(), 1e-12 * x.norm());
  }
}

TEST(DenseApertureModel, SingularJacobianIsAConvergenceErrorOnBothPaths) {
  for (const int n : {10, kLapackLuMinNodes}) {
    SCOPED_TRACE(n);
    Problem p(n);
    p.a.setZero();
    p.s.setZero();  // J = 0
    DenseApertureModel model(p.s);
    model.factorize(p.a, p.e, p.d);
    EXPECT_THROW(model.solve(Eigen::VectorXd::Ones(n), 1e-10), ConvergenceError);
  }
}

}  // namespace
}  // namespace hfdda::fluid
