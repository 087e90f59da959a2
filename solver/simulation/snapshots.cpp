#include "simulation/snapshots.hpp"

#include <map>

namespace hfdda::simulation {

io::BlockFrame block_frame(const dda::BlockSystem& s, const std::vector<int>& zone_of_material) {
  io::BlockFrame f;
  f.corner_offsets.push_back(0);
  for (int b = 0; b < s.n_blocks(); ++b) {
    for (int k = 0; k < s.n_corners(b); ++k) {
      f.corners.push_back(s.corner(b, k));
      f.corner_displacement.push_back(s.corner(b, k) - s.initial_corner(b, k));
    }
    f.corner_offsets.push_back(static_cast<int>(f.corners.size()));
    f.stress.push_back(s.stress(b));
    const int material = s.block_material()[b];
    f.material.push_back(zone_of_material.empty() ? material : zone_of_material[static_cast<std::size_t>(material)]);
  }
  return f;
}

std::vector<io::JointRow> joint_rows(const dda::BlockSystem& s, const fluid::FlowNetwork* flow) {
  const auto& m = s.mesh();
  std::vector<io::JointRow> rows(m.joints.size());
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const auto& joint = m.joints[j];
    const int na = s.n_corners(joint.block_a), nb = s.n_corners(joint.block_b);
    io::JointRow& r = rows[j];
    r.id = static_cast<int>(j);
    // Current end points: mean of the two faces' corners at each end.
    r.p = 0.5 * (s.corner(joint.block_a, joint.corner_a) + s.corner(joint.block_b, (joint.corner_b + 1) % nb));
    r.q = 0.5 * (s.corner(joint.block_a, (joint.corner_a + 1) % na) + s.corner(joint.block_b, joint.corner_b));
    r.length_m = (r.q - r.p).norm();
    const auto [cp, cq] = s.joint_contacts(static_cast<int>(j));
    const auto& contact_p = s.contacts()[cp];
    const auto& contact_q = s.contacts()[cq];
    r.aperture_p_m = std::max(0.0, s.joint_gap(static_cast<int>(j), 0));
    r.aperture_q_m = std::max(0.0, s.joint_gap(static_cast<int>(j), 1));
    const auto [np, sp] = s.contact_forces(cp);
    const auto [nq, sq] = s.contact_forces(cq);
    r.normal_stress_p_Pa = np / contact_p.length_m;
    r.normal_stress_q_Pa = nq / contact_q.length_m;
    r.shear_stress_p_Pa = sp / contact_p.length_m;
    r.shear_stress_q_Pa = sq / contact_q.length_m;
    r.state_p = dda::to_string(contact_p.state);
    r.state_q = dda::to_string(contact_q.state);
    r.broken = !contact_p.bonded || !contact_q.bonded;
    r.natural = joint.properties.natural;
    // Without a flow network, fluid is where a pressure is prescribed (coupling::PrescribedPressure).
    r.fluid = flow ? flow->wetted(static_cast<int>(j)) : joint.properties.prescribed_pressure_Pa >= 0.0;
    if (flow && r.fluid) {
      r.pressure_p_Pa = flow->pressure(joint.point_p);
      r.pressure_q_Pa = flow->pressure(joint.point_q);
    }
  }
  return rows;
}

std::vector<std::pair<int, double>> apertures_at_points(const dda::BlockSystem& s, const std::vector<int>& joints) {
  std::map<int, std::pair<double, int>> sum;  // point -> (sum, count)
  for (int j : joints) {
    const auto& joint = s.mesh().joints[j];
    for (int end = 0; end < 2; ++end) {
      auto& acc = sum[end == 0 ? joint.point_p : joint.point_q];
      acc.first += std::max(0.0, s.joint_gap(j, end));
      ++acc.second;
    }
  }
  std::vector<std::pair<int, double>> out;
  for (const auto& [point, acc] : sum) out.emplace_back(point, acc.first / acc.second);
  return out;
}

}  // namespace hfdda::simulation
