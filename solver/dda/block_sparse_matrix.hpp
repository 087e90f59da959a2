#pragma once
// Global DDA matrix K (6x6 blocks, seed eq. 2.12) in a sparsity pattern fixed for the
// whole run: the contact list is built once (seed 2.3 iv), so every block pair that
// can ever interact gets its slot up front, and CHOLMOD's symbolic analysis (fill-
// reducing ordering, supernodes) is computed once and reused by every factorisation.

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

#include "dda/block_kinematics.hpp"

namespace hfdda::dda {

/// Lower triangle of a symmetric block matrix, compressed-column storage.
class BlockSparseMatrix {
 public:
  BlockSparseMatrix() = default;
  /// `couplings`: unordered block pairs (i != j) that may be coupled; duplicates allowed.
  BlockSparseMatrix(int n_blocks, const std::vector<std::pair<int, int>>& couplings);

  int n_blocks() const { return n_blocks_; }
  void set_zero();
  /// K_ii += m (only the lower triangle of m is read).
  void add_diagonal(int block, const Mat6& m);
  /// Slot of the off-diagonal block pair (i, j), i != j; throws if not in the pattern.
  int coupling_slot(int i, int j) const;
  /// K_ij += m_ij (and implicitly K_ji += m_ij^T), with the slot from coupling_slot(i, j).
  void add_coupling(int slot, int i, int j, const Mat6& m_ij);

  const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }
  /// y = K x using the symmetric lower storage.
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;

 private:
  struct Slot {
    int row_block;      // > column block
    int column_block;
    int value_offset;   // 6 x (rank of r among c's neighbours): row offset past the diagonal block
  };
  int n_blocks_ = 0;
  Eigen::SparseMatrix<double> matrix_;
  std::vector<int> neighbour_start_;  // per column block, into slots_
  std::vector<Slot> slots_;
};

/// Sparse Cholesky of K with CHOLMOD (supernodal), symbolic analysis done once.
class SpdSolver {
 public:
  /// Numeric factorisation; the first call also runs the symbolic analysis.
  /// Throws ConvergenceError if K is not positive definite.
  void factorize(const Eigen::SparseMatrix<double>& lower);
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  /// Several right-hand sides at once (one pass through the factor, BLAS-3).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const;
  /// Forget the symbolic analysis (the pattern changed); the next factorize redoes it.
  void reset_pattern() { analysed_ = false; }
  int factorizations() const { return factorizations_; }
  double factorization_seconds() const { return factorization_seconds_; }

 private:
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt_;
  bool analysed_ = false;
  int factorizations_ = 0;
  double factorization_seconds_ = 0.0;
};

}  // namespace hfdda::dda
