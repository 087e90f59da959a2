#pragma once
// Failure of the bonds between blocks (seed section 2.3), as pure functions of
// explicit inputs: the trial contact forces of the intact joint contacts, their
// strengths and lengths, which points hold pressurised fluid and which contacts have
// an open neighbour. The coupled step calls failing_bonds() between the trial
// tractions of an open-close iteration and applying its state changes.
//
// The pieces, each replaceable on its own:
//   bond_strength()   T0, C0, phi of a joint's bond from its properties; a fracture
//                     toughness K_IC becomes T0 = K_IC / sqrt(pi L / 2) from the
//                     joint's length L (seed eq. 4.13)
//   failure_mode()    the criterion: Rankine tension, else Mohr-Coulomb shear
//   may_fail()        eligibility, seed 2.3 (i) for rock bonds, seed 5.1 for natural
//                     fractures (failure localised at their tip)
//   most_stressed()   selection among the tension failures, seed 2.3 (iii)
// FractureRules::criterion chooses between these rules everywhere (the seed) and the
// toughness criterion at crack tips (toughness_criterion.hpp) with these rules elsewhere.

#include <cstdint>
#include <vector>

#include "fracture/toughness_criterion.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::fracture {

/// Strength of the bond of one joint contact.
struct BondStrength {
  double tensile_strength_Pa = 0.0;  ///< T0 (Rankine limit)
  double cohesion_Pa = 0.0;          ///< C0 (Mohr-Coulomb)
  double tan_friction = 0.0;         ///< tan phi
};

/// The bond strength of a joint from its properties (both of its contacts share it).
/// With a fracture toughness K_IC [Pa m^0.5] the tensile strength is
/// T0 = K_IC / sqrt(pi L / 2), L = joint_length_m the whole joint's length (seed eq. 4.13:
/// the joint ahead of a crack tip carries K_I sqrt(2 L / pi) at failure); without one it
/// is properties.tensile_strength_Pa and the length is not used.
BondStrength bond_strength(const mesh::JointProperties& properties, double joint_length_m);

/// T0 = K_IC / sqrt(pi L / 2) [Pa] for toughness K_IC [Pa m^0.5] and joint length L [m] (seed eq. 4.13).
double tensile_strength_from_toughness(double fracture_toughness_Pa_sqrt_m, double joint_length_m);

/// The rules of seed 2.3 that are case settings.
struct FractureRules {
  double tie_tolerance = 1.0e-3;               ///< 2.3 (iii): relative tie of the largest tensions
  bool shear_failure_of_intact_joints = false; ///< Mohr-Coulomb failure of intact bonds
  /// Seed 2.3 (i): a bond may fail only next to an open contact and a pressurised point.
  bool failure_needs_open_neighbour_and_fluid = true;
  /// Bonds fail only in an open-close round in which no contact changes state (not in
  /// the seed, which checks both in one round): the failure is judged on a settled state.
  bool failures_on_settled_contacts = false;
  /// strength: the rules above everywhere (the seed). energy_release_rate: intact joints
  /// at a crack tip fail by the toughness criterion (toughness_criterion.hpp), the
  /// bonds elsewhere by the rules above.
  FailureCriterion criterion = FailureCriterion::strength;
  Toughness toughness;  ///< with energy_release_rate: K_IC and K_IIC
};

/// An intact (bonded, locked) joint contact at the trial state of an open-close iteration.
struct Bond {
  int contact = -1;                 ///< index of the contact (returned with its failure)
  int point = -1, other_point = -1; ///< the contact's point and the joint's other end
  double length_m = 0.0;            ///< contact length Lc (half the joint)
  double normal_N = 0.0;            ///< trial normal force, tension positive [N per m thickness]
  double shear_N = 0.0;             ///< trial shear force [N per m thickness]
  BondStrength strength;
  bool breakable = true;            ///< false: the bond never fails
  /// Part of a natural fracture (seed 5.1): it may fail in shear whatever
  /// FractureRules::shear_failure_of_intact_joints says, under the natural-fracture
  /// localisation of may_fail().
  bool natural = false;
  bool open_neighbour = false;      ///< the joint's other end or a joint contact at `point` is open
  /// The joint's other end or a joint contact at `point` has failed: open, or its bond
  /// broken (sliding or re-closed). Natural fractures only (seed 5.1).
  bool failed_neighbour = false;
};

enum class FailureMode : std::uint8_t { none, tension, shear };

/// The limit the bond's forces exceed: tension N > T0 Lc first; else, if shear failure
/// of intact joints is on or the bond is natural, |S| > C0 Lc + max(-N, 0) tan phi.
FailureMode failure_mode(const Bond& bond, bool shear_failure_of_intact_joints);

/// Breakable and, if FractureRules::failure_needs_open_neighbour_and_fluid is on:
///  - a rock bond (seed 2.3 i): next to an open contact and to a pressurised point (at
///    either end of its joint);
///  - a natural-fracture bond (seed 5.1): at a pressurised point, or next to a contact
///    that has already failed (open or sliding), so that a natural fracture fails from
///    its tip on rather than along its whole length at once.
bool may_fail(const Bond& bond, const std::vector<char>& pressurised_points, const FractureRules& rules);

/// Seed 2.3 (iii): of the tension failures only the most stressed fails, with all
/// within tie_tolerance (relative) of it. Returns the indices into `normal_stress_Pa`.
std::vector<int> most_stressed(const std::vector<double>& normal_stress_Pa, double tie_tolerance);

struct BondFailure {
  int contact = -1;
  FailureMode mode = FailureMode::none;
  double friction_sign = 0.0;  ///< shear failures: sense of the sliding friction force
};

/// The bonds that fail in this open-close iteration: the shear failures in bond order,
/// then the selected tension failures in bond order.
std::vector<BondFailure> failing_bonds(const std::vector<Bond>& bonds, const std::vector<char>& pressurised_points,
                                       const FractureRules& rules);

}  // namespace hfdda::fracture

namespace hfdda::fracture {

/// How far an intact bond is from the limits of failure_mode() [N per m thickness]: the
/// smaller of T0 Lc - N and, if shear failure of intact joints is on,
/// C0 Lc + max(-N, 0) tan phi - |S|. Positive below both limits.
double failure_margin_N(const Bond& bond, bool shear_failure_of_intact_joints);

/// The load level at which a margin that is linear in the level reaches zero, from its
/// values at two distinct levels; +infinity if the margin does not decrease with the level.
/// (Before the first failure a static DDA system is linear in its loads, seed 4.2.)
double level_at_zero_margin(double level_a, double margin_a, double level_b, double margin_b);

}  // namespace hfdda::fracture
