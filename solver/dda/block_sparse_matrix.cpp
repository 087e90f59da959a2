#include "dda/block_sparse_matrix.hpp"

#include <algorithm>
#include <array>
#include <cholmod.h>
#include <cmath>
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

/// CHOLMOD's view of the lower triangle (no copy).
cholmod_sparse view_lower(const Eigen::SparseMatrix<double>& lower) {
  cholmod_sparse a{};
  a.nrow = a.ncol = static_cast<std::size_t>(lower.rows());
  a.nzmax = static_cast<std::size_t>(lower.nonZeros());
  a.p = const_cast<int*>(lower.outerIndexPtr());
  a.i = const_cast<int*>(lower.innerIndexPtr());
  a.x = const_cast<double*>(lower.valuePtr());
  a.stype = -1;
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  return a;
}

/// CHOLMOD's view of a column-major dense block (no copy).
cholmod_dense view_dense(const double* data, int rows, int cols) {
  cholmod_dense d{};
  d.nrow = d.d = static_cast<std::size_t>(rows);
  d.ncol = static_cast<std::size_t>(cols);
  d.nzmax = d.nrow * d.ncol;
  d.x = const_cast<double*>(data);
  d.xtype = CHOLMOD_REAL;
  d.dtype = CHOLMOD_DOUBLE;
  return d;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

struct SpdSolver::Cholmod {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;    // supernodal LL' of the last factorize()
  cholmod_factor* modified = nullptr;  // simplicial LDL' with the springs modified since
  std::vector<int> new_row;            // original unknown -> row of the permuted factor
  // cholmod_solve2's solution and workspace, kept between solves: allocating them anew
  // for every solve of the contact iterations cost page faults (a vector of K's size is
  // above malloc's mmap threshold).
  cholmod_dense* solution = nullptr;
  cholmod_dense* work_y = nullptr;
  cholmod_dense* work_e = nullptr;
  Cholmod() {
    cholmod_start(&common);
    common.final_asis = 1;
    common.supernodal = CHOLMOD_SUPERNODAL;
    // Errors only: a matrix that is not positive definite is a warning to CHOLMOD, and
    // factorize() reports it with the unknown and block where it failed.
    common.print = 1;
    relax_supernodes(common);
  }
  ~Cholmod() {
    for (cholmod_dense** d : {&solution, &work_y, &work_e})
      if (*d) cholmod_free_dense(d, &common);
    free_modified();
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
  Cholmod(const Cholmod&) = delete;
  Cholmod& operator=(const Cholmod&) = delete;
  void free_modified() {
    if (modified) cholmod_free_factor(&modified, &common);
  }
  cholmod_factor* active() const { return modified ? modified : factor; }
};

SpdSolver::SpdSolver() : cholmod_(std::make_unique<Cholmod>()) {}
SpdSolver::~SpdSolver() = default;
SpdSolver::SpdSolver(SpdSolver&&) noexcept = default;
SpdSolver& SpdSolver::operator=(SpdSolver&&) noexcept = default;

void SpdSolver::factorize(const Eigen::SparseMatrix<double>& lower) {
  const auto start = std::chrono::steady_clock::now();
  Cholmod& c = *cholmod_;
  c.free_modified();
  modified_springs_.clear();
  woodbury_solutions_.resize(0, 0);
  cholmod_sparse a = view_lower(lower);
  if (!analysed_) {
    if (c.factor) cholmod_free_factor(&c.factor, &c.common);
    c.factor = cholmod_analyze(&a, &c.common);
    if (!c.factor) throw std::runtime_error("CHOLMOD's symbolic analysis of K failed");
    const int* perm = static_cast<const int*>(c.factor->Perm);
    c.new_row.assign(c.factor->n, 0);
    for (std::size_t k = 0; k < c.factor->n; ++k) c.new_row[perm[k]] = static_cast<int>(k);
    analysed_ = true;
  }
  cholmod_factorize(&a, c.factor, &c.common);
  factorization_seconds_ += seconds_since(start);
  ++factorizations_;
  failed_unknown_ = -1;
  if (c.factor->minor != c.factor->n) {
    // minor: the first column of the permuted matrix without a positive pivot.
    failed_unknown_ = static_cast<const int*>(c.factor->Perm)[c.factor->minor];
    throw ConvergenceError("the block stiffness matrix K is not positive definite (CHOLMOD factorisation failed)");
  }
}

bool SpdSolver::modify(const std::vector<SpringTerm>& changes, LowRankMethod method) {
  if (changes.empty()) return true;
  const auto start = std::chrono::steady_clock::now();
  Cholmod& c = *cholmod_;
  if (!c.factor || !analysed_) throw std::logic_error("SpdSolver::modify before factorize");
  const bool woodbury = method == LowRankMethod::woodbury;
  if (!modified_springs_.empty() && woodbury == (c.modified != nullptr))
    throw std::logic_error("SpdSolver::modify: one method between two factorisations");
  const int first = modified_rank();
  const int r = static_cast<int>(changes.size());
  modified_springs_.insert(modified_springs_.end(), changes.begin(), changes.end());
  bool ok = true;
  if (woodbury) {
    // W's new columns: K0^-1 C for the new springs, one multi-column supernodal solve.
    const int n = static_cast<int>(c.factor->n);
    Eigen::MatrixXd columns = Eigen::MatrixXd::Zero(n, r);
    for (int s = 0; s < r; ++s) {
      const SpringTerm& t = changes[s];
      const double scale = std::sqrt(std::abs(t.stiffness));
      columns.col(s).segment<6>(6 * t.block_a) += scale * t.row_a.transpose();
      columns.col(s).segment<6>(6 * t.block_b) += scale * t.row_b.transpose();
    }
    woodbury_solutions_.conservativeResize(n, first + r);
    woodbury_solutions_.rightCols(r) = solve_factor(columns);
    // M = D + C^T W (D^-1 = D for D = +-1), symmetric: its new rows and columns.
    const int rank = first + r;
    capacitance_.conservativeResize(rank, rank);
    const Eigen::MatrixXd new_rows = spring_projection(woodbury_solutions_).bottomRows(r);  // C_new^T W
    capacitance_.bottomRows(r) = new_rows;
    capacitance_.rightCols(r) = new_rows.transpose();
    for (int s = first; s < rank; ++s) capacitance_(s, s) += modified_springs_[s].stiffness > 0.0 ? 1.0 : -1.0;
    capacitance_lu_.compute(capacitance_);
    // A singular M: the modified K is singular (a downdate removed what held a block).
    ok = std::isfinite(capacitance_lu_.rcond()) && capacitance_lu_.rcond() > 1e-14;
  } else {
    if (!c.modified) {
      // cholmod_updown works on a simplicial LDL' factor: convert a copy, so that the
      // supernodal factor keeps its storage for the next factorisation.
      c.modified = cholmod_copy_factor(c.factor, &c.common);
      cholmod_change_factor(CHOLMOD_REAL, false, false, true, true, c.modified, &c.common);
    }
    // Updates first: the matrix stays positive definite in between.
    for (const bool update : {true, false}) {
      std::vector<const SpringTerm*> part;
      for (const SpringTerm& t : changes)
        if ((t.stiffness > 0.0) == update) part.push_back(&t);
      if (part.empty()) continue;
      // C (permuted like the factor): column s holds sqrt(|k|) e of spring s.
      const int columns_count = static_cast<int>(part.size());
      cholmod_sparse* columns = cholmod_allocate_sparse(c.modified->n, columns_count, 12 * part.size(), true, true,
                                                        0, CHOLMOD_REAL, &c.common);
      int* p = static_cast<int*>(columns->p);
      int* i = static_cast<int*>(columns->i);
      double* x = static_cast<double*>(columns->x);
      std::array<std::pair<int, double>, 12> entries;
      int nz = 0;
      for (int s = 0; s < columns_count; ++s) {
        const SpringTerm& t = *part[s];
        const double scale = std::sqrt(std::abs(t.stiffness));
        for (int a = 0; a < 6; ++a) {
          entries[a] = {c.new_row[6 * t.block_a + a], scale * t.row_a[a]};
          entries[6 + a] = {c.new_row[6 * t.block_b + a], scale * t.row_b[a]};
        }
        std::sort(entries.begin(), entries.end());
        p[s] = nz;
        for (const auto& [row, value] : entries) i[nz] = row, x[nz++] = value;
      }
      p[columns_count] = nz;
      ok = ok && cholmod_updown(update, columns, c.modified, &c.common) && c.common.status == CHOLMOD_OK &&
           c.modified->minor == c.modified->n;
      cholmod_free_sparse(&columns, &c.common);
    }
  }
  modification_seconds_ += seconds_since(start);
  return ok;
}

Eigen::MatrixXd SpdSolver::spring_projection(const Eigen::MatrixXd& y) const {
  Eigen::MatrixXd projection(modified_rank(), y.cols());
  for (int s = 0; s < modified_rank(); ++s) {
    const SpringTerm& t = modified_springs_[s];
    projection.row(s) = std::sqrt(std::abs(t.stiffness)) * (t.row_a * y.middleRows<6>(6 * t.block_a) +
                                                  t.row_b * y.middleRows<6>(6 * t.block_b));
  }
  return projection;
}

Eigen::VectorXd SpdSolver::woodbury_check_solve(const Eigen::VectorXd& x_exact) const {
  Eigen::VectorXd dct = spring_projection(x_exact);  // D C^T x
  for (int s = 0; s < modified_rank(); ++s)
    if (modified_springs_[s].stiffness < 0.0) dct[s] = -dct[s];
  const Eigen::VectorXd y = x_exact + woodbury_solutions_ * dct;
  return y - woodbury_solutions_ * capacitance_lu_.solve(spring_projection(y));
}

Eigen::MatrixXd SpdSolver::solve_capacitance(const Eigen::MatrixXd& v) const { return capacitance_lu_.solve(v); }

std::size_t SpdSolver::factor_entries() const {
  const cholmod_factor* f = cholmod_->active();
  if (!f) return 0;
  return f->is_super ? f->xsize : f->nzmax;
}

const double* SpdSolver::solve_factor_in_place(const double* rhs, int rows) const {
  Cholmod& c = *cholmod_;
  cholmod_dense b = view_dense(rhs, rows, 1);
  if (!cholmod_solve2(CHOLMOD_A, c.active(), &b, nullptr, &c.solution, nullptr, &c.work_y, &c.work_e, &c.common))
    throw std::runtime_error("CHOLMOD's solve failed");
  return static_cast<const double*>(c.solution->x);
}

Eigen::MatrixXd SpdSolver::solve_factor(const Eigen::MatrixXd& rhs) const {
  if (rhs.cols() == 1) {
    const double* x = solve_factor_in_place(rhs.data(), static_cast<int>(rhs.rows()));
    return Eigen::Map<const Eigen::MatrixXd>(x, rhs.rows(), 1);
  }
  // Several columns: a workspace for this solve only, so that the one kept for the
  // single solves of the contact iterations does not grow to the widest block solved.
  Cholmod& c = *cholmod_;
  cholmod_dense b = view_dense(rhs.data(), static_cast<int>(rhs.rows()), static_cast<int>(rhs.cols()));
  cholmod_dense *x = nullptr, *y = nullptr, *e = nullptr;
  const bool ok = cholmod_solve2(CHOLMOD_A, c.active(), &b, nullptr, &x, nullptr, &y, &e, &c.common);
  Eigen::MatrixXd result;
  if (ok) result = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(x->x), rhs.rows(), rhs.cols());
  for (cholmod_dense** d : {&x, &y, &e})
    if (*d) cholmod_free_dense(d, &c.common);
  if (!ok) throw std::runtime_error("CHOLMOD's solve failed");
  return result;
}

Eigen::VectorXd SpdSolver::solve(const Eigen::VectorXd& rhs) const {
  const double* x = solve_factor_in_place(rhs.data(), static_cast<int>(rhs.size()));
  Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(x, rhs.size());
  if (woodbury_solutions_.cols() > 0) y.noalias() -= woodbury_solutions_ * capacitance_lu_.solve(spring_projection(y));
  return y;
}

Eigen::MatrixXd SpdSolver::solve(const Eigen::MatrixXd& rhs) const {
  Eigen::MatrixXd y = solve_factor(rhs);
  if (woodbury_solutions_.cols() > 0) y.noalias() -= woodbury_solutions_ * capacitance_lu_.solve(spring_projection(y));
  return y;
}

}  // namespace hfdda::dda
