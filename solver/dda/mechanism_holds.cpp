// Mechanisms of a contact state: groups of blocks that the step's closed contacts do not
// hold. In static analysis only the inertia term 2 M / dt^2 resists their motion, and at
// the flow's steps (a minute at reservoir scale) that is nothing: a pair of blocks bonded
// to each other and touching the rest of the rock by one sliding joint moved 2.4 mm per
// pascal of fluid pressure, and the flow solve could not converge on it
// (docs/design_notes.md section 25). Such groups alone take the inertia of a shorter time,
// MechanicsSettings::mechanism_inertia_time_s; the rest of the rock mass is untouched.

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "dda/block_system.hpp"

namespace hfdda::dda {

namespace {

/// Groups of blocks joined rigidly (union-find with path halving).
class RigidGroups {
 public:
  explicit RigidGroups(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int b) {
    while (parent_[b] != b) b = parent_[b] = parent_[parent_[b]];
    return b;
  }
  void join(int a, int b) { parent_[find(a)] = find(b); }

 private:
  std::vector<int> parent_;
};

}  // namespace

std::vector<int> BlockSystem::mechanism_blocks() const {
  const int nb = n_blocks();
  const auto& contacts = contacts_.all();
  // Two blocks move as one where the joint between them is locked at both ends; a joint
  // locked at one end only is a hinge.
  RigidGroups groups(nb);
  for (int j = 0; j < static_cast<int>(mesh_.joints.size()); ++j) {
    const mesh::Joint& joint = mesh_.joints[j];
    if (joint.block_a < 0 || joint.block_b < 0) continue;
    const auto [c0, c1] = joint_contacts(j);
    if (contacts[c0].state == ContactState::locked && contacts[c1].state == ContactState::locked)
      groups.join(joint.block_a, joint.block_b);
  }
  std::vector<int> group(nb), size(nb, 0);
  std::vector<double> area(nb, 0.0);
  std::vector<Vec2> moment(nb, Vec2::Zero());
  std::vector<char> supported(nb, 0);
  for (int b = 0; b < nb; ++b) {
    group[b] = groups.find(b);
    ++size[group[b]];
    area[group[b]] += moments_[b].area;
    moment[group[b]] += moments_[b].area * moments_[b].centroid;
  }
  // Two fixed points at different places hold a group; one is a pin it may turn about (a
  // corner group of the boundary ring cut off by open joints turned about its corner by
  // kilometres, section 25), so a pinned group is tested with its pin among its springs.
  std::vector<int> first_pin(nb, -1);
  for (int k = 0; k < static_cast<int>(loads_.fixed_points.size()); ++k) {
    const auto& fp = loads_.fixed_points[k];
    int& pin = first_pin[group[fp.block]];
    if (pin < 0)
      pin = k;
    else if ((loads_.fixed_points[pin].anchor - fp.anchor).norm() > 1e-9 * std::sqrt(std::abs(area[group[fp.block]])))
      supported[group[fp.block]] = 1;
  }
  // Where no group is held by two fixed points, the rock mass (the largest group) is held
  // by balanced far-field loads: its rigid-body motion is the model's (no fixed point, or
  // one), not a mechanism of the contact state.
  if (std::find(supported.begin(), supported.end(), 1) == supported.end())
    supported[std::max_element(size.begin(), size.end()) - size.begin()] = 1;

  // The groups nothing holds, numbered; in a bonded rock mass there are none, and the
  // contacts need not be visited.
  std::vector<int> free_index(nb, -1);
  std::vector<Vec2> free_centre;
  std::vector<double> free_length;
  for (int g = 0; g < nb; ++g)
    if (size[g] > 0 && !supported[g]) {
      free_index[g] = static_cast<int>(free_centre.size());
      free_centre.push_back(moment[g] / area[g]);
      free_length.push_back(std::sqrt(std::abs(area[g])));
    }
  if (free_centre.empty()) return {};

  // Per free group, the stiffness of its rigid motion (u, v, theta L) against the closed
  // contacts to other groups, with unit springs: only its rank matters.
  std::vector<Eigen::Matrix3d> rigid(free_centre.size(), Eigen::Matrix3d::Zero());
  auto add_row = [&](int b, const Row6& row) {
    const int i = free_index[group[b]];
    if (i < 0) return;
    const Vec2 r = moments_[b].centroid - free_centre[i];
    // Block DOFs of a rigid motion of the group: translation plus theta x r, rotation theta.
    const Eigen::RowVector3d a(row[0], row[1], (row[2] - r.y() * row[0] + r.x() * row[1]) / free_length[i]);
    rigid[i] += a.transpose() * a;
  };
  for (const auto& fp : loads_.fixed_points) {
    const int i = free_index[group[fp.block]];
    if (i < 0) continue;
    const Vec2 r = fp.anchor - free_centre[i];
    for (const Eigen::RowVector3d& a : {Eigen::RowVector3d(1.0, 0.0, -r.y() / free_length[i]),
                                       Eigen::RowVector3d(0.0, 1.0, r.x() / free_length[i])})
      rigid[i] += a.transpose() * a;
  }
  for (const auto& c : contacts) {
    if (c.state == ContactState::open || (c.joint < 0 && !c.vertex_vertex_active)) continue;
    for (int k = 0; k < c.n_springs; ++k) {
      const auto& s = c.springs[k];
      if (group[s.vertex_block] == group[s.edge_block]) continue;  // inside one group
      add_row(s.vertex_block, s.gap_vertex);
      add_row(s.edge_block, s.gap_edge);
      if (c.state == ContactState::locked) {
        add_row(s.vertex_block, s.shear_vertex);
        add_row(s.edge_block, s.shear_edge);
      }
    }
  }
  // A group is a mechanism when some rigid motion stretches none of its springs.
  std::vector<char> mechanism(rigid.size(), 0);
  for (std::size_t i = 0; i < rigid.size(); ++i) {
    const Eigen::Vector3d eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(rigid[i], Eigen::EigenvaluesOnly).eigenvalues();
    mechanism[i] = eig[0] <= kMechanismStiffnessRatio * eig[2];
  }
  std::vector<int> blocks;
  for (int b = 0; b < nb; ++b)
    if (free_index[group[b]] >= 0 && mechanism[free_index[group[b]]]) blocks.push_back(b);
  return blocks;
}

void BlockSystem::hold_mechanisms() {
  held_blocks_.clear();
  if (settings_.dynamic || !(settings_.mechanism_inertia_time_s < step_dt_s_)) return;
  const double extra = 2.0 / (settings_.mechanism_inertia_time_s * settings_.mechanism_inertia_time_s) -
                       2.0 / (step_dt_s_ * step_dt_s_);
  held_blocks_ = mechanism_blocks();
  for (const int b : held_blocks_) {
    const Material& m = materials_[blocks_.material[b]];
    stiffness_.add_diagonal(b, extra * m.density_kg_m3 * displacement_matrix_gram(moments_[b]));
  }
}

}  // namespace hfdda::dda
