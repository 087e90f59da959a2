#pragma once
// The intact joint bonds of a block system as fracture::Bond records (seed 2.3, 5.1),
// in one place: their strengths are computed once from the joint properties and the
// undeformed joint lengths (eq. 4.13 for a toughness), and a bond record is filled from
// a contact and the forces it carries. The coupled step reads it at the trial forces of
// an open-close iteration, the load ramp at the committed forces of a level.

#include <vector>

#include "coupling/crack_tips.hpp"
#include "dda/block_system.hpp"
#include "fracture/fracture_criteria.hpp"

namespace hfdda::coupling {

class BondList {
 public:
  explicit BondList(const dda::BlockSystem& system);

  /// Whether joint contact `contact` is an intact bond that may ever fail (bonded,
  /// locked, its joint breakable).
  bool is_candidate(const dda::BlockSystem& system, int contact) const;
  /// The bond of joint contact `contact` carrying forces (normal tension positive, shear)
  /// [N per m thickness]; the neighbour queries of the localisation rules are left unset.
  fracture::Bond bond(const dda::BlockSystem& system, int contact, double normal_N, double shear_N) const;
  /// Fills the neighbour queries the localisation rules need (seed 2.3 i, 5.1).
  static void add_neighbours(const dda::BlockSystem& system, fracture::Bond& bond);
  const fracture::BondStrength& strength(int joint) const { return strength_[joint]; }
  /// The crack tips of the system (the toughness criterion's view of the same bonds).
  const CrackTips& crack_tips() const { return crack_tips_; }

 private:
  std::vector<fracture::BondStrength> strength_;  // per joint
  CrackTips crack_tips_;
};

}  // namespace hfdda::coupling
