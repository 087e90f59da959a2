#pragma once
// A fracture-toughness criterion evaluated from the solution at a crack tip, beside the
// seed's strength rule (fracture_criteria.hpp). Pure functions of explicit inputs: the
// forces of the intact joint ahead of a tip, the opening and slip of the broken joint
// behind it, the plane-strain modulus and the toughness.
//
//   vcct_energy_release_rates()  G_I and G_II by the virtual crack closure technique
//                                (Rybicki & Kanninen 1977) in the DDA's lumping: a joint
//                                carries its traction as two contact forces at its ends
//   stress_intensities()         K_I, K_II from G (Irwin, plane strain: G = K^2 / E',
//                                E' = E / (1 - nu^2)); K_II signed by the sense of slip
//   mixed_mode_ratio()           G_I / G_IC + G_II / G_IIC; the tip joint fails at >= 1
//   kink_angle_rad()             direction of growth, maximum hoop stress (Erdogan & Sih 1963)
//   level_at_critical_ratio()    the load level at which the ratio reaches 1, from two levels
//                                of a response linear in the level (G is then quadratic in it)
//
// Where there is no crack tip (an uncracked body) the criterion does not apply: the
// bonds there keep the strength rule, T0 (docs/formulation.md section 5).

#include <vector>

#include "core/geometry.hpp"

