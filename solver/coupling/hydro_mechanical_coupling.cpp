#include "coupling/hydro_mechanical_coupling.hpp"

#include <algorithm>
#include <chrono>

namespace hfdda::coupling {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}
/// Right-hand sides per multi-column solve: bounds the dense block to 6 nb x 64.
constexpr int kColumnsPerSolve = 64;
}  // namespace

HydroMechanicalCoupling::HydroMechanicalCoupling(fluid::FlowNetwork& network, FlowJacobian jacobian)
    : network_(network), jacobian_(jacobian), pressurised_(network.n_points(), 0) {}

void HydroMechanicalCoupling::refresh_pressurised() {
  std::fill(pressurised_.begin(), pressurised_.end(), 0);
  for (int point : network_.trial_nodes()) pressurised_[point] = network_.trial_pressurised(point);
}

void HydroMechanicalCoupling::begin_step(dda::BlockSystem& system, double dt_s) {
  if (system.mesh().joints.size() != static_cast<std::size_t>(network_.n_fractures()))
    throw std::invalid_argument("HydroMechanicalCoupling: the network's fractures must be the mesh joints");
  stats_ = {};
  network_.begin_step(dt_s);
  topology_changed_ = true;
  refresh_pressurised();
}

Eigen::VectorXd HydroMechanicalCoupling::end_gaps(const Eigen::VectorXd& u) const {
  Eigen::VectorXd out(gaps_.size());
  for (std::size_t e = 0; e < gaps_.size(); ++e) {
    const auto& g = gaps_[e];
    out[e] = g.row_a.dot(u.segment<6>(6 * g.block_a)) + g.row_b.dot(u.segment<6>(6 * g.block_b));
  }
  return out;
}

Eigen::MatrixXd HydroMechanicalCoupling::end_gaps_of(const Eigen::MatrixXd& u) const {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(gaps_.size()), u.cols());
  for (std::size_t e = 0; e < gaps_.size(); ++e) {
    const auto& g = gaps_[e];
    out.row(static_cast<Eigen::Index>(e)) = g.row_a * u.middleRows<6>(6 * g.block_a) + g.row_b * u.middleRows<6>(6 * g.block_b);
  }
  return out;
}

const Eigen::VectorXd& HydroMechanicalCoupling::pressure_load(const dda::BlockSystem& system,
                                                              const Eigen::VectorXd& p) {
  work_.setZero(6 * system.n_blocks());
  for (int i = 0; i < p.size(); ++i)
    for (const NodeLoad& l : loads_[i]) work_.segment<6>(6 * l.block) += p[i] * l.force;
  return work_;
}

void HydroMechanicalCoupling::prepare(const dda::BlockSystem& system, bool stiffness_changed) {
  if (!stiffness_changed && !topology_changed_) return;
  pressure_response_valid_ = false;
  const dda::SpdSolver& solver = system.solver();
  const auto start = Clock::now();
  const auto& fractures = network_.trial_fractures();
  const auto& nodes = network_.trial_nodes();
  const int nf = static_cast<int>(fractures.size());
  const int n = static_cast<int>(nodes.size());
  const int nb = system.n_blocks();
  stats_.max_nodes = std::max(stats_.max_nodes, n);

  gaps_.resize(2 * nf);
  for (int k = 0; k < nf; ++k)
    for (int end = 0; end < 2; ++end) gaps_[2 * k + end] = system.joint_end_gap(fractures[k], end);

  // B: block forces per unit nodal pressure, from the trapezoidal face loads.
  work_.setZero(6 * nb);
  loads_.assign(n, {});
  for (int k = 0; k < nf; ++k) {
    const int j = fractures[k];
    const auto& joint = system.mesh().joints[j];
    const int blocks[2] = {joint.block_a, joint.block_b};
    for (int end = 0; end < 2; ++end) {
      const int node = network_.node_index(end == 0 ? joint.point_p : joint.point_q);
      system.add_joint_pressure_load(j, end == 0 ? 1.0 : 0.0, end == 0 ? 0.0 : 1.0, work_);
      for (int b : blocks) {
        loads_[node].push_back({b, work_.segment<6>(6 * b)});
        work_.segment<6>(6 * b).setZero();
      }
    }
  }

  if (use_operator(n)) {
    nodes_of_fracture_.resize(nf);  // the network's connectivity, for the operator's aggregates
    for (int k = 0; k < nf; ++k) {
      const auto& joint = system.mesh().joints[fractures[k]];
      nodes_of_fracture_[k] = {network_.node_index(joint.point_p), network_.node_index(joint.point_q)};
    }
    operator_ = std::make_unique<ApertureOperator>(
        system, gaps_, loads_, nodes_of_fracture_, near_field_hops_,
        jacobian_ == FlowJacobian::krylov ? FlowLinearSolve::gmres : FlowLinearSolve::augmented);
    sensitivity_.resize(0, 0);
    sensitivity_version_ = -1;
    // The dense path's X (flow_jacobian auto, a network that grew past the bound) is not
    // used again: its memory is freed.
    responses_.resize(0, 0);
    response_version_ = -1;
    topology_changed_ = false;
    stats_.seconds_sensitivity += seconds_since(start);
    return;
  }
  operator_.reset();
  last_update_size_ = 0.0;
  if (system.settings().converged_response()) {
    // S_c from K with the iterated springs stiffened: respond() then shifts the base.
    response_version_ = -1;
    form_sensitivity(system, system.converged_response_solver(), false);
  } else {
    const double bytes = 6.0 * nb * n * sizeof(double);
    form_sensitivity(system, solver, bytes <= max_response_bytes_);
  }
  topology_changed_ = false;
  stats_.seconds_sensitivity += seconds_since(start);
}

