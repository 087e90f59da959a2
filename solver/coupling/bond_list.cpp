#include "coupling/bond_list.hpp"

namespace hfdda::coupling {

BondList::BondList(const dda::BlockSystem& system) : crack_tips_(system) {
  const auto& joints = system.mesh().joints;
  const auto& points = system.mesh().points;
  strength_.reserve(joints.size());
  for (const auto& joint : joints)
    strength_.push_back(
        fracture::bond_strength(joint.properties, (points[joint.point_q] - points[joint.point_p]).norm()));
}

bool BondList::is_candidate(const dda::BlockSystem& system, int contact) const {
  const dda::Contact& c = system.contacts()[contact];
  return c.joint >= 0 && c.bonded && c.state == dda::ContactState::locked &&
         system.mesh().joints[c.joint].properties.breakable;
}

fracture::Bond BondList::bond(const dda::BlockSystem& system, int contact, double normal_N, double shear_N) const {
  const dda::Contact& c = system.contacts()[contact];
  const mesh::Joint& joint = system.mesh().joints[c.joint];
  fracture::Bond b;
  b.contact = contact;
  b.point = c.point;
  b.other_point = c.end == 0 ? joint.point_q : joint.point_p;
  b.length_m = c.length_m;
  b.normal_N = normal_N;
  b.shear_N = shear_N;
  b.strength = strength_[c.joint];
  b.breakable = joint.properties.breakable;
  b.natural = joint.properties.natural;
  return b;
}

void BondList::add_neighbours(const dda::BlockSystem& system, fracture::Bond& bond) {
  bond.open_neighbour = system.has_open_neighbour(bond.contact);
  if (bond.natural) bond.failed_neighbour = system.has_failed_neighbour(bond.contact);
}

}  // namespace hfdda::coupling
