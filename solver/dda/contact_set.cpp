#include "dda/contact_set.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <tuple>

namespace hfdda::dda {

namespace {

/// The two contacts of each joint: the seed's symmetric pair of vertex-edge springs.
void add_joint_contacts(const mesh::Mesh& mesh, std::vector<Contact>& contacts,
                        std::vector<std::pair<int, int>>& couplings) {
  auto n_of = [&](int b) { return static_cast<int>(mesh.blocks[b].points.size()); };
  for (int j = 0; j < static_cast<int>(mesh.joints.size()); ++j) {
    const mesh::Joint& joint = mesh.joints[j];
    const int a = joint.block_a, b = joint.block_b;
    const int a_at_p = joint.corner_a, a_at_q = (joint.corner_a + 1) % n_of(a);
    const int b_at_q = joint.corner_b, b_at_p = (joint.corner_b + 1) % n_of(b);
    const double length = (mesh.points[joint.point_q] - mesh.points[joint.point_p]).norm();
    const auto& props = joint.properties;
    for (int end = 0; end < 2; ++end) {
      Contact c;
      c.joint = j;
      c.end = end;
      c.point = end == 0 ? joint.point_p : joint.point_q;
      c.n_springs = 2;
      // Symmetric pair (eq. 2.21): each block's corner against the other block's edge.
      // Edge a runs p -> q, edge b runs q -> p: the shared point sits at ratio 0 or 1.
      c.springs[0] = {a, end == 0 ? a_at_p : a_at_q, b, joint.corner_b};
      c.springs[0].reference_ratio = end == 0 ? 1.0 : 0.0;
      c.springs[1] = {b, end == 0 ? b_at_p : b_at_q, a, joint.corner_a};
      c.springs[1].reference_ratio = end == 0 ? 0.0 : 1.0;
      c.length_m = 0.5 * length;
      c.cohesion_Pa = props.cohesion_Pa;
      c.tan_friction = std::tan(props.friction_angle_rad);
      c.bonded = !props.initially_open;
      c.state = props.initially_open ? ContactState::open : ContactState::locked;
      contacts.push_back(c);
    }
    couplings.emplace_back(a, b);
  }
}

/// Vertex-vertex candidates: blocks sharing a point but no joint ending there.
void add_vertex_vertex_candidates(const mesh::Mesh& mesh, std::vector<Contact>& contacts) {
  std::vector<std::vector<std::pair<int, int>>> blocks_at_point(mesh.points.size());
  for (int b = 0; b < static_cast<int>(mesh.blocks.size()); ++b)
    for (int k = 0; k < static_cast<int>(mesh.blocks[b].points.size()); ++k)
      blocks_at_point[mesh.blocks[b].points[k]].emplace_back(b, k);
  std::set<std::tuple<int, int, int>> joined;  // (point, min block, max block)
  for (const auto& joint : mesh.joints) {
    const int lo = std::min(joint.block_a, joint.block_b), hi = std::max(joint.block_a, joint.block_b);
    joined.emplace(joint.point_p, lo, hi);
    joined.emplace(joint.point_q, lo, hi);
  }
  std::size_t n_candidates = 0;  // reserve exactly: the list is the largest array of a model
  for (const auto& around : blocks_at_point) n_candidates += around.size() * (around.size() - 1) / 2;
  contacts.reserve(contacts.size() + n_candidates);
  for (int p = 0; p < static_cast<int>(blocks_at_point.size()); ++p) {
    const auto& around = blocks_at_point[p];
    for (std::size_t i = 0; i < around.size(); ++i)
      for (std::size_t k = i + 1; k < around.size(); ++k) {
        const auto [ba, ka] = around[i];
        const auto [bc, kc] = around[k];
        if (joined.count({p, std::min(ba, bc), std::max(ba, bc)})) continue;
        Contact c;
        c.point = p;
        c.n_springs = 1;
        c.state = ContactState::open;
        c.bonded = false;
        c.block_a = ba, c.corner_a = ka, c.block_c = bc, c.corner_c = kc;
        contacts.push_back(c);
      }
  }
}

}  // namespace

ContactSet::ContactSet(const mesh::Mesh& mesh) {
  const int n_joints = static_cast<int>(mesh.joints.size());
  n_joint_contacts_ = 2 * n_joints;
  contacts_.reserve(n_joint_contacts_);
  couplings_.reserve(n_joints);
  add_joint_contacts(mesh, contacts_, couplings_);
  // Vertex-vertex pairs enter K's pattern only once one activates: they would
  // otherwise multiply the off-diagonal blocks (and the fill) several times over.
  add_vertex_vertex_candidates(mesh, contacts_);

  // Joint contacts by point, for the propagation rule (seed 2.3 i).
  at_point_offset_.assign(mesh.points.size() + 1, 0);
  for (int ci = 0; ci < n_joint_contacts_; ++ci) ++at_point_offset_[contacts_[ci].point + 1];
  for (std::size_t p = 0; p < mesh.points.size(); ++p) at_point_offset_[p + 1] += at_point_offset_[p];
  at_point_.assign(n_joint_contacts_, 0);
  std::vector<int> fill(at_point_offset_.begin(), at_point_offset_.end() - 1);
  for (int ci = 0; ci < n_joint_contacts_; ++ci) at_point_[fill[contacts_[ci].point]++] = ci;
}

void ContactSet::add_coupling(int block_a, int block_c) {
  couplings_.emplace_back(block_a, block_c);
  pattern_changed_ = true;
}

void ContactSet::begin_step() {
  joints_at_start_.assign(contacts_.begin(), contacts_.begin() + n_joint_contacts_);
  vertex_vertex_at_start_.clear();
  vertex_vertex_remembered_.assign(contacts_.size() - n_joint_contacts_, 0);
  for (int ci = n_joint_contacts_; ci < size(); ++ci)
    if (contacts_[ci].vertex_vertex_active) remember(ci);
  flips_.assign(contacts_.size(), 0);
  failed_in_step_.assign(contacts_.size(), 0);
  most_open_.resize(contacts_.size());
  for (int ci = 0; ci < size(); ++ci) most_open_[ci] = contacts_[ci].state;
}

void ContactSet::remember(int ci) {
  if (ci < n_joint_contacts_) return;  // all copied at the start of the step
  char& remembered = vertex_vertex_remembered_[ci - n_joint_contacts_];
  if (remembered) return;
  remembered = 1;
  vertex_vertex_at_start_.emplace_back(ci, contacts_[ci]);
}

void ContactSet::roll_back() {
  std::copy(joints_at_start_.begin(), joints_at_start_.end(), contacts_.begin());
  for (const auto& [ci, contact] : vertex_vertex_at_start_) contacts_[ci] = contact;
}

bool ContactSet::has_open_neighbour(int contact) const {
  const Contact& c = contacts_[contact];
  if (c.joint < 0) return false;
  const Contact& other_end = contacts_[2 * c.joint + (1 - c.end)];
  if (other_end.state == ContactState::open) return true;
  for (int k = at_point_offset_[c.point]; k < at_point_offset_[c.point + 1]; ++k) {
    const Contact& n = contacts_[at_point_[k]];
    if (&n != &c && n.state == ContactState::open) return true;
  }
  return false;
}

bool ContactSet::has_failed_neighbour(int contact) const {
  const Contact& c = contacts_[contact];
  if (c.joint < 0) return false;
  auto failed = [](const Contact& n) { return n.state == ContactState::open || !n.bonded; };
  if (failed(contacts_[2 * c.joint + (1 - c.end)])) return true;
  for (int k = at_point_offset_[c.point]; k < at_point_offset_[c.point + 1]; ++k) {
    const Contact& n = contacts_[at_point_[k]];
    if (&n != &c && failed(n)) return true;
  }
  return false;
}

bool ContactSet::joined_by_closed_joints(int point, int block_a, int block_c,
                                         const std::vector<ContactState>& joint_state) const {
  // Breadth-first search over the blocks around the point (at most a dozen).
  std::array<int, 32> reached{};
  int n_reached = 0, next = 0;
  reached[n_reached++] = block_a;
  while (next < n_reached) {
    const int from = reached[next++];
    for (int k = at_point_offset_[point]; k < at_point_offset_[point + 1]; ++k) {
      const Contact& j = contacts_[at_point_[k]];
      if (joint_state[at_point_[k]] == ContactState::open) continue;
      const int a = j.springs[0].vertex_block, b = j.springs[0].edge_block;
      const int to = a == from ? b : b == from ? a : -1;
      if (to < 0 || std::find(reached.begin(), reached.begin() + n_reached, to) != reached.begin() + n_reached) continue;
      if (to == block_c) return true;
      if (n_reached == static_cast<int>(reached.size())) return false;
      reached[n_reached++] = to;
    }
  }
  return false;
}

}  // namespace hfdda::dda