void HydroMechanicalCoupling::form_sensitivity(const dda::BlockSystem& system, const dda::SpdSolver& solver,
                                               bool keep) {
  const auto& nodes = network_.trial_nodes();
  const int n = static_cast<int>(nodes.size());
  const int rows = 6 * system.n_blocks();
  const bool own_factor = &solver == &system.solver();  // not the converged response's
  if (!keep) {
    response_version_ = -1;
    // Too large to keep X: S itself follows the springs changed in K, where it can.
    if (own_factor && update_sensitivity(system)) {
      ++stats_.sensitivity_corrections;
      return;
    }
  }
  sensitivity_version_ = -1;
  if (response_version_ >= 0 && response_version_ != system.stiffness_version() && !update_responses(system))
    response_version_ = -1;

  // Columns of X: kept where the node's loads are those X was solved for, solved otherwise.
  std::vector<int> kept_column(n, -1), to_solve;
  if (response_version_ >= 0) {
    std::vector<int> column_of_point(network_.n_points(), -1);
    for (std::size_t c = 0; c < response_points_.size(); ++c) column_of_point[response_points_[c]] = static_cast<int>(c);
    const auto same = [](const NodeLoad& a, const NodeLoad& b) { return a.block == b.block && a.force == b.force; };
    for (int i = 0; i < n; ++i) {
      const int c = column_of_point[nodes[i]];
      if (c >= 0 && std::equal(loads_[i].begin(), loads_[i].end(), response_loads_[c].begin(),
                               response_loads_[c].end(), same))
        kept_column[i] = c;
    }
  }
  for (int i = 0; i < n; ++i)
    if (kept_column[i] < 0) to_solve.push_back(i);
  if (to_solve.size() < static_cast<std::size_t>(n)) ++stats_.sensitivity_corrections;
  else ++stats_.sensitivity_builds;
  stats_.response_columns_solved += static_cast<int>(to_solve.size());

  // Every kept column where it was (the network grew by new nodes at the end, or did
  // not change): X is extended where it is, without a second copy of it.
  bool in_place = keep && response_version_ >= 0 && responses_.cols() <= n;
  for (int i = 0; in_place && i < n; ++i) in_place = kept_column[i] == i || kept_column[i] < 0;
  Eigen::MatrixXd x_new;
  if (in_place) {
    if (responses_.cols() < n) responses_.conservativeResize(Eigen::NoChange, n);
    x_new.swap(responses_);
  } else if (keep) {
    x_new.resize(rows, n);
    for (int i = 0; i < n; ++i)
      if (kept_column[i] >= 0) x_new.col(i) = responses_.col(kept_column[i]);
  }
  const auto project = [this](const Eigen::MatrixXd& x, std::size_t e, Eigen::Index col) {
    const auto& g = gaps_[e];
    return g.row_a.dot(x.col(col).segment<6>(6 * g.block_a)) + g.row_b.dot(x.col(col).segment<6>(6 * g.block_b));
  };
  sensitivity_.setZero(static_cast<Eigen::Index>(gaps_.size()), n);
  Eigen::MatrixXd rhs;
  for (std::size_t first = 0; first < to_solve.size(); first += kColumnsPerSolve) {
    const int cols = static_cast<int>(std::min<std::size_t>(kColumnsPerSolve, to_solve.size() - first));
    rhs.setZero(rows, cols);
    for (int c = 0; c < cols; ++c)
      for (const NodeLoad& l : loads_[to_solve[first + c]]) rhs.block<6, 1>(6 * l.block, c) += l.force;
    const Eigen::MatrixXd x = solver.solve(rhs);
    for (int c = 0; c < cols; ++c) {
      const int i = to_solve[first + c];
      if (keep) {
        x_new.col(i) = x.col(c);
      } else {
        for (std::size_t e = 0; e < gaps_.size(); ++e) sensitivity_(e, i) = project(x, e, c);
      }
    }
  }
  if (!keep) {
    if (own_factor) {
      sensitivity_version_ = system.stiffness_version();
      sensitivity_fractures_ = network_.trial_fractures();
      sensitivity_points_ = nodes;
    }
    return;
  }
  for (int i = 0; i < n; ++i)
    for (std::size_t e = 0; e < gaps_.size(); ++e) sensitivity_(e, i) = project(x_new, e, i);
  responses_.swap(x_new);
  response_points_ = nodes;
  response_loads_ = loads_;
  response_version_ = system.stiffness_version();
}

