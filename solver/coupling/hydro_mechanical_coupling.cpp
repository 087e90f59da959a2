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

  if (use_krylov()) {
    nodes_of_fracture_.resize(nf);  // the network's connectivity, for the operator's aggregates
    for (int k = 0; k < nf; ++k) {
      const auto& joint = system.mesh().joints[fractures[k]];
      nodes_of_fracture_[k] = {network_.node_index(joint.point_p), network_.node_index(joint.point_q)};
    }
    operator_ = std::make_unique<ApertureOperator>(system, gaps_, loads_, nodes_of_fracture_);
    sensitivity_.resize(0, 0);
    topology_changed_ = false;
    stats_.seconds_sensitivity += seconds_since(start);
    return;
  }
  operator_.reset();
  const bool converged_response = system.settings().converged_response();
  if (!topology_changed_ && !converged_response && correct_sensitivity(solver)) {
    ++stats_.sensitivity_corrections;
    stats_.seconds_sensitivity += seconds_since(start);
    return;
  }

  // S = J K^-1 B, a few dozen columns per solve; with K's iterated springs stiffened,
  // the response of the converged contact problem (respond() then shifts the base).
  const dda::SpdSolver& response = converged_response ? system.converged_response_solver() : solver;
  sensitivity_.setZero(2 * nf, n);
  Eigen::MatrixXd rhs;
  for (int first = 0; first < n; first += kColumnsPerSolve) {
    const int cols = std::min(kColumnsPerSolve, n - first);
    rhs.setZero(6 * nb, cols);
    for (int c = 0; c < cols; ++c)
      for (const NodeLoad& l : loads_[first + c]) rhs.block<6, 1>(6 * l.block, c) += l.force;
    const Eigen::MatrixXd x = response.solve(rhs);
    for (int e = 0; e < 2 * nf; ++e) {
      const auto& g = gaps_[e];
      sensitivity_.row(e).segment(first, cols) =
          g.row_a * x.middleRows<6>(6 * g.block_a) + g.row_b * x.middleRows<6>(6 * g.block_b);
    }
  }
  if (converged_response) {
    base_factorization_ = -1;  // S_c is not corrected for low-rank changes of K
  } else {
    // The base of later corrections: S of the factorised K0, without this K's changes.
    sensitivity_base_ = sensitivity_;
    if (solver.modified_rank() > 0) sensitivity_base_ += low_rank_correction(solver);
    base_factorization_ = solver.factorizations();
    base_gaps_ = gaps_;
  }
  ++stats_.sensitivity_builds;
  topology_changed_ = false;
  stats_.seconds_sensitivity += seconds_since(start);
}

bool HydroMechanicalCoupling::correct_sensitivity(const dda::SpdSolver& solver) {
  const int rank = solver.modified_rank();
  if (base_factorization_ != solver.factorizations() || rank == 0 ||
      solver.woodbury_solutions().cols() != rank || base_gaps_.size() != gaps_.size() ||
      sensitivity_base_.cols() != static_cast<Eigen::Index>(loads_.size()))
    return false;
  for (std::size_t e = 0; e < gaps_.size(); ++e) {
    const dda::JointEndGap& a = gaps_[e];
    const dda::JointEndGap& b = base_gaps_[e];
    if (a.block_a != b.block_a || a.block_b != b.block_b || a.row_a != b.row_a || a.row_b != b.row_b) return false;
  }
  sensitivity_ = sensitivity_base_ - low_rank_correction(solver);
  return true;
}

Eigen::MatrixXd HydroMechanicalCoupling::low_rank_correction(const dda::SpdSolver& solver) const {
  // K^-1 = K0^-1 - W M^-1 W^T with W = K0^-1 C: S = J K0^-1 B - (J W) M^-1 (W^T B).
  const Eigen::MatrixXd& w = solver.woodbury_solutions();
  const int n_ends = static_cast<int>(gaps_.size());
  const int n_nodes = static_cast<int>(loads_.size());
  Eigen::MatrixXd jw(n_ends, w.cols());
  for (int e = 0; e < n_ends; ++e) {
    const auto& g = gaps_[e];
    jw.row(e) = g.row_a * w.middleRows<6>(6 * g.block_a) + g.row_b * w.middleRows<6>(6 * g.block_b);
  }
  Eigen::MatrixXd wtb = Eigen::MatrixXd::Zero(w.cols(), n_nodes);
  for (int i = 0; i < n_nodes; ++i)
    for (const NodeLoad& l : loads_[i]) wtb.col(i).noalias() += w.middleRows<6>(6 * l.block).transpose() * l.force;
  return jw * solver.solve_capacitance(wtb);
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
  const Eigen::VectorXd pressure_displacement = system.solver().solve(pressure_load(system, p));
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
