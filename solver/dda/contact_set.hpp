#pragma once
// The contacts of a block system (seed 2.3 iv: the list is built once from the mesh):
// two per joint (ends p and q) first, then the vertex-vertex candidates; the block
// pairs of K's pattern; the joint contacts around each point (propagation rule 2.3 i,
// closed-joint chains); and the per-step bookkeeping (state at the start of the step,
// flips of each contact for the cycle detection, bonds broken in the step).

#include <algorithm>
#include <utility>
#include <vector>

#include "dda/contacts.hpp"
#include "mesh/mesh.hpp"

namespace hfdda {
class BinaryWriter;
class BinaryReader;
}  // namespace hfdda

namespace hfdda::dda {

class ContactSet {
 public:
  ContactSet() = default;
  /// Joint-end contacts with the joints' properties and the vertex-vertex candidates.
  explicit ContactSet(const mesh::Mesh& mesh);

  std::vector<Contact>& all() { return contacts_; }
  const std::vector<Contact>& all() const { return contacts_; }
  Contact& operator[](int i) { return contacts_[i]; }
  const Contact& operator[](int i) const { return contacts_[i]; }
  int size() const { return static_cast<int>(contacts_.size()); }
  int n_joint_contacts() const { return n_joint_contacts_; }
  int index_of(const Contact& c) const { return static_cast<int>(&c - contacts_.data()); }

  /// Block pairs of K's pattern: the joints' pairs, then vertex-vertex pairs once active.
  const std::vector<std::pair<int, int>>& couplings() const { return couplings_; }
  /// First activation of a vertex-vertex contact: its block pair joins the pattern.
  void add_coupling(int block_a, int block_c);
  bool pattern_changed() const { return pattern_changed_; }
  void pattern_rebuilt() { pattern_changed_ = false; }

  /// The joint's other end or another joint contact at the same point is open (the
  /// open-neighbour half of the propagation rule, seed 2.3 i).
  bool has_open_neighbour(int contact) const;
  /// The joint's other end or another joint contact at the same point has failed: it is
  /// open or its bond is broken (natural-fracture localisation, seed 5.1).
  bool has_failed_neighbour(int contact) const;
  /// Blocks a and c are joined at the point by a chain of joint contacts that are
  /// closed in `joint_state` (one state per joint contact).
  bool joined_by_closed_joints(int point, int block_a, int block_c, const std::vector<ContactState>& joint_state) const;

  /// Start of a step: remember the contacts for roll_back() and clear the flip counts.
  /// The joint contacts and the active vertex-vertex contacts are copied; an inactive
  /// vertex-vertex candidate is copied only when remember() is called before its change.
  void begin_step();
  /// Call before changing contact `ci` within a step (the state changes of the
  /// open-close iterations): keeps an inactive vertex-vertex candidate for roll_back().
  void remember(int ci);
  /// Counts a state change of a contact in this step; returns the count so far.
  int count_flip(int contact) { return ++flips_[contact]; }
  /// The most open state the contact has had in this step (open < sliding < locked).
  ContactState most_open(int contact) const { return most_open_[contact]; }
  /// Holds the contact at `state` for the rest of the step, whatever it had before.
  void hold(int contact, ContactState state) { most_open_[contact] = state; }
  void note_state(int contact) { most_open_[contact] = std::min(most_open_[contact], contacts_[contact].state); }
  /// The contact's bond broke in this step.
  void note_bond_failure(int contact) { failed_in_step_[contact] = 1; }
  bool bond_failed_in_step(int contact) const { return failed_in_step_[contact] != 0; }
  /// The contacts and K's block pairs, for a checkpoint (dda/block_system_state.cpp).
  void save_state(BinaryWriter& out) const;
  void restore_state(BinaryReader& in);

  /// Joint contact `ci` as it was at the start of the step.
  const Contact& joint_at_step_start(int ci) const { return joints_at_start_[ci]; }
  /// Back to the contacts at the start of the step (K's pattern is kept).
  void roll_back();

 private:
  std::vector<Contact> contacts_;
  // The step's start, for roll_back(). Vertex-vertex candidates are about two thirds of
  // the contacts and almost all stay inactive: copying only the few that change keeps
  // the snapshot to the joint contacts (a 51k-block mesh: 96 MB instead of 270 MB).
  std::vector<Contact> joints_at_start_;
  std::vector<std::pair<int, Contact>> vertex_vertex_at_start_;
  std::vector<char> vertex_vertex_remembered_;  // per candidate, in this step
  int n_joint_contacts_ = 0;
  std::vector<int> at_point_offset_, at_point_;  // joint contacts by point
  std::vector<int> flips_;                       // state changes of each contact within the step
  std::vector<ContactState> most_open_;          // most open state of each contact within the step
  std::vector<char> failed_in_step_;             // the contact's bond broke within the step
  std::vector<std::pair<int, int>> couplings_;
  bool pattern_changed_ = false;
};

}  // namespace hfdda::dda