namespace hfdda::fracture {

/// Which rule fails an intact joint at a crack tip.
enum class FailureCriterion { strength, energy_release_rate };

/// How G is read from the discrete crack closure (vcct_energy_release_rates).
enum class CrackClosure {
  one_joint,     ///< the joint ahead closed against the joint behind (error O(da / a))
  extrapolated,  ///< one joint and two joints of closure, extrapolated to da -> 0
};

/// Critical energy release rates from the toughnesses of the case [Pa m^0.5], and how
/// G is evaluated.
struct Toughness {
  double mode1_Pa_sqrt_m = 0.0;  ///< K_IC
  double mode2_Pa_sqrt_m = 0.0;  ///< K_IIC (the case's default: K_IC)
  CrackClosure closure = CrackClosure::extrapolated;
};

/// The discrete crack-closure data of one crack tip, in the tip's frame: e along the
/// intact joint ahead of the tip (from the tip point), n = e turned +90 degrees. Plain
/// values only (a load ramp's checkpoint stores them).
/// Forces are those the joint's contacts carry [N per m thickness], tension positive;
/// shear forces and slips are along e, of the +n face relative to the -n face.
struct CrackTip {
  int joint = -1;                  ///< the intact joint ahead of the tip (the reference for G)
  int behind_joint = -1;           ///< the broken joint behind the tip
  int tip_point = -1;
  double length_m = 0.0;           ///< da: length of the joint ahead
  double behind_length_m = 0.0;    ///< length of the joint behind
  double tip_normal_N = 0.0, tip_shear_N = 0.0;  ///< contact of the joint ahead at the tip
  double far_normal_N = 0.0, far_shear_N = 0.0;  ///< its contact at its far end
  /// Opening and slip of the joint behind at its far end (behind_length_m from the tip) [m].
  double far_opening_m = 0.0, far_slip_m = 0.0;
  /// Opening and slip of the joint behind at the tip point [m] (zero for a sharp tip).
  double near_opening_m = 0.0, near_slip_m = 0.0;
  /// Opening and slip at the far end of the second broken joint behind (the one that
  /// continues the joint behind in a straight line), and that end's distance from the
  /// tip [m]; distance 0: there is none (CrackClosure::extrapolated then reads one joint).
  double second_opening_m = 0.0, second_slip_m = 0.0, second_distance_m = 0.0;
  double plane_strain_modulus_Pa = 0.0;  ///< E' = E / (1 - nu^2) of the rock at the tip
};

struct EnergyReleaseRates {
  double mode1_J_m2 = 0.0;
  double mode2_J_m2 = 0.0;
};

struct StressIntensities {
  double mode1_Pa_sqrt_m = 0.0;  ///< K_I >= 0 (a closed tip has none)
  double mode2_Pa_sqrt_m = 0.0;  ///< K_II, the sign of the slip along e of the +n face
};

/// E' = E / (1 - nu^2) (plane strain).
double plane_strain_modulus_Pa(double youngs_modulus_Pa, double poissons_ratio);

/// pi / (2 sqrt 2) = 1.1107: the crack-closure integral of the near-tip field
/// (traction K / sqrt(2 pi x), opening 8 K sqrt(r / 2 pi) / E') over its value in the
/// DDA's lumping below, where the traction of the half joint next to the tip acts at
/// the tip and meets the opening at da: K sqrt(da / pi) 4 K sqrt(2 da / pi) / E' / (2 da)
/// = (2 sqrt 2 / pi) K^2 / E'. With it the lumped form is exact for that field.
inline constexpr double kLumpedClosureFactor = 1.1107207345395915;

/// VCCT in the DDA's lumping. Closing the joint ahead (length da) closes its two
/// contacts: the one at the tip, standing for the traction on the half joint next to the
/// tip, comes to lie da from the new tip, the one at the far end at the new tip. Each is
/// paired with the joint behind's opening at the same distance from the tip:
///   G_I  = c [F_n,tip d_n(da) + F_n,far d_n(0)] / (2 da),
///   G_II = c |F_s,tip d_s(da) + F_s,far d_s(0)| / (2 da),
/// c = kLumpedClosureFactor, with d(da) = d(L_b) sqrt(da / L_b) from the opening at the
/// far end of the joint behind (length L_b; the near-tip opening grows as sqrt(r)).
/// A Mode I pair counts only with tension and opening (F_n > 0, d_n > 0): compression
/// or faces pressed together release nothing. Throws std::invalid_argument for a
/// non-positive length.
///
/// CrackClosure::extrapolated: the pairing over one joint errs by O(da / a) (the joint
/// ahead reaches beyond the near-tip field: K_I 4 % low at a = 2 da on the Griffith
/// field). The pairing over a closure of 2 da, the whole joint ahead's two forces at the
/// tip against the opening 2 da behind (the second joint's far end, scaled by
/// sqrt(2 da / r2)), errs twice as much to first order, so G = 2 G(da) - G(2 da)
/// (Richardson) removes it:
///   G_I(da) = [F_n,tip d_n(da) + F_n,far d_n(0)] / (2 da),
///   G_I(2 da) = [F_n,tip + F_n,far] d_n(2 da) / (4 da)   (each force and d >= 0),
/// Mode II alike with |.|; each mode's result at least 0. Here the contact forces count as
/// they are, the textbook VCCT of nodal forces (c = 1), not with the factor c above: on
/// the DDA meshes the extrapolated rates with c converge to c G under refinement (Mode I
/// failure stresses 5-6 % below LEFM at every joint length, docs/design_notes.md section
/// 36), i.e. the contact forces next to a tip are not the half-joint integrals of the
/// singular traction that c assumes. Without a second joint behind, one joint (with c).
EnergyReleaseRates vcct_energy_release_rates(const CrackTip& tip, CrackClosure closure = CrackClosure::one_joint);

/// K = sqrt(G E') [Pa m^0.5] (Irwin, plane strain).
double stress_intensity_Pa_sqrt_m(double energy_release_rate_J_m2, double plane_strain_modulus_Pa);
/// G = K^2 / E' [J/m^2].
double energy_release_rate_J_m2(double stress_intensity_Pa_sqrt_m, double plane_strain_modulus_Pa);

/// K_I and K_II of a tip from its VCCT energy release rates; K_II takes the sign of the
/// slip at the far end of the joint behind.
StressIntensities stress_intensities(const CrackTip& tip, CrackClosure closure = CrackClosure::one_joint);

/// G_I / G_IC + G_II / G_IIC with G_C = K_C^2 / E' (the linear mixed-mode law; equal
/// toughnesses make it K_I^2 + K_II^2 >= K_IC^2). Throws std::invalid_argument for a
/// non-positive toughness or modulus.
double mixed_mode_ratio(const EnergyReleaseRates& rates, const Toughness& toughness, double plane_strain_modulus_Pa);

/// The tip's mixed_mode_ratio from its VCCT rates.
double mixed_mode_ratio(const CrackTip& tip, const Toughness& toughness);

/// Angle of growth from the crack's line [rad], counter-clockwise positive, by the
/// maximum hoop stress rule (Erdogan & Sih 1963): K_I sin(t) + K_II (3 cos(t) - 1) = 0,
///   t = 2 atan( -2 K_II / (K_I + sqrt(K_I^2 + 8 K_II^2)) ).
/// Pure Mode II (K_II > 0) gives -70.53 degrees; K_I < 0 is taken as 0; no load gives 0.
double kink_angle_rad(double mode1_Pa_sqrt_m, double mode2_Pa_sqrt_m);

/// Index of the direction nearest to `crack_direction` turned by `kink_rad` (unit
/// vectors or not); -1 for an empty list.
int nearest_direction(const std::vector<Vec2>& directions, const Vec2& crack_direction, double kink_rad);

/// The level at which the tip's mixed_mode_ratio reaches 1, from the tip at two distinct
/// levels of a response linear in the level (forces and openings each linear, so G is
/// quadratic): the smallest level beyond level_b; +infinity if the ratio does not reach
/// 1 there, or if it does so only past a contact that stops pulling (the quadratic ends
/// there). (The energy analogue of level_at_zero_margin().)
double level_at_critical_ratio(double level_a, const CrackTip& tip_a, double level_b, const CrackTip& tip_b,
                               const Toughness& toughness);

/// The tips at or above ratio 1, each of which advances by one joint. Indices into
/// `ratios`. Every tip, not only the largest (seed 2.3 iii picks the most stressed
/// bond): each tip is a front of its own, and as G grows with every joint a front opens,
/// the first front to fail would otherwise run alone while the others, a few per cent
/// lower on an irregular mesh, never catch up.
std::vector<int> critical_tips(const std::vector<double>& ratios);

}  // namespace hfdda::fracture