bool HydroMechanicalCoupling::stiffness_change(const dda::BlockSystem& system, int version,
                                               const std::vector<std::vector<NodeLoad>>& loads, int max_springs,
                                               Eigen::MatrixXd& y, Eigen::MatrixXd& coefficients) const {
  std::vector<dda::SpringTerm> changes;
  if (!system.spring_changes_since(version, changes)) return false;
  const int r = static_cast<int>(changes.size());
  const int n = static_cast<int>(loads.size());
  // r solves and a product of r columns, against solving the n columns anew.
  if (r >= max_springs) return false;
  y.resize(0, 0);
  coefficients.resize(0, 0);
  if (r == 0) return true;
  const int rows = 6 * system.n_blocks();
  // K_new = K_old + C D C^T, column s of C: sqrt(|k_s|) e_s, D = sign(k_s). With
  // Y = K_new^-1 C: K_new^-1 = K_old^-1 - Y N^-1 Y^T, N = D - C^T Y.
  {
    Eigen::MatrixXd c = Eigen::MatrixXd::Zero(rows, r);  // freed once Y is solved
    for (int k = 0; k < r; ++k) {
      const dda::SpringTerm& t = changes[k];
      const double scale = std::sqrt(std::abs(t.stiffness));
      c.col(k).segment<6>(6 * t.block_a) += scale * t.row_a.transpose();
      c.col(k).segment<6>(6 * t.block_b) += scale * t.row_b.transpose();
    }
    y = system.solver().solve(c);
  }
  Eigen::MatrixXd nmat(r, r);
  for (int k = 0; k < r; ++k) {
    const dda::SpringTerm& t = changes[k];
    const double scale = std::sqrt(std::abs(t.stiffness));
    nmat.row(k) = -scale * (t.row_a * y.middleRows<6>(6 * t.block_a) + t.row_b * y.middleRows<6>(6 * t.block_b));
    nmat(k, k) += t.stiffness > 0.0 ? 1.0 : -1.0;
  }
  Eigen::MatrixXd ytb = Eigen::MatrixXd::Zero(r, n);  // Y^T B for the given loads
  for (int i = 0; i < n; ++i)
    for (const NodeLoad& l : loads[i]) ytb.col(i).noalias() += y.middleRows<6>(6 * l.block).transpose() * l.force;
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(nmat);
  if (!(lu.rcond() > 1e-14)) return false;  // the new K singular where the springs act
  coefficients = lu.solve(ytb);             // N^-1 Y^T B, r x n
  return true;
}

