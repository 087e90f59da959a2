// Open-close checks of the contacts (seed 2.3): the trial tractions, the state rules
// of joint and vertex-vertex contacts, and applying the changes of a round (bond
// failures come from fracture/ through the coupled step).

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dda/block_system.hpp"

namespace hfdda::dda {

Vec2 BlockSystem::displaced(int block, const Vec2& p, const Eigen::VectorXd& d) const {
  return p + displacement_matrix(p, moments_[block].centroid) * d.segment<6>(6 * block);
}

void BlockSystem::reset_shear_reference(VertexEdgeSpring& s, const Eigen::VectorXd& d) const {
  // New reference = where the corner projects on the edge now: no shear at locking.
  const Vec2 p1 = displaced(s.vertex_block, corner(s.vertex_block, s.vertex_corner), d);
  const Vec2 p2 = displaced(s.edge_block, corner(s.edge_block, s.edge_corner), d);
  const Vec2 p3 = displaced(s.edge_block, blocks_.next_corner(s.edge_block, s.edge_corner), d);
  // Not clamped to the edge: a corner that closes just beyond the end of the edge (a
  // joint end after opening) would otherwise start with a shear offset.
  s.reference_ratio = (p1 - p2).dot(p3 - p2) / (p3 - p2).squaredNorm();
  s.shear_multiplier_N = 0.0;
}

std::optional<VertexEdgeSpring> BlockSystem::vertex_vertex_spring(const Contact& c, const Eigen::VectorXd& d,
                                                                   double& max_penetration) const {
  // Depth of a corner inside the other block's angle at the shared point: the smaller
  // of its distances behind the two edges meeting there (the way out of the block).
  auto try_orientation = [&](int vb, int vc, int eb, int ec) -> std::optional<VertexEdgeSpring> {
    const int n = n_corners(eb);
    const Vec2 p = displaced(vb, corner(vb, vc), d);
    const Vec2 here = displaced(eb, corner(eb, ec), d);
    const Vec2 next = displaced(eb, corner(eb, (ec + 1) % n), d);
    const Vec2 prev = displaced(eb, corner(eb, (ec + n - 1) % n), d);
    const double d_next = (p - here).dot(outward_normal(here, next));   // edge ec -> ec+1
    const double d_prev = (p - prev).dot(outward_normal(prev, here));   // edge ec-1 -> ec
    if (d_next >= 0.0 || d_prev >= 0.0) return std::nullopt;
    const double depth = std::min(-d_next, -d_prev);
    max_penetration = std::max(max_penetration, depth);
    if (depth <= settings_.vertex_vertex_activation_m) return std::nullopt;
    VertexEdgeSpring s;
    s.vertex_block = vb, s.vertex_corner = vc, s.edge_block = eb;
    s.edge_corner = -d_next < -d_prev ? ec : (ec + n - 1) % n;  // the nearer edge is the reference line
    return s;
  };
  if (auto s = try_orientation(c.block_a, c.corner_a, c.block_c, c.corner_c)) return s;
  return try_orientation(c.block_c, c.corner_c, c.block_a, c.corner_a);
}

ContactTraction BlockSystem::trial_traction(const Contact& c, const Eigen::VectorXd& d, StepStatistics& stats) const {
  const double kn = normal_stiffness(c), ks = shear_stiffness(c);
  const double w = 1.0 / c.n_springs;
  ContactTraction t;
  for (int k = 0; k < c.n_springs; ++k) {
    const auto& s = c.springs[k];
    const double g = spring_gap(s, d);
    t.gap_m += w * g;
    t.normal_N += w * (s.normal_multiplier_N + kn * g);
    t.shear_N += w * (s.shear_multiplier_N + ks * spring_shear(s, d));
  }
  stats.max_penetration_m = std::max(stats.max_penetration_m, -t.gap_m);
  return t;
}

std::optional<ContactChange> BlockSystem::open_close_change(int ci, const ContactTraction& t,
                                                            const Eigen::VectorXd& d) const {
  const Contact& c = contacts_[ci];
  const double friction_limit = std::max(-t.normal_N, 0.0) * c.tan_friction;
  switch (c.state) {
    case ContactState::open:
      if (t.gap_m < 0.0) return ContactChange{ci, ContactState::locked};
      break;
    case ContactState::locked:
      if (c.bonded) break;  // an intact bond: the fracture criteria decide
      if (t.normal_N > 0.0) return ContactChange{ci, ContactState::open};
      if (std::abs(t.shear_N) > friction_limit)
        return ContactChange{ci, ContactState::sliding, false, t.shear_N >= 0.0 ? 1.0 : -1.0};
      break;
    case ContactState::sliding: {
      if (t.normal_N > 0.0) return ContactChange{ci, ContactState::open};
      const bool may_relock = settings_.relock_in_failure_step || !contacts_.bond_failed_in_step(ci);
      if (c.joint < 0 || !may_relock) break;
      // A reversal of the slip against the friction force re-locks (Shi 1988). For a
      // held (penalty) contact closed at the step's start the slip is that of this step
      // (the spring's shear without its value at the start): friction that outlasts the
      // driving shear then stops the block where the step began, instead of pulling it
      // back along the whole slip since it last locked (docs/design_notes.md section 41).
      // For one that closed in this step, and for iterated contacts, the slip since it
      // closed or last locked: an Augmented Lagrangian contact locked back at the start
      // stopped Mode II and mixed-mode runs on its multipliers (section 41).
      const bool held = settings_.friction_at_solution && !(settings_.augmented_lagrangian && iterated(c));
      const bool closed_at_start = held && contacts_.joint_at_step_start(ci).state != ContactState::open;
      double slip = 0.0;
      for (int k = 0; k < c.n_springs; ++k)
        slip += 1.0 / c.n_springs * (spring_shear(c.springs[k], d) - (closed_at_start ? c.springs[k].shear0 : 0.0));
      if (slip * c.friction_sign < 0.0) {
        ContactChange relock{ci, ContactState::locked};
        relock.relock_at_step_start = closed_at_start;
        return relock;
      }
      break;
    }
  }
  return std::nullopt;
}

OpenCloseTrial BlockSystem::trial_contacts(const Eigen::VectorXd& d, StepStatistics& stats) const {
  OpenCloseTrial trial;
  const int n = contacts_.n_joint_contacts();
  trial.tractions.resize(n);
  for (int ci = 0; ci < n; ++ci) {
    trial.tractions[ci] = trial_traction(contacts_[ci], d, stats);
    if (auto change = open_close_change(ci, trial.tractions[ci], d)) trial.changes.push_back(*change);
  }
  return trial;
}

void BlockSystem::add_vertex_vertex_changes(const Eigen::VectorXd& d, std::vector<ContactChange>& changes,
                                            StepStatistics& stats) {
  // Vertex-vertex contacts (frictionless normal springs, state "sliding") come last,
  // judged on the joint states this round leads to. With the Augmented Lagrangian, two
  // blocks joined at the point by a chain of closed joint contacts cannot penetrate
  // each other there (the wedges between them are in contact and their gaps are driven
  // to zero): a vertex-vertex spring would be a redundant constraint with its own
  // geometric offset, which the iterations cannot satisfy. With penalty springs the
  // joints do overlap, and the seed's vertex-vertex springs (3.1) stay.
  const int n_joint_contacts = contacts_.n_joint_contacts();
  next_joint_state_.resize(n_joint_contacts);
  for (int ci = 0; ci < n_joint_contacts; ++ci) next_joint_state_[ci] = contacts_[ci].state;
  for (const ContactChange& ch : changes) next_joint_state_[ch.contact] = ch.to;
  for (int ci = n_joint_contacts; ci < contacts_.size(); ++ci) {
    const Contact& c = contacts_[ci];
    const bool joined = settings_.augmented_lagrangian &&
                        contacts_.joined_by_closed_joints(c.point, c.block_a, c.block_c, next_joint_state_);
    if (!c.vertex_vertex_active) {
      if (!joined)
        if (auto s = vertex_vertex_spring(c, d, stats.max_penetration_m))
          changes.push_back({ci, ContactState::sliding, false, 0.0, s});
    } else if (joined) {
      changes.push_back({ci, ContactState::open});
    } else if (auto change = open_close_change(ci, trial_traction(c, d, stats), d)) {
      changes.push_back(*change);
    }
  }
}

void BlockSystem::describe_first_change(const Contact& c, ContactState to) {
  const Vec2& at = mesh_.points[c.point];
  std::ostringstream where;
  where << (c.joint >= 0 ? "joint " + std::to_string(c.joint) : std::string("vertex-vertex contact")) << " at ("
        << at.x() << ", " << at.y() << "): " << to_string(c.state) << " -> " << to_string(to);
  first_change_ = where.str();
}

void BlockSystem::apply_change(const ContactChange& ch, const Eigen::VectorXd& d, StepStatistics& stats) {
  remember_assembled_terms(ch.contact);
  Contact& c = contacts_[ch.contact];
  if (ch.breaks_bond) {
    c.bonded = false;
    contacts_.note_bond_failure(ch.contact);
    ++stats.bonds_broken;
  }
  if (ch.vertex_vertex) {
    c.springs[0] = *ch.vertex_vertex;
    if (!c.ever_active) {  // first activation: its block pair joins K's pattern
      contacts_.add_coupling(c.block_a, c.block_c);
      c.ever_active = true;
    } else {
      // Activated again: the pair is in the pattern already, so no rebuild will give the
      // new spring its slot (it had none: an out-of-range write into K followed).
      c.springs[0].slot = stiffness_.coupling_slot(c.springs[0].vertex_block, c.springs[0].edge_block);
    }
    c.vertex_vertex_active = true;
    c.friction_sign = 0.0;
    ++stats.vertex_vertex_activations;
  }
  if (c.joint < 0 && ch.to == ContactState::open) c.vertex_vertex_active = false;
  c.state = ch.to;
  c.friction_normal_N = -1.0;  // a new state starts from the step's normal force
  for (int k = 0; k < c.n_springs; ++k) {
    auto& s = c.springs[k];
    if (ch.to == ContactState::open) {
      s.normal_multiplier_N = s.shear_multiplier_N = 0.0;
    } else if (ch.relock_at_step_start) {
      // Locked where it was when the step began: as it was then if it was locked (and its
      // bond has not broken since), else at the point its corner faced at the start.
      const Contact& start = contacts_.joint_at_step_start(ch.contact);
      if (start.state == ContactState::locked && start.bonded == c.bonded) {
        s.reference_ratio = start.springs[k].reference_ratio;
        s.shear_multiplier_N = start.springs[k].shear_multiplier_N;
      } else {
        reset_shear_reference(s, Eigen::VectorXd::Zero(d.size()));
      }
      linearise_spring(s);
    } else {
      reset_shear_reference(s, d);  // slip and shear are measured from the closing point
      linearise_spring(s);
    }
  }
}

int BlockSystem::apply_state_changes(const Eigen::VectorXd& d, const std::vector<ContactChange>& joint_changes,
                                     StepStatistics& stats) {
  std::vector<ContactChange> changes = joint_changes;
  add_vertex_vertex_changes(d, changes, stats);
  int applied = 0;
  first_change_.clear();
  for (const ContactChange& ch : changes) {
    contacts_.remember(ch.contact);
    Contact& c = contacts_[ch.contact];
    if (first_change_.empty()) describe_first_change(c, ch.to);
    if (ch.friction_sign != 0.0) c.friction_sign = ch.friction_sign;
    // Cycle detection (seed 5.1): a contact that keeps flipping is resolved by the most
    // open state it has had in this step and held there for the rest of the step.
    if (contacts_.count_flip(ch.contact) > settings_.max_state_flips && !ch.breaks_bond) {
      ++stats.cycle_holds;
      const ContactState most_open = contacts_.most_open(ch.contact);
      if (settings_.close_penetrating_cycles && c.joint >= 0 && !c.bonded && most_open == ContactState::open &&
          ch.to != ContactState::open &&
          -trial_traction(c, d, stats).gap_m > kCycleHoldPenetration * 2.0 * c.length_m) {
        // Held open, its faces would pass through each other (a step that ends so is cut
        // by the overlap guard, section 24): closed and held sliding instead.
        contacts_.hold(ch.contact, ContactState::sliding);
        ++applied;
        apply_change(ch, d, stats);
        continue;
      }
      if (c.state == most_open) continue;
      ContactChange resolved = ch;
      resolved.to = most_open;
      resolved.vertex_vertex.reset();
      if (c.joint < 0 && most_open != ContactState::open) continue;  // a vertex-vertex spring is kept as it is
      ++applied;
      apply_change(resolved, d, stats);
      continue;
    }
    ++applied;
    apply_change(ch, d, stats);
    contacts_.note_state(ch.contact);
  }
  if (contacts_.pattern_changed()) rebuild_pattern();
  stats.state_changes += applied;
  return applied;
}

}  // namespace hfdda::dda
