#include "fracture/fracture_criteria.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace hfdda::fracture {

double tensile_strength_from_toughness(double fracture_toughness_Pa_sqrt_m, double joint_length_m) {
  return fracture_toughness_Pa_sqrt_m / std::sqrt(std::numbers::pi * joint_length_m / 2.0);  // eq. 4.13
}

BondStrength bond_strength(const mesh::JointProperties& p, double joint_length_m) {
  const double t0 = p.fracture_toughness_Pa_sqrt_m
                        ? tensile_strength_from_toughness(*p.fracture_toughness_Pa_sqrt_m, joint_length_m)
                        : p.tensile_strength_Pa;
  return {t0, p.cohesion_Pa, std::tan(p.friction_angle_rad)};
}

FailureMode failure_mode(const Bond& b, bool shear_failure_of_intact_joints) {
  if (b.normal_N > b.strength.tensile_strength_Pa * b.length_m) return FailureMode::tension;
  const double friction_limit = std::max(-b.normal_N, 0.0) * b.strength.tan_friction;
  if ((shear_failure_of_intact_joints || b.natural) && std::abs(b.shear_N) > b.strength.cohesion_Pa * b.length_m + friction_limit)
    return FailureMode::shear;
  return FailureMode::none;
}

bool may_fail(const Bond& b, const std::vector<char>& pressurised, const FractureRules& rules) {
  if (!b.breakable) return false;
  if (!rules.failure_needs_open_neighbour_and_fluid) return true;
  if (b.natural) return pressurised[b.point] || b.failed_neighbour;
  if (!pressurised[b.point] && !pressurised[b.other_point]) return false;
  return b.open_neighbour;
}

std::vector<int> most_stressed(const std::vector<double>& stress, double tie_tolerance) {
  std::vector<int> selected;
  if (stress.empty()) return selected;
  const double top = *std::max_element(stress.begin(), stress.end());
  for (int i = 0; i < static_cast<int>(stress.size()); ++i)
    if (stress[i] >= top - tie_tolerance * std::abs(top)) selected.push_back(i);
  return selected;
}

std::vector<BondFailure> failing_bonds(const std::vector<Bond>& bonds, const std::vector<char>& pressurised,
                                       const FractureRules& rules) {
  std::vector<BondFailure> failures;
  std::vector<double> tension_stress;  // N / Lc of the tension candidates
  std::vector<int> tension_contact;
  for (const Bond& b : bonds) {
    const FailureMode mode = failure_mode(b, rules.shear_failure_of_intact_joints);
    if (mode == FailureMode::none || !may_fail(b, pressurised, rules)) continue;
    if (mode == FailureMode::tension) {
      tension_stress.push_back(b.normal_N / b.length_m);
      tension_contact.push_back(b.contact);
    } else {
      failures.push_back({b.contact, FailureMode::shear, b.shear_N >= 0.0 ? 1.0 : -1.0});
    }
  }
  for (int i : most_stressed(tension_stress, rules.tie_tolerance))
    failures.push_back({tension_contact[i], FailureMode::tension, 0.0});
  return failures;
}

}  // namespace hfdda::fracture

namespace hfdda::fracture {

double failure_margin_N(const Bond& b, bool shear_failure_of_intact_joints) {
  const double tension = b.strength.tensile_strength_Pa * b.length_m - b.normal_N;
  if (!shear_failure_of_intact_joints && !b.natural) return tension;
  const double shear = b.strength.cohesion_Pa * b.length_m + std::max(-b.normal_N, 0.0) * b.strength.tan_friction -
                       std::abs(b.shear_N);
  return std::min(tension, shear);
}

double level_at_zero_margin(double level_a, double margin_a, double level_b, double margin_b) {
  const double slope = (margin_b - margin_a) / (level_b - level_a);
  if (!(slope < 0.0)) return std::numeric_limits<double>::infinity();
  return level_b - margin_b / slope;
}

}  // namespace hfdda::fracture
