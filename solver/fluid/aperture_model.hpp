#pragma once
// How the flow network sees the rock: the apertures of the wetted fracture ends as an
// affine function of the nodal pressures, w = base + S p (exact for the linear block
// system while its contacts are fixed; seed 2.4), and the linear solves of the flow
// Newton iteration whose Jacobian couples through S:
//
//     J = A + E S diag(d)
//
// A (n x n, sparse): storage, leak-off and flow between nodes at fixed apertures;
// E (n x 2 nf, sparse): how each end's aperture enters the mass balance of the nodes;
// d (n): the slope of the pressure in each node's unknown (0 at zero-pressure nodes).
// S itself may be a dense matrix (DenseApertureModel) or an operator whose products
// cost one solve with the factorised block stiffness (coupling/aperture_operator.hpp).

#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

namespace hfdda::fluid {

class ApertureModel {
 public:
  virtual ~ApertureModel() = default;
  /// Number of fracture ends (rows of S) and of nodes (columns of S).
  virtual int n_ends() const = 0;
  virtual int n_nodes() const = 0;
  /// out = S p [m].
  virtual void apply(const Eigen::VectorXd& pressure_Pa, Eigen::VectorXd& out_m) const = 0;
  /// S(end, node) for an end at that node: its compliance to its own node's pressure [m/Pa].
  virtual double self_entry(int end, int node) const = 0;
  /// Prepares solves with J = A + E S diag(d). Throws ConvergenceError if J is singular.
  virtual void factorize(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e,
                         const Eigen::VectorXd& d) = 0;
  /// x = J^-1 r with the last factorize. Throws ConvergenceError if it fails.
  /// `forcing`: the relative residual the caller accepts (the forcing term of an inexact
  /// Newton iteration); models that solve exactly ignore it, iterative ones may stop there.
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& r, double forcing) = 0;
  /// Products with S and inner linear iterations since construction (operator models).
  virtual long products() const { return 0; }
  virtual long linear_iterations() const { return 0; }
  /// Solves whose inner iteration stopped at its limit before its tolerance; Newton
  /// then takes the inexact step (its own test is on the mass residual), counted here.
  virtual long inexact_solves() const { return 0; }
};

/// S held as a dense matrix; J formed densely and factorised by LU with partial pivoting:
/// Eigen's below kLapackLuMinNodes nodes, LAPACK's (dgetrf, the BLAS kernels of the
/// processor) from there on, 2.6-3.2 times faster at 256-1,177 nodes (docs/design_notes.md
/// section 19).
class DenseApertureModel final : public ApertureModel {
 public:
  explicit DenseApertureModel(const Eigen::MatrixXd& sensitivity_m_Pa) : s_(sensitivity_m_Pa) {}
  int n_ends() const override { return static_cast<int>(s_.rows()); }
  int n_nodes() const override { return static_cast<int>(s_.cols()); }
  void apply(const Eigen::VectorXd& p, Eigen::VectorXd& out) const override { out.noalias() = s_ * p; }
  double self_entry(int end, int node) const override { return s_(end, node); }
  void factorize(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e,
                 const Eigen::VectorXd& d) override;
  Eigen::VectorXd solve(const Eigen::VectorXd& r, double forcing) override;

 private:
  const Eigen::MatrixXd& s_;
  Eigen::MatrixXd jacobian_;  ///< J, or its LAPACK LU factors in place
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  bool lapack_ = false;       ///< the factors are LAPACK's (jacobian_, pivots_)
  std::vector<int> pivots_;
  int lapack_info_ = 0;       ///< dgetrf's info: > 0, an exactly zero pivot
};

/// Wetted nodes from which DenseApertureModel factorises J with LAPACK. LAPACK's LU is
/// 1.1 times faster at 64 nodes and 1.8-3.2 times from 128; the switch is set at 256,
/// above every network of the verification suite (at most 195 nodes), whose results are
/// thereby those of Eigen's LU to the last digit.
inline constexpr int kLapackLuMinNodes = 256;

}  // namespace hfdda::fluid
