#include "coupling/crack_tips.hpp"

#include <algorithm>
#include <cmath>
#include <span>

namespace hfdda::coupling {

namespace {

/// Unit vector from `point` along joint `j` (towards its other end).
Vec2 direction_from(const mesh::Mesh& m, int j, int point) {
  const mesh::Joint& joint = m.joints[j];
  const int other = joint.point_p == point ? joint.point_q : joint.point_p;
  return (m.points[other] - m.points[point]).normalized();
}

/// The end (0: p, 1: q) of joint `j` at `point`.
int end_at(const mesh::Mesh& m, int j, int point) { return m.joints[j].point_p == point ? 0 : 1; }

/// +1 if block b of joint `j` lies on the +n side of the tip frame, else -1 (block a
/// runs p -> q counter-clockwise, so b is on the right of p -> q).
double b_side(const mesh::Mesh& m, int j, const Vec2& n) {
  const Vec2 t = m.points[m.joints[j].point_q] - m.points[m.joints[j].point_p];
  return Vec2(t.y(), -t.x()).dot(n) > 0.0 ? 1.0 : -1.0;
}

/// Along e: +1 if the joint runs p -> q along e, else -1.
double along(const mesh::Mesh& m, int j, const Vec2& e) {
  return (m.points[m.joints[j].point_q] - m.points[m.joints[j].point_p]).dot(e) > 0.0 ? 1.0 : -1.0;
}

/// The crack-closure data of the tip at `point` with joint `reference` ahead and joint
/// `behind` behind it (and `second` behind that, -1: none), at the contact forces
/// `tractions` and step displacement `d`.
fracture::CrackTip closure_data(const dda::BlockSystem& system, const std::vector<dda::ContactTraction>& tractions,
                                const Eigen::VectorXd& d, int reference, int behind, int second, int point) {
  const mesh::Mesh& m = system.mesh();
  const auto& contacts = system.contacts();
  fracture::CrackTip tip;
  const Vec2 e = direction_from(m, reference, point);
  const Vec2 n(-e.y(), e.x());
  tip.joint = reference;
  tip.behind_joint = behind;
  tip.tip_point = point;
  tip.length_m = (m.points[m.joints[reference].point_q] - m.points[m.joints[reference].point_p]).norm();
  tip.behind_length_m = (m.points[m.joints[behind].point_q] - m.points[m.joints[behind].point_p]).norm();
  // Forces of the joint ahead: shear_N is the spring's stretch of b relative to a
  // along p -> q; in the tip frame, of the +n face relative to the -n face along e.
  const auto ahead = system.joint_contacts(reference);
  const int tip_end = end_at(m, reference, point);
  const double shear_to_frame = b_side(m, reference, n) * along(m, reference, e);
  auto force = [&](int ci, bool normal) {
    if (!contacts[ci].bonded) return 0.0;  // a broken bond releases nothing
    return normal ? tractions[ci].normal_N : shear_to_frame * tractions[ci].shear_N;
  };
  tip.tip_normal_N = force(ahead[tip_end], true);
  tip.tip_shear_N = force(ahead[tip_end], false);
  tip.far_normal_N = force(ahead[1 - tip_end], true);
  tip.far_shear_N = force(ahead[1 - tip_end], false);
  // Opening and slip of the joint behind, of its +n face relative to its -n face.
  const int behind_tip_end = end_at(m, behind, point);
  const double side = b_side(m, behind, n);
  const Vec2 near = side * system.joint_end_separation(behind, behind_tip_end, d);
  const Vec2 far = side * system.joint_end_separation(behind, 1 - behind_tip_end, d);
  tip.near_opening_m = near.dot(n);
  tip.near_slip_m = near.dot(e);
  tip.far_opening_m = far.dot(n);
  tip.far_slip_m = far.dot(e);
  if (second >= 0) {
    const int joined = behind_tip_end == 0 ? m.joints[behind].point_q : m.joints[behind].point_p;
    const Vec2 far2 = b_side(m, second, n) * system.joint_end_separation(second, 1 - end_at(m, second, joined), d);
    tip.second_opening_m = far2.dot(n);
    tip.second_slip_m = far2.dot(e);
    tip.second_distance_m =
        tip.behind_length_m + (m.points[m.joints[second].point_q] - m.points[m.joints[second].point_p]).norm();
  }
  const dda::Material& rock = system.materials()[system.block_material()[m.joints[reference].block_a]];
  tip.plane_strain_modulus_Pa = fracture::plane_strain_modulus_Pa(rock.youngs_modulus_Pa, rock.poissons_ratio);
  return tip;
}

}  // namespace

CrackTips::CrackTips(const dda::BlockSystem& system) {
  const mesh::Mesh& m = system.mesh();
  joint_offset_.assign(m.points.size() + 1, 0);
  for (const auto& j : m.joints) ++joint_offset_[j.point_p + 1], ++joint_offset_[j.point_q + 1];
  for (std::size_t p = 0; p < m.points.size(); ++p) joint_offset_[p + 1] += joint_offset_[p];
  joints_.resize(joint_offset_.back());
  std::vector<int> next(joint_offset_.begin(), joint_offset_.end() - 1);
  for (int j = 0; j < static_cast<int>(m.joints.size()); ++j)
    for (int p : {m.joints[j].point_p, m.joints[j].point_q}) joints_[next[p]++] = j;
}

std::vector<dda::ContactTraction> CrackTips::committed_tractions(const dda::BlockSystem& system) {
  std::vector<dda::ContactTraction> tractions(system.contacts().size());
  for (int j = 0; j < static_cast<int>(system.mesh().joints.size()); ++j)
    for (int ci : system.joint_contacts(j)) {
      const auto [normal_N, shear_N] = system.contact_forces(ci);
      tractions[ci].normal_N = normal_N;
      tractions[ci].shear_N = shear_N;
    }
  return tractions;
}

int CrackTips::continuing_broken_joint(const dda::BlockSystem& system, int behind, int tip_point) const {
  const mesh::Mesh& m = system.mesh();
  const int joined = m.joints[behind].point_p == tip_point ? m.joints[behind].point_q : m.joints[behind].point_p;
  const Vec2 away = (m.points[joined] - m.points[tip_point]).normalized();
  // Within about 18 degrees of a straight line: the extrapolation assumes one crack.
  constexpr double kMinCosine = 0.95;
  int best = -1;
  double best_cosine = kMinCosine;
  for (int k : std::span(joints_).subspan(joint_offset_[joined], joint_offset_[joined + 1] - joint_offset_[joined])) {
    if (k == behind) continue;
    bool broken = true;
    for (int ci : system.joint_contacts(k)) broken = broken && !system.contacts()[ci].bonded;
    if (!broken) continue;
    const double cosine = direction_from(m, k, joined).dot(away);
    if (cosine >= best_cosine) best = k, best_cosine = cosine;
  }
  return best;
}

void CrackTips::find(const dda::BlockSystem& system, const std::vector<dda::ContactTraction>& tractions,
                     const Eigen::VectorXd& d, std::vector<CrackTipState>& tips, std::vector<char>& governed) const {
  const mesh::Mesh& m = system.mesh();
  const auto& contacts = system.contacts();
  tips.clear();
  governed.assign(contacts.size(), 0);
  // A joint is broken at a point when its contact there is: a joint broken at one end
  // only (its other bond intact) is then crack behind that end and intact ahead of the other.
  auto bonded_at = [&](int j, int point) { return contacts[system.joint_contacts(j)[end_at(m, j, point)]].bonded; };

  std::vector<char> visited(m.points.size(), 0);
  std::vector<Vec2> candidate_directions;
  std::vector<int> candidates;
  for (int ci = 0; ci < static_cast<int>(contacts.size()); ++ci) {
    const dda::Contact& broken_contact = contacts[ci];
    if (broken_contact.joint < 0 || broken_contact.bonded) continue;
    const int point = broken_contact.point;
    if (visited[point]) continue;
    visited[point] = 1;
    const auto at_point = std::span(joints_).subspan(joint_offset_[point], joint_offset_[point + 1] - joint_offset_[point]);
    // Forward joints: bonded at the point and pointing away from every joint broken there.
    int reference = -1, behind = -1;
    double best_alignment = -2.0;
    candidates.clear();
    candidate_directions.clear();
    for (int a : at_point) {
      if (!bonded_at(a, point)) continue;
      const Vec2 da = direction_from(m, a, point);
      bool forward = true;
      int most_opposite = -1;
      double alignment = -2.0;
      for (int k : at_point) {
        if (bonded_at(k, point)) continue;
        const double cosine = da.dot(direction_from(m, k, point));
        forward = forward && cosine < 0.0;
        if (-cosine > alignment) alignment = -cosine, most_opposite = k;
      }
      if (!forward) continue;
      if (alignment > best_alignment) best_alignment = alignment, reference = a, behind = most_opposite;
      if (m.joints[a].properties.breakable) candidates.push_back(a), candidate_directions.push_back(da);
    }
    if (reference < 0) continue;  // the inside of a crack, or its faces: no tip here
    const int second = continuing_broken_joint(system, behind, point);
    for (int a : at_point)
      if (bonded_at(a, point))
        for (int end_contact : system.joint_contacts(a)) governed[end_contact] = 1;

    CrackTipState state;
    state.tip = closure_data(system, tractions, d, reference, behind, second, point);
    state.direction = direction_from(m, reference, point);
    if (!candidates.empty()) {
      const fracture::StressIntensities k = fracture::stress_intensities(state.tip);
      const double kink = fracture::kink_angle_rad(k.mode1_Pa_sqrt_m, k.mode2_Pa_sqrt_m);
      state.failing_joint = candidates[fracture::nearest_direction(candidate_directions, state.direction, kink)];
      state.failing_contact = system.joint_contacts(state.failing_joint)[end_at(m, state.failing_joint, point)];
    }
    tips.push_back(state);
  }
}

}  // namespace hfdda::coupling
