// Contact springs and the contact iterations of one open-close iteration: the spring
// linearisation, K's contact terms, and the Augmented Lagrangian (Uzawa, seed eq.
// 2.19) or penalty right-hand sides and multiplier updates.

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.hpp"
#include "dda/block_system.hpp"

namespace hfdda::dda {

namespace {

/// Largest gap or shear left by stalled Augmented Lagrangian iterations (inconsistent
/// loops of closed contacts, see update_multipliers), relative to the contact's length:
/// 1e-6 is well below the elastic strains of rock under stress (1e-4 at 2.5 MPa and 25 GPa).
constexpr double kAlmStallMismatch = 1.0e-6;

/// The friction of a sliding contact with held springs is iterated with the contact
/// iterations until its normal force changes by at most this fraction between two
/// iterates: the friction force is then within 0.1 % of tan(phi) times the normal force
/// of the solution, well inside the spread of measured friction angles (a degree at
/// 30 degrees is 4 % of tan phi).
constexpr double kFrictionNormalTolerance = 1.0e-3;
/// Iterates after which the friction stops following the normal force within one contact
/// solve and is frozen at its last value (counted: friction_iterations_frozen). The fixed
/// point contracts by 0.001-0.6 per iterate where it converges; where a wedge of sliding
/// contacts amplifies it, it does not, and the open-close iterations must change a state.
constexpr int kMaxFrictionIterations = 30;

void add_spring_to_rhs(Eigen::VectorXd& f, const VertexEdgeSpring& s, double weight, double force_normal,
                       double force_shear) {
  // Pi = w (lambda g + k/2 g^2) with g = g0 + e.D gives F -= w (lambda + k g0) e^T.
  auto fv = f.segment<6>(6 * s.vertex_block);
  auto fe = f.segment<6>(6 * s.edge_block);
  fv -= weight * force_normal * s.gap_vertex.transpose();
  fe -= weight * force_normal * s.gap_edge.transpose();
  fv -= weight * force_shear * s.shear_vertex.transpose();
  fe -= weight * force_shear * s.shear_edge.transpose();
}

}  // namespace

void BlockSystem::rebuild_pattern() {
  stiffness_ = BlockSparseMatrix(n_blocks(), contacts_.couplings());
  solver_.reset_pattern();
  stiffened_solver_.reset_pattern();
  factor_of_this_step_ = false;
  for (auto& c : contacts_.all())
    if (c.joint >= 0 || c.vertex_vertex_active)
      for (int k = 0; k < c.n_springs; ++k)
        c.springs[k].slot = stiffness_.coupling_slot(c.springs[k].vertex_block, c.springs[k].edge_block);
  contacts_.pattern_rebuilt();
}

void BlockSystem::linearise_spring(VertexEdgeSpring& s) const {
  linearise_vertex_edge(corner(s.vertex_block, s.vertex_corner), corner(s.edge_block, s.edge_corner),
                        blocks_.next_corner(s.edge_block, s.edge_corner), moments_[s.vertex_block].centroid,
                        moments_[s.edge_block].centroid, s);
}

void BlockSystem::linearise_contacts() {
  for (auto& c : contacts_.all()) {
    if (c.joint < 0 && !c.vertex_vertex_active) continue;
    for (int k = 0; k < c.n_springs; ++k) linearise_spring(c.springs[k]);
  }
}

void BlockSystem::assemble_contacts() {
  stiffness_.set_zero();
  for (int b = 0; b < n_blocks(); ++b) stiffness_.add_diagonal(b, block_matrix_[b]);
  for (const auto& c : contacts_.all()) {
    if (c.state == ContactState::open) continue;
    const ContactTerms terms = contact_terms(c);
    for (int k = 0; k < 4; ++k) {
      if (!terms.present[k]) continue;
      add_spring_term(stiffness_, c.springs[k / 2].slot, terms.term[k], terms.term[k].stiffness);
    }
  }
  hold_mechanisms();
}

void BlockSystem::add_spring_term(BlockSparseMatrix& matrix, int slot, const SpringTerm& t, double stiffness) {
  matrix.add_diagonal(t.block_a, stiffness * t.row_a.transpose() * t.row_a);
  matrix.add_diagonal(t.block_b, stiffness * t.row_b.transpose() * t.row_b);
  matrix.add_coupling(slot, t.block_a, t.block_b, stiffness * t.row_a.transpose() * t.row_b);
}

double BlockSystem::spring_gap(const VertexEdgeSpring& s, const Eigen::VectorXd& d) const {
  return s.gap0 + s.gap_vertex.dot(d.segment<6>(6 * s.vertex_block)) + s.gap_edge.dot(d.segment<6>(6 * s.edge_block));
}

double BlockSystem::spring_shear(const VertexEdgeSpring& s, const Eigen::VectorXd& d) const {
  return s.shear0 + s.shear_vertex.dot(d.segment<6>(6 * s.vertex_block)) +
         s.shear_edge.dot(d.segment<6>(6 * s.edge_block));
}

void BlockSystem::begin_contact_iterations() {
  // Per contact: k g and k s of its mean gap and shear [N], the multiplier update of
  // this iteration and of the last (for the stall test).
  alm_corrections_.assign(2 * contacts_.size(), 0.0);
  alm_previous_corrections_.assign(2 * contacts_.size(), 0.0);
  alm_worst_contact_ = -1;
  friction_contacts_.clear();
  restart_friction_fixed_point();
}

void BlockSystem::restart_friction_fixed_point() {
  friction_acceleration_.reset();
  friction_accelerated_ = false;
  friction_residual_N_ = -1.0;
}

Eigen::VectorXd BlockSystem::contact_rhs() const {
  Eigen::VectorXd f = step_loads_;
  for (const auto& c : contacts_.all()) {
    if (c.state == ContactState::open) continue;
    const double kn = normal_stiffness(c), ks = shear_stiffness(c);
    const double w = 1.0 / c.n_springs;
    // Sliding: constant friction force opposing slip (Mohr-Coulomb limit) instead of a shear spring.
    // Iterated contacts take their normal force from the multiplier, which follows the
    // solution; held ones from the step's start, or with friction_at_solution from their
    // last iterate (follow_friction_normal_forces).
    double friction = 0.0;
    if (c.state == ContactState::sliding) {
      double normal = 0.0;
      for (int k = 0; k < c.n_springs; ++k) normal += w * (c.springs[k].normal_multiplier_N + kn * c.springs[k].gap0);
      const double compression = c.friction_normal_N >= 0.0 ? c.friction_normal_N : std::max(-normal, 0.0);
      friction = c.friction_sign * (c.cohesion_Pa * c.length_m * c.bonded + compression * c.tan_friction);
    }
    for (int k = 0; k < c.n_springs; ++k) {
      const auto& s = c.springs[k];
      const bool locked = c.state == ContactState::locked;
      add_spring_to_rhs(f, s, w, s.normal_multiplier_N + kn * s.gap0,
                        locked ? s.shear_multiplier_N + ks * s.shear0 : friction);
    }
  }
  return f;
}

bool BlockSystem::follow_friction_normal_forces(const Eigen::VectorXd& d) {
  // Eq. 2.16 asks for the friction of the normal force at the step's solution. A held
  // (penalty) spring's normal force is k g(D): taken at the start of the step, friction
  // lags the normal force by a step, and under a constant load a wedge of sliding
  // contacts winds its forces up from step to step (docs/design_notes.md section 41).
  // Within the contact solve the forces are a fixed point N = G(N) (the solve with the
  // friction of N gives the normal forces G(N)); in a wedge whose friction angle exceeds
  // its angle the plain iteration N <- G(N) diverges with alternating sign although the
  // fixed point exists, so the iterates are accelerated (section 48).
  bool moved = false;
  const double round_off_force = settings_.normal_stiffness_N_m * gap_round_off_m_;
  // Buffers kept between iterates: this runs once per contact iterate.
  std::vector<int>& contacts = friction_scratch_contacts_;
  std::vector<double>& used_forces = friction_used_N_;
  std::vector<double>& now_forces = friction_now_N_;
  contacts.clear();
  used_forces.clear();
  now_forces.clear();
  for (auto& c : contacts_.all()) {
    if (c.state != ContactState::sliding || c.joint < 0 || c.tan_friction == 0.0) continue;
    if (settings_.augmented_lagrangian && iterated(c)) continue;  // the multiplier follows the solution
    const double kn = normal_stiffness(c), w = 1.0 / c.n_springs;
    // The force the last solve used: the last iterate's, or the step's start (gap0) on the
    // first iterate in this state, as contact_rhs takes it.
    const bool first_iterate = c.friction_normal_N < 0.0;
    double normal_now = 0.0, normal_used = 0.0;
    for (int k = 0; k < c.n_springs; ++k) {
      const auto& s = c.springs[k];
      normal_now += w * (s.normal_multiplier_N + kn * spring_gap(s, d));
      if (first_iterate) normal_used += w * (s.normal_multiplier_N + kn * s.gap0);
    }
    const double used = first_iterate ? std::max(-normal_used, 0.0) : c.friction_normal_N;
    const double now = std::max(-normal_now, 0.0);
    if (std::abs(now - used) > kFrictionNormalTolerance * std::max(now, used) + round_off_force) moved = true;
    contacts.push_back(contacts_.index_of(c));
    used_forces.push_back(used);
    now_forces.push_back(now);
  }
  if (contacts.empty()) return moved;
  if (contacts != friction_contacts_) {
    friction_contacts_ = contacts;
    restart_friction_fixed_point();
  }
  const Eigen::Map<const Eigen::VectorXd> used(used_forces.data(), static_cast<Eigen::Index>(used_forces.size()));
  const Eigen::Map<const Eigen::VectorXd> now(now_forces.data(), static_cast<Eigen::Index>(now_forces.size()));
  const Eigen::VectorXd next = friction_acceleration_.next(used, now);
  // The plain iterate while the iteration contracts: the acceleration extrapolates, and
  // an extrapolated iterate is solved with the flow like any other. Once the residual
  // stops shrinking (a wedge's gain above one) the solve takes the accelerated iterates.
  const double residual = (now - used).norm();
  if (friction_residual_N_ >= 0.0 && residual >= friction_residual_N_) friction_accelerated_ = true;
  friction_residual_N_ = residual;
  const Eigen::VectorXd chosen = friction_accelerated_ ? next : Eigen::VectorXd(now);
  auto& all = contacts_.all();
  for (std::size_t i = 0; i < contacts.size(); ++i)
    all[contacts[i]].friction_normal_N = std::max(chosen[static_cast<Eigen::Index>(i)], 0.0);  // compression only
  return moved;
}

ContactIteration BlockSystem::update_multipliers(const Eigen::VectorXd& d, int iteration, StepStatistics& stats) {
  bool friction_moved = false;
  if (settings_.friction_at_solution && iteration < kMaxFrictionIterations) {
    friction_moved = follow_friction_normal_forces(d);
    if (friction_moved && iteration + 1 == kMaxFrictionIterations) {
      ++stats.friction_iterations_frozen;
      friction_moved = false;
    }
  }
  if (!settings_.augmented_lagrangian)  // penalty: one solve, repeated while the friction moves
    return friction_moved ? ContactIteration::again : ContactIteration::converged;
  double largest_stiffness = std::max(settings_.normal_stiffness_N_m, settings_.shear_stiffness_N_m);
  // Uzawa update of the multipliers (eq. 2.19); stop when the corrections are
  // negligible against the contact forces themselves. A contact is one normal and
  // one shear constraint: its springs (one per orientation at a joint end) are driven
  // by their mean gap and mean shear. Once the two faces meet at an angle, the two
  // springs' own gaps or shears differ by a geometric offset that no displacement
  // removes, and per-spring updates would pull them apart for ever.
  std::vector<double>& correction = alm_corrections_;
  std::vector<double>& previous = alm_previous_corrections_;
  double error = 0.0, scale = 0.0;
  previous.swap(correction);
  double change = 0.0;    // largest change of a correction since the last iteration [N]
  double mismatch = 0.0;  // largest |gap| or |shear| over the contact's length
  for (const auto& c : contacts_.all()) {
    if (c.state == ContactState::open || !iterated(c)) continue;
    const double kn = normal_stiffness(c), ks = shear_stiffness(c);
    largest_stiffness = std::max({largest_stiffness, kn, ks});
    const double w = 1.0 / c.n_springs;
    const double error_before = error;
    double gap = 0.0, shear = 0.0;
    for (int k = 0; k < c.n_springs; ++k) {
      const auto& s = c.springs[k];
      gap += w * spring_gap(s, d);
      scale = std::max(scale, std::abs(s.normal_multiplier_N));
      if (c.state == ContactState::locked) {
        shear += w * spring_shear(s, d);
        scale = std::max(scale, std::abs(s.shear_multiplier_N));
      }
    }
    error = std::max({error, std::abs(kn * gap), std::abs(ks * shear)});
    const double length = c.joint >= 0 ? c.length_m : c.springs[0].edge_length_m;
    mismatch = std::max(mismatch, std::max(std::abs(gap), std::abs(shear)) / length);
    const int ci = contacts_.index_of(c);
    if (error > error_before) alm_worst_contact_ = ci;
    correction[2 * ci] = kn * gap;
    correction[2 * ci + 1] = ks * shear;
    change = std::max({change, std::abs(correction[2 * ci] - previous[2 * ci]),
                       std::abs(correction[2 * ci + 1] - previous[2 * ci + 1])});
  }
  // Gaps cannot be resolved below the round-off of the coordinates they come from.
  const double round_off_force = largest_stiffness * gap_round_off_m_;
  if (!friction_moved && error <= settings_.alm_force_tolerance * scale + round_off_force)
    return ContactIteration::converged;
  // Stalled: the corrections no longer change, so the multiplier updates no longer
  // move the blocks. Around a point where every joint is closed, the contacts form a
  // loop of constraints; once some of them slipped and re-locked, the rotations of
  // the blocks leave their reference points inconsistent by a few nanometres, and no
  // displacement closes every gap. The remaining gaps are that geometric mismatch:
  // accept them if they are small against the contacts' lengths (kAlmStallMismatch),
  // and count the stall and its mismatch.
  if (!friction_moved && iteration > 0 && change <= settings_.alm_force_tolerance * scale + round_off_force &&
      mismatch <= kAlmStallMismatch) {
    ++stats.alm_stalls;
    stats.max_alm_stall_mismatch = std::max(stats.max_alm_stall_mismatch, mismatch);
    return ContactIteration::stalled;
  }
  for (auto& c : contacts_.all()) {
    if (c.state == ContactState::open || !iterated(c)) continue;
    const int ci = contacts_.index_of(c);
    for (int k = 0; k < c.n_springs; ++k) {
      c.springs[k].normal_multiplier_N += correction[2 * ci];
      c.springs[k].shear_multiplier_N += correction[2 * ci + 1];  // 0 unless locked
    }
  }
  if (iteration + 1 == settings_.max_alm_iterations) throw_alm_limit(error, scale);
  return ContactIteration::again;
}

void BlockSystem::throw_alm_limit(double error, double scale) const {
  std::ostringstream msg;
  msg << "Augmented Lagrangian iterations did not converge in " << settings_.max_alm_iterations
      << " iterations: largest spring force correction " << error << " N against contact forces of " << scale
      << " N (tolerance " << settings_.alm_force_tolerance << ")";
  if (alm_worst_contact_ >= 0) {
    const Contact& c = contacts_[alm_worst_contact_];
    const Vec2& at = mesh_.points[c.point];
    msg << "; largest at the " << to_string(c.state) << " contact of joint " << c.joint << " at point " << c.point
        << " (" << at.x() << ", " << at.y() << ") m";
  }
  throw ConvergenceError(msg.str());
}

}  // namespace hfdda::dda