bool HydroMechanicalCoupling::update_responses(const dda::BlockSystem& system) {
  Eigen::MatrixXd y, coefficients;
  const int n = static_cast<int>(responses_.cols());
  if (!stiffness_change(system, response_version_, response_loads_, n, y, coefficients)) return false;
  if (y.cols() > 0) {
    const int rows = static_cast<int>(responses_.rows());
    responses_.noalias() -= y * coefficients;  // no temporary of X's size
    // Checked like a corrected factorisation (dda/low_rank_updates.cpp): K X v = B v.
    Eigen::VectorXd bv = Eigen::VectorXd::Zero(rows);
    for (int i = 0; i < n; ++i)
      for (const NodeLoad& l : response_loads_[i]) bv.segment<6>(6 * l.block) += l.force;
    const Eigen::VectorXd xv = responses_.rowwise().sum();
    const double residual = (system.stiffness().multiply(xv) - bv).norm() / bv.norm();
    if (!(residual <= kResponseResidual)) return false;
    // For tests: how far the update moved S, max |J Y N^-1 Y^T B|.
    const Eigen::MatrixXd jy = end_gaps_of(y);
    const double moved = gaps_.empty() ? 0.0 : (jy * coefficients).cwiseAbs().maxCoeff();
    const double scale = sensitivity_.size() > 0 ? sensitivity_.cwiseAbs().maxCoeff() : 0.0;
    last_update_size_ = scale > 0.0 ? moved / scale : 0.0;
  }
  response_version_ = system.stiffness_version();
  return true;
}

bool HydroMechanicalCoupling::update_sensitivity(const dda::BlockSystem& system) {
  const int n = static_cast<int>(loads_.size());
  if (sensitivity_version_ < 0 || sensitivity_.cols() != n || sensitivity_fractures_ != network_.trial_fractures() ||
      sensitivity_points_ != network_.trial_nodes())
    return false;
  Eigen::MatrixXd y, coefficients;
  // C and Y (6 nb x r each) are held by the update: no more springs than fit the bound of X.
  const double column_bytes = 6.0 * system.n_blocks() * sizeof(double);
  const int max_springs = static_cast<int>(std::min<double>(n, kMaxResponseBytes / column_bytes));
  if (!stiffness_change(system, sensitivity_version_, loads_, max_springs, y, coefficients)) return false;
  if (y.cols() > 0) {
    const Eigen::MatrixXd change = end_gaps_of(y) * coefficients;  // J Y N^-1 Y^T B
    // Checked against one solve with the new factor: S v = J K^-1 B v, v all ones.
    const Eigen::VectorXd reference = end_gaps(system.solver().solve(pressure_load(system, Eigen::VectorXd::Ones(n))));
    const Eigen::VectorXd updated_sum = sensitivity_.rowwise().sum() - change.rowwise().sum();
    const double error = (updated_sum - reference).norm() / reference.norm();
    if (!(error <= kResponseResidual)) return false;
    const double scale = sensitivity_.cwiseAbs().maxCoeff();
    last_update_size_ = scale > 0.0 ? change.cwiseAbs().maxCoeff() / scale : 0.0;
    sensitivity_ -= change;
    stats_.response_columns_solved += static_cast<int>(y.cols()) + 1;
  }
  sensitivity_version_ = system.stiffness_version();
  return true;
}

bool HydroMechanicalCoupling::responses_apply(const dda::BlockSystem& system) const {
  if (response_version_ < 0 || response_version_ != system.stiffness_version()) return false;
  if (responses_.cols() != network_.trial_pressure().size()) return false;
  return static_cast<double>(responses_.size()) <= 2.0 * static_cast<double>(system.solver().factor_entries());
}

