#include "coupling/aperture_operator.hpp"

#include <unsupported/Eigen/IterativeSolvers>

#include <algorithm>
#include <cmath>
#include <deque>

#include "core/errors.hpp"

namespace hfdda::coupling {

namespace {
constexpr int kMaxLinearIterations = 400;
/// Never restarted: a product with S (a solve with K) costs far more than keeping and
/// applying every Krylov vector (400 of them on 10,585 nodes take 34 MB, and an
/// iteration took 0.15 s there unrestarted, 0.14 s restarted). Restarted every 80
/// iterations, GMRES stalled on the scaling benchmark's 10,585-node network (a relative
/// residual of 0.9 after 400 iterations) where it converges unrestarted in about 200
/// (design notes 45).
constexpr int kRestart = kMaxLinearIterations;
/// Right-hand sides per solve when S P and the near field are formed.
constexpr int kColumnsPerSolve = 64;

/// The Jacobian and the preconditioner in the forms Eigen's GMRES expects.
struct JacobianProduct {
  const ApertureOperator* op;
  Eigen::Index rows() const { return op->n_nodes(); }
  Eigen::Index cols() const { return op->n_nodes(); }
  Eigen::VectorXd operator*(const Eigen::VectorXd& v) const { return op->jacobian_times(v); }
};
/// Per node, the nodes one fracture away.
std::vector<std::vector<int>> network_neighbours(int n_nodes, const std::vector<std::array<int, 2>>& nodes_of_fracture) {
  std::vector<std::vector<int>> neighbours(n_nodes);
  for (const auto& [a, b] : nodes_of_fracture) {
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  return neighbours;
}
struct TwoLevel {
  const ApertureOperator* op;
  Eigen::VectorXd solve(const Eigen::VectorXd& v) const { return op->precondition(v); }
};
}  // namespace

ApertureOperator::ApertureOperator(const dda::BlockSystem& system, const std::vector<dda::JointEndGap>& gaps,
                                   const std::vector<std::vector<NodeLoad>>& loads,
                                   const std::vector<std::array<int, 2>>& nodes_of_fracture, int near_hops,
                                   FlowLinearSolve linear_solve)
    : system_(system), gaps_(gaps), loads_(loads) {
  build_aggregates(nodes_of_fracture);
  rhs_.setZero(6 * system_.n_blocks());
  if (linear_solve == FlowLinearSolve::augmented) {
    // The LU needs neither the coarse space nor the near field; S P is formed only if
    // self_entry is asked for (the pseudo-transient fallback).
    augmented_ = std::make_unique<AugmentedFlowSystem>(system, gaps, loads);
    return;
  }
  if (near_hops > 0) build_near_field(nodes_of_fracture, near_hops);
  form_probes();
}

ApertureOperator::~ApertureOperator() = default;

void ApertureOperator::form_probes() const {
  // S P and the probes of the near field: solves with one right-hand side per aggregate
  // and per colour, kColumnsPerSolve at a time (the block system's unknowns times the
  // columns is what a solve holds, several times over inside CHOLMOD).
  const int m = n_aggregates(), nb = system_.n_blocks(), columns = m + n_colours_;
  s_times_p_.resize(n_ends(), m);
  for (int first = 0; first < columns; first += kColumnsPerSolve) {
    const int width = std::min(kColumnsPerSolve, columns - first);
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(6 * nb, width);
    for (int i = 0; i < n_nodes(); ++i)
      for (const int column : {aggregate_[i], n_colours_ > 0 ? m + colour_[i] : -1})
        if (column >= first && column < first + width)
          for (const NodeLoad& l : loads_[i]) rhs.block<6, 1>(6 * l.block, column - first) += l.force;
    const Eigen::MatrixXd x = system_.solver().solve(rhs);
    for (int e = 0; e < n_ends(); ++e) {
      const auto& g = gaps_[e];
      const Eigen::RowVectorXd row =
          g.row_a * x.middleRows<6>(6 * g.block_a) + g.row_b * x.middleRows<6>(6 * g.block_b);
      for (int c = first; c < std::min(first + width, m); ++c) s_times_p_(e, c) = row[c - first];
      if (n_colours_ > 0)
        for (auto& [node, entry] : near_[e]) {
          const int column = m + colour_[node];
          if (column >= first && column < first + width) entry = row[column - first];
        }
    }
  }
  probes_formed_ = true;
}

void ApertureOperator::build_near_field(const std::vector<std::array<int, 2>>& nodes_of_fracture, int near_hops) {
  const int n = n_nodes();
  const std::vector<std::vector<int>> neighbours = network_neighbours(n, nodes_of_fracture);
  // Nodes within `hops` of `start` (breadth-first), into `found`.
  std::vector<int> seen(n, -1);
  int search = 0;  // stamps the nodes each search has found
  auto within = [&](int start, int hops, std::vector<int>& found) {
    ++search;
    found.assign(1, start);
    seen[start] = search;
    for (std::size_t head = 0, level_end = 1, level = 0; head < found.size() && level < std::size_t(hops); ++level) {
      for (; head < level_end; ++head)
        for (int j : neighbours[found[head]])
          if (seen[j] != search) {
            seen[j] = search;
            found.push_back(j);
          }
      level_end = found.size();
    }
  };
  colour_.assign(n, -1);
  n_colours_ = 0;
  std::vector<int> found;
  std::vector<char> used;
  for (int i = 0; i < n; ++i) {
    within(i, 2 * near_hops, found);
    used.assign(n_colours_ + 1, 0);
    for (int j : found)
      if (colour_[j] >= 0) used[colour_[j]] = 1;
    int c = 0;
    while (used[c]) ++c;
    colour_[i] = c;
    n_colours_ = std::max(n_colours_, c + 1);
  }
  near_.assign(n_ends(), {});
  for (int e = 0; e < n_ends(); ++e) {
    within(nodes_of_fracture[e / 2][e % 2], near_hops, found);
    for (int j : found) near_[e].push_back({j, 0.0});
  }
}

void ApertureOperator::build_aggregates(const std::vector<std::array<int, 2>>& nodes_of_fracture) {
  // Breadth-first along the network from the lowest unassigned node, closing an
  // aggregate at the target size: connected groups of about sqrt(n) / 2 nodes.
  const int n = n_nodes();
  const std::vector<std::vector<int>> neighbours = network_neighbours(n, nodes_of_fracture);
  const int target = std::max(4, static_cast<int>(std::ceil(0.5 * std::sqrt(static_cast<double>(n)))));
  aggregate_.assign(n, -1);
  aggregate_size_.clear();
  for (int seed = 0; seed < n; ++seed) {
    if (aggregate_[seed] >= 0) continue;
    const int id = static_cast<int>(aggregate_size_.size());
    int size = 0;
    std::deque<int> queue{seed};
    aggregate_[seed] = id;
    while (!queue.empty() && size < target) {
      const int i = queue.front();
      queue.pop_front();
      ++size;
      for (int j : neighbours[i])
        if (aggregate_[j] < 0 && size + static_cast<int>(queue.size()) < target) {
          aggregate_[j] = id;
          queue.push_back(j);
        }
    }
    size += static_cast<int>(queue.size());  // assigned but not expanded
    aggregate_size_.push_back(size);
  }
}

void ApertureOperator::apply(const Eigen::VectorXd& p, Eigen::VectorXd& out) const {
  rhs_.setZero();
  for (int i = 0; i < n_nodes(); ++i)
    if (p[i] != 0.0)
      for (const NodeLoad& l : loads_[i]) rhs_.segment<6>(6 * l.block) += p[i] * l.force;
  const Eigen::VectorXd u = system_.solver().solve(rhs_);
  ++products_;
  out.resize(n_ends());
  for (int e = 0; e < n_ends(); ++e) {
    const auto& g = gaps_[e];
    out[e] = g.row_a.dot(u.segment<6>(6 * g.block_a)) + g.row_b.dot(u.segment<6>(6 * g.block_b));
  }
}

double ApertureOperator::self_entry(int end, int node) const {
  if (!probes_formed_) form_probes();
  const int c = aggregate_[node];
  return s_times_p_(end, c) / aggregate_size_[c];
}

void ApertureOperator::factorize(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e,
                                 const Eigen::VectorXd& d) {
  if (augmented_) {  // A, E and d are kept only for GMRES's products with J
    augmented_->factorize(a, e, d);
    return;
  }
  a_ = a, e_ = e, d_ = d;
  const int n = n_nodes(), m = n_aggregates();
  if (n_colours_ > 0) {
    // Local part with the probed near field of S: A + E S_near diag(d). A probe also
    // carries the responses to the colour's far nodes (more than near_hops away); the
    // preconditioner only needs to be close to J, not equal to it.
    std::vector<Eigen::Triplet<double>> near;
    for (int k = 0; k < e_.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(e_, k); it; ++it)
        for (const auto& [node, entry] : near_[it.col()])
          if (d_[node] != 0.0) near.emplace_back(it.row(), node, it.value() * entry * d_[node]);
    Eigen::SparseMatrix<double> local(n, n);
    local.setFromTriplets(near.begin(), near.end());
    local += a_;
    local_lu_.compute(local);
  } else {
    local_lu_.compute(a_);
  }
  if (local_lu_.info() != Eigen::Success) throw ConvergenceError("fluid flow: singular local part of the mass-balance Jacobian");
  // Coarse: P^T A P + P^T E (S P) diag(d_c).
  d_coarse_.setZero(m);
  for (int i = 0; i < n; ++i) d_coarse_[aggregate_[i]] += d_[i] / aggregate_size_[aggregate_[i]];
  Eigen::MatrixXd coarse = Eigen::MatrixXd::Zero(m, m);
  for (int k = 0; k < a_.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(a_, k); it; ++it)
      coarse(aggregate_[it.row()], aggregate_[it.col()]) += it.value();
  Eigen::MatrixXd pe = Eigen::MatrixXd::Zero(m, n_ends());  // P^T E
  for (int k = 0; k < e_.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(e_, k); it; ++it) pe(aggregate_[it.row()], it.col()) += it.value();
  coarse.noalias() += pe * s_times_p_ * d_coarse_.asDiagonal();
  coarse_lu_.compute(coarse);
}

Eigen::VectorXd ApertureOperator::jacobian_times(const Eigen::VectorXd& v) const {
  Eigen::VectorXd w;
  apply(d_.cwiseProduct(v), w);
  return a_ * v + e_ * w;
}

Eigen::VectorXd ApertureOperator::precondition(const Eigen::VectorXd& v) const {
  const int n = n_nodes(), m = n_aggregates();
  Eigen::VectorXd coarse_rhs = Eigen::VectorXd::Zero(m);
  for (int i = 0; i < n; ++i) coarse_rhs[aggregate_[i]] += v[i];
  const Eigen::VectorXd z = coarse_lu_.solve(coarse_rhs);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) y[i] = z[aggregate_[i]];
  // The residual of the coarse correction under the coarse model of J (S P precomputed).
  const Eigen::VectorXd residual = v - a_ * y - e_ * (s_times_p_ * d_coarse_.cwiseProduct(z));
  return y + local_lu_.solve(residual);
}

Eigen::VectorXd ApertureOperator::solve(const Eigen::VectorXd& r, double forcing) {
  if (augmented_) return augmented_->solve(r);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n_nodes());
  Eigen::Index iterations = kMaxLinearIterations;
  double error = forcing;
  Eigen::internal::gmres(JacobianProduct{this}, r, x, TwoLevel{this}, iterations, kRestart, error);
  iterations_ += iterations;
  if (!x.allFinite()) throw ConvergenceError("fluid flow: the Krylov solve of the mass balance diverged");
  if (error > forcing) ++inexact_solves_;  // GMRES stopped at its iteration limit
  return x;
}

}  // namespace hfdda::coupling
