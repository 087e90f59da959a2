#pragma once
// Global DDA matrix K (6x6 blocks, seed eq. 2.12) in a sparsity pattern fixed for the
// whole run: the contact list is built once (seed 2.3 iv), so every block pair that
// can ever interact gets its slot up front, and CHOLMOD's symbolic analysis (fill-
// reducing ordering, supernodes) is computed once and reused by every factorisation.

#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <memory>
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

/// One penalty spring's term k e e^T of K: e holds `row_a` on block_a's six unknowns and
/// `row_b` on block_b's (block_a != block_b), k = `stiffness` [N/m]; as a change of K,
/// a negative k removes the spring.
struct SpringTerm {
  int block_a = -1, block_b = -1;
  Row6 row_a = Row6::Zero(), row_b = Row6::Zero();
  double stiffness = 0.0;
};

/// How SpdSolver::modify changes the factorised K (docs/design_notes.md section 26).
enum class LowRankMethod {
  /// cholmod_updown on a simplicial LDL' copy of the factor; the solves use that copy.
  updown,
  /// Woodbury identity: the supernodal factor of K0 is kept and K = K0 + C D C^T
  /// (D = +-1) is solved as K0^-1 b - W M^-1 C^T K0^-1 b, W = K0^-1 C, M = D + C^T W.
  woodbury,
};

/// Sparse Cholesky of K with CHOLMOD (supernodal), symbolic analysis done once. Springs
/// added to or removed from the factorised K can be applied without a new
/// factorisation (modify), until the next factorize().
class SpdSolver {
 public:
  SpdSolver();
  ~SpdSolver();
  SpdSolver(SpdSolver&&) noexcept;
  SpdSolver& operator=(SpdSolver&&) noexcept;
  SpdSolver(const SpdSolver&) = delete;
  SpdSolver& operator=(const SpdSolver&) = delete;

  /// Numeric factorisation; the first call also runs the symbolic analysis.
  /// Throws ConvergenceError if K is not positive definite (failed_unknown() then says
  /// where).
  void factorize(const Eigen::SparseMatrix<double>& lower);
  /// The unknown (row of K) whose pivot was not positive in the last failed
  /// factorize(); -1 after a successful one.
  int failed_unknown() const { return failed_unknown_; }
  /// The solves from now on are of K + sum k e e^T over `changes` (k < 0: a spring
  /// removed). Returns false if the modified matrix is found not positive definite
  /// (updown) or its capacitance matrix singular (woodbury); factorize() again then.
  /// One method between two factorisations.
  bool modify(const std::vector<SpringTerm>& changes, LowRankMethod method = LowRankMethod::woodbury);
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  /// Several right-hand sides at once (one pass through the factor, BLAS-3 when supernodal).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const;
  /// Forget the symbolic analysis (the pattern changed); the next factorize redoes it.
  void reset_pattern() { analysed_ = false; }
  int factorizations() const { return factorizations_; }
  /// Entries stored in the factor (supernodal: with the relaxed supernodes' zeros): a
  /// solve reads them twice, once per triangle, which bounds its cost by memory traffic.
  std::size_t factor_entries() const;
  double factorization_seconds() const { return factorization_seconds_; }
  /// Rank-one modifications since the last factorize().
  int modified_rank() const { return static_cast<int>(modified_springs_.size()); }
  /// Seconds spent in modify() so far.
  double modification_seconds() const { return modification_seconds_; }

  // Woodbury: K^-1 = K0^-1 - W M^-1 W^T, for callers that keep products with K0^-1.
  /// W = K0^-1 C (unknowns x modified_rank()).
  const Eigen::MatrixXd& woodbury_solutions() const { return woodbury_solutions_; }
  /// M^-1 v for v with modified_rank() rows.
  Eigen::MatrixXd solve_capacitance(const Eigen::MatrixXd& v) const;
  /// The Woodbury solve of K x = b for b = K x_exact, without a solve with the factor:
  /// K0^-1 b = x_exact + W D C^T x_exact. |K x - b| then shows the digits the
  /// capacitance matrix loses (a downdate of a stiff spring), at the cost of products.
  Eigen::VectorXd woodbury_check_solve(const Eigen::VectorXd& x_exact) const;

 private:
  struct Cholmod;  // CHOLMOD's workspace and factors (block_sparse_matrix.cpp)
  std::unique_ptr<Cholmod> cholmod_;
  bool analysed_ = false;
  int failed_unknown_ = -1;
  int factorizations_ = 0;
  double factorization_seconds_ = 0.0;
  double modification_seconds_ = 0.0;
  // Since the last factorisation: the changes and, for the Woodbury identity, W and
  // the LU factors of M.
  std::vector<SpringTerm> modified_springs_;
  Eigen::MatrixXd woodbury_solutions_;
  Eigen::MatrixXd capacitance_;
  Eigen::PartialPivLU<Eigen::MatrixXd> capacitance_lu_;
  /// C^T y for the modified springs (column s of C: sqrt(|k_s|) e_s).
  Eigen::MatrixXd spring_projection(const Eigen::MatrixXd& y) const;
  Eigen::MatrixXd solve_factor(const Eigen::MatrixXd& rhs) const;
  /// K0^-1 rhs for one right-hand side, into the kept solution vector; valid until the next solve.
  const double* solve_factor_in_place(const double* rhs, int rows) const;
};

}  // namespace hfdda::dda