void HydroMechanicalCoupling::respond(const dda::BlockSystem& system, Eigen::VectorXd& d) {
  const auto start = Clock::now();
  const int n_ends = static_cast<int>(gaps_.size());
  Eigen::VectorXd base(n_ends);
  for (int e = 0; e < n_ends; ++e) {
    const auto& g = gaps_[e];
    base[e] = g.gap0_m + g.row_a.dot(d.segment<6>(6 * g.block_a)) +
              g.row_b.dot(d.segment<6>(6 * g.block_b));
  }
  if (system.settings().converged_response() && !operator_) {
    // S is the converged contact problem's response S_c, the base that of K at this
    // iteration's multipliers: linearise about the pressures p_ref of the last flow solve,
    // w(p) = base + J K^-1 B p_ref + S_c (p - p_ref), so that where the multipliers have
    // converged (p = p_ref) the flow solve sees the apertures K gives.
    // J K^-1 B p_ref is the last respond()'s, unless K or the network changed since.
    const Eigen::VectorXd& p_ref = network_.trial_pressure();
    if (!pressure_response_valid_) pressure_response_ = end_gaps(system.solver().solve(pressure_load(system, p_ref)));
    base += pressure_response_;
    base.noalias() -= sensitivity_ * p_ref;
  }
  fluid::FlowSolveStatistics fs;
  if (operator_) {
    const long products = operator_->products(), iterations = operator_->linear_iterations(),
               inexact = operator_->inexact_solves();
    fs = network_.solve(base, *operator_);
    stats_.sensitivity_products += operator_->products() - products;
    stats_.krylov_iterations += operator_->linear_iterations() - iterations;
    stats_.inexact_linear_solves += operator_->inexact_solves() - inexact;
  } else {
    fs = network_.solve(base, sensitivity_);
  }
  ++stats_.flow_solves;
  stats_.newton_iterations += fs.newton_iterations;
  stats_.newton_restarts += fs.restarts;
  stats_.max_relative_residual = std::max(stats_.max_relative_residual, fs.max_relative_residual);
  refresh_pressurised();

  const Eigen::VectorXd& p = network_.trial_pressure();
  Eigen::VectorXd pressure_displacement;
  if (responses_apply(system)) {
    pressure_displacement.noalias() = responses_ * p;
    ++stats_.response_products;
  } else {
    pressure_displacement = system.solver().solve(pressure_load(system, p));
  }
  d += pressure_displacement;  // the mechanical displacement plus K^-1 B p
  if (system.settings().converged_response() && !operator_) {
    pressure_response_ = end_gaps(pressure_displacement);
    pressure_response_valid_ = true;
  }
  stats_.seconds_flow += seconds_since(start);
}

int HydroMechanicalCoupling::update_states(const dda::BlockSystem& system) {
  // Figure 2.8: a joint whose contact is open at a pressurised node takes in fluid; a
  // joint with a hydraulic width w0 (a natural fracture, seed 5.2) takes it in at a
  // pressurised node whether open or not: the fluid invades it through w0.
  int changes = 0;
  const auto& joints = system.mesh().joints;
  for (int j = 0; j < static_cast<int>(joints.size()); ++j) {
    if (network_.wetted_in_trial(j)) continue;
    const bool conducts_closed = network_.fracture(j).hydraulic_width_m > 0.0;
    for (int end = 0; end < 2; ++end) {
      const int point = end == 0 ? joints[j].point_p : joints[j].point_q;
      if (!pressurised_[point]) continue;
      if (!conducts_closed && system.joint_end_state(j, end) != dda::ContactState::open) continue;
      if (network_.wet(j)) ++changes;
      break;
    }
  }
  if (changes > 0) {
    topology_changed_ = true;
    stats_.fractures_wetted += changes;
  }
  return changes;
}

void HydroMechanicalCoupling::commit(const dda::BlockSystem&) {
  network_.commit();
  refresh_pressurised();
}

void HydroMechanicalCoupling::roll_back() { topology_changed_ = true; }

void HydroMechanicalCoupling::add_statistics(StepStatistics& step) const {
  step.fractures_wetted += stats_.fractures_wetted;
  step.flow_solves += stats_.flow_solves;
  step.flow_newton_iterations += stats_.newton_iterations;
  step.flow_newton_restarts += stats_.newton_restarts;
  step.flow_krylov_iterations += stats_.krylov_iterations;
  step.flow_inexact_linear_solves += stats_.inexact_linear_solves;
  step.max_flow_nodes = std::max(step.max_flow_nodes, stats_.max_nodes);
  step.max_flow_residual = std::max(step.max_flow_residual, stats_.max_relative_residual);
  step.seconds_sensitivity += stats_.seconds_sensitivity;
  step.sensitivity_builds += stats_.sensitivity_builds;
  step.sensitivity_corrections += stats_.sensitivity_corrections;
  step.seconds_flow += stats_.seconds_flow;
}

}  // namespace hfdda::coupling
