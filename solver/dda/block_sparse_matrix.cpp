#include "dda/block_sparse_matrix.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "core/errors.hpp"

namespace hfdda::dda {

BlockSparseMatrix::BlockSparseMatrix(int n_blocks, const std::vector<std::pair<int, int>>& couplings)
    : n_blocks_(n_blocks) {
  // Neighbour lists per column block (row block > column block), sorted and unique.
  std::vector<std::vector<int>> lower_neighbours(n_blocks);
  for (auto [i, j] : couplings) {
    if (i == j) continue;
    const int c = std::min(i, j), r = std::max(i, j);
    lower_neighbours[c].push_back(r);
  }
  neighbour_start_.assign(n_blocks + 1, 0);
  for (int c = 0; c < n_blocks; ++c) {
    auto& v = lower_neighbours[c];
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    neighbour_start_[c + 1] = neighbour_start_[c] + static_cast<int>(v.size());
  }

  // Column 6c+a holds the diagonal block's rows 6c+a..6c+5, then 6 rows per neighbour.
  const int n = 6 * n_blocks;
  matrix_.resize(n, n);
  std::vector<int> column_nnz(n);
  for (int c = 0; c < n_blocks; ++c)
    for (int a = 0; a < 6; ++a) column_nnz[6 * c + a] = (6 - a) + 6 * static_cast<int>(lower_neighbours[c].size());
  matrix_.reserve(column_nnz);
  for (int c = 0; c < n_blocks; ++c)
    for (int a = 0; a < 6; ++a) {
      for (int b = a; b < 6; ++b) matrix_.insert(6 * c + b, 6 * c + a) = 0.0;
      for (int r : lower_neighbours[c])
        for (int b = 0; b < 6; ++b) matrix_.insert(6 * r + b, 6 * c + a) = 0.0;
    }
  matrix_.makeCompressed();

  slots_.reserve(neighbour_start_[n_blocks]);
  for (int c = 0; c < n_blocks; ++c)
    for (std::size_t k = 0; k < lower_neighbours[c].size(); ++k)
      slots_.push_back({lower_neighbours[c][k], c, 6 * static_cast<int>(k)});
}

void BlockSparseMatrix::set_zero() {
  std::fill(matrix_.valuePtr(), matrix_.valuePtr() + matrix_.nonZeros(), 0.0);
}

void BlockSparseMatrix::add_diagonal(int block, const Mat6& m) {
  double* values = matrix_.valuePtr();
  const int* outer = matrix_.outerIndexPtr();
  for (int a = 0; a < 6; ++a) {
    double* column = values + outer[6 * block + a];
    for (int b = a; b < 6; ++b) column[b - a] += m(b, a);
  }
}

int BlockSparseMatrix::coupling_slot(int i, int j) const {
  const int c = std::min(i, j), r = std::max(i, j);
  const auto first = slots_.begin() + neighbour_start_[c];
  const auto last = slots_.begin() + neighbour_start_[c + 1];
  const auto it = std::lower_bound(first, last, r, [](const Slot& s, int row) { return s.row_block < row; });
  if (i == j || it == last || it->row_block != r)
    throw std::logic_error("block pair (" + std::to_string(i) + ", " + std::to_string(j) + ") is not in the pattern");
  return static_cast<int>(it - slots_.begin());
}

void BlockSparseMatrix::add_coupling(int slot, int i, int j, const Mat6& m_ij) {
  if (slot < 0 || slot >= static_cast<int>(slots_.size()))
    throw std::logic_error("block pair (" + std::to_string(i) + ", " + std::to_string(j) + ") has no slot in K's pattern");
  const Slot& s = slots_[slot];
  double* values = matrix_.valuePtr();
  const int* outer = matrix_.outerIndexPtr();
  // Stored block is K_rc with r > c: K_ij itself when i > j, otherwise its transpose.
  const bool transpose = i < j;
  for (int a = 0; a < 6; ++a) {
    // Column 6c+a: (6 - a) diagonal-block rows come first, then 6 rows per neighbour.
    double* column = values + outer[6 * s.column_block + a] + (6 - a) + s.value_offset;
    for (int b = 0; b < 6; ++b) column[b] += transpose ? m_ij(a, b) : m_ij(b, a);
  }
}

Eigen::VectorXd BlockSparseMatrix::multiply(const Eigen::VectorXd& x) const {
  return matrix_.selfadjointView<Eigen::Lower>() * x;
}

namespace {

/// CHOLMOD's default supernode amalgamation (nrelax 4/16/48 columns) suits matrices of
/// scalar unknowns. K has 6 x 6 block entries, so its fundamental supernodes are already
/// 6 columns wide and the defaults leave thousands of small ones. Each supernode costs
/// a few OpenMP regions in CHOLMOD's numeric factorisation, and libgomp makes a futex
/// system call at the end of every region even with one thread. Merging supernodes of
/// up to 16/64/192 columns (zero-fill limits unchanged) cut the factorisation time by
/// 35-45 % and the futex calls by a factor of 3 (docs/design_notes.md, Threads).
void relax_supernodes(cholmod_common& common) {
  common.nrelax[0] = 16;
  common.nrelax[1] = 64;
  common.nrelax[2] = 192;
}

}  // namespace

void SpdSolver::factorize(const Eigen::SparseMatrix<double>& lower) {
  const auto start = std::chrono::steady_clock::now();
  if (!analysed_) {
    relax_supernodes(llt_.cholmod());
    llt_.analyzePattern(lower);
    analysed_ = true;
  }
  llt_.factorize(lower);
  factorization_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++factorizations_;
  if (llt_.info() != Eigen::Success)
    throw ConvergenceError("the block stiffness matrix K is not positive definite (CHOLMOD factorisation failed); "
                           "a block is probably unconstrained");
}

Eigen::VectorXd SpdSolver::solve(const Eigen::VectorXd& rhs) const { return llt_.solve(rhs); }

Eigen::MatrixXd SpdSolver::solve(const Eigen::MatrixXd& rhs) const { return llt_.solve(rhs); }

}  // namespace hfdda::dda
