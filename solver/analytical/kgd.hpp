#pragma once
// KGD (plane-strain, bi-wing) hydraulic fracture in the viscosity-storage regime:
// zero toughness (K' = 0), zero leak-off (C' = 0), Newtonian fluid, constant total
// injection rate. This is the "M-vertex" of Detournay's parametric space (Adachi &
// Detournay 2002; Garagash & Detournay 2005; seed section 3.2, eqs. 3.2-3.4).
//
// Inputs and units
//   E   Young's modulus [Pa], nu Poisson's ratio [-]  -> E'  = E / (1 - nu^2)
//   mu  dynamic viscosity [Pa s]                      -> mu' = 12 mu   (seed eq. 3.2)
//   Q0  total volumetric injection rate into both wings per metre of fracture height
//       [m^2/s] (= mass rate per metre [kg/(s m)] / fluid density [kg/m^3]; seed 3.2:
//       Q0 = 4 kg/s / 1000 kg/m^3 = 4e-3 m^2/s)
//   t   time since the start of injection [s]
//
// Scalings (seed eq. 3.4):
//   zeta(t) = (mu' / (E' t))^(1/3)                [-]
//   psi(t)  = (E' Q0^3 / mu')^(1/6) t^(2/3)       [m]
// Solution (seed eq. 3.3 with erratum 3 in docs/seed_errata.md):
//   l(t)  = Gamma psi,                 Gamma  = 0.61524   half-length [m]
//   w0(t) = zeta psi Gamma Omega0,     Omega0 = 1.8302    inlet width [m]
//           (the seed's eq. 3.3 omits Gamma: Omega0 is normalised by the half-length)
//   p0(t) = zeta E' Phi0,              Phi0   = 0.54495   inlet NET pressure [Pa]
//           (net pressure = fluid pressure - far-field compressive stress normal to
//           the fracture, both compression positive)
// Independent closed forms (GEOS documentation, Adachi & Detournay 2002; erratum 3
// in docs/seed_errata.md), the reference used by the verification driver:
//   w0^2   = 2.1  sqrt(mu' Q0 / E') l
//   w0 p0  = 0.62 sqrt(mu' Q0 E')
// The two agree to rounding of the published coefficients: 2.1 vs
// Gamma Omega0^2 = 2.0608 (w0 +0.95 %), 0.62 vs Gamma Omega0 Phi0 = 0.61362 (p0 +0.09 %);
// tests/test_analytical_kgd.cpp pins this down.
//
// Growth laws: l ~ t^(2/3), w0 ~ t^(1/3), p0 ~ t^(-1/3).

#include <cmath>

namespace hfdda::analytical {

/// Dimensionless M-vertex constants of the seed (section 3.2, Newtonian fluid).
inline constexpr double kKgdMGamma = 0.61524;   ///< normalised half-length
inline constexpr double kKgdMOmega0 = 1.8302;   ///< normalised inlet opening (per half-length)
inline constexpr double kKgdMPhi0 = 0.54495;    ///< normalised inlet net pressure
/// Coefficients of the closed forms of erratum 3 in docs/seed_errata.md (GEOS docs, Adachi & Detournay 2002).
inline constexpr double kKgdMWidthSquaredCoefficient = 2.1;   ///< w0^2 = 2.1 sqrt(mu' Q0 / E') l
inline constexpr double kKgdMWidthPressureCoefficient = 0.62; ///< w0 p0 = 0.62 sqrt(mu' Q0 E')

/// Plane-strain modulus E' = E / (1 - nu^2) [Pa] (seed eq. 3.2).
inline double plane_strain_modulus(double youngs_modulus_Pa, double poissons_ratio) {
  return youngs_modulus_Pa / (1.0 - poissons_ratio * poissons_ratio);
}

/// M-vertex KGD state at one time; every field in SI units.
struct KgdViscositySolution {
  double time_s = 0.0;
  double plane_strain_modulus_Pa = 0.0;   ///< E'
  double scaled_viscosity_Pa_s = 0.0;     ///< mu' = 12 mu
  double zeta = 0.0;                      ///< (mu' / (E' t))^(1/3), eq. 3.4 [-]
  double psi_m = 0.0;                     ///< (E' Q0^3 / mu')^(1/6) t^(2/3), eq. 3.4 [m]
  double half_length_m = 0.0;             ///< l = Gamma psi
  /// Reference values (erratum 3 in docs/seed_errata.md): w0^2 = 2.1 sqrt(mu' Q0/E') l, w0 p0 = 0.62 sqrt(mu' Q0 E').
  double inlet_width_m = 0.0;
  double inlet_net_pressure_Pa = 0.0;
  /// Seed-form values (eq. 3.3 corrected by erratum 3): w0 = zeta psi Gamma Omega0, p0 = zeta E' Phi0.
  double inlet_width_seed_form_m = 0.0;
  double inlet_net_pressure_seed_form_Pa = 0.0;
};

/// Zero-toughness, zero-leak-off KGD fracture (M-vertex) at time t > 0 for total
/// injection rate Q0 [m^2/s] (both wings, per metre of height). Seed section 3.2,
/// eqs. 3.2-3.4, with erratum 3 in docs/seed_errata.md for the inlet width and net pressure.
inline KgdViscositySolution kgd_viscosity_storage(double youngs_modulus_Pa, double poissons_ratio,
                                                   double viscosity_Pa_s, double total_rate_m2_s, double time_s) {
  KgdViscositySolution s;
  const double Ep = plane_strain_modulus(youngs_modulus_Pa, poissons_ratio);
  const double mup = 12.0 * viscosity_Pa_s;  // eq. 3.2
  const double Q0 = total_rate_m2_s;
  s.time_s = time_s;
  s.plane_strain_modulus_Pa = Ep;
  s.scaled_viscosity_Pa_s = mup;
  s.zeta = std::cbrt(mup / (Ep * time_s));                                            // eq. 3.4
  s.psi_m = std::pow(Ep * Q0 * Q0 * Q0 / mup, 1.0 / 6.0) * std::pow(time_s, 2.0 / 3.0);  // eq. 3.4
  s.half_length_m = kKgdMGamma * s.psi_m;                                             // eq. 3.3
  s.inlet_width_m = std::sqrt(kKgdMWidthSquaredCoefficient * std::sqrt(mup * Q0 / Ep) * s.half_length_m);
  s.inlet_net_pressure_Pa = kKgdMWidthPressureCoefficient * std::sqrt(mup * Q0 * Ep) / s.inlet_width_m;
  s.inlet_width_seed_form_m = s.zeta * s.psi_m * kKgdMGamma * kKgdMOmega0;  // eq. 3.3, erratum 3
  s.inlet_net_pressure_seed_form_Pa = s.zeta * Ep * kKgdMPhi0;            // eq. 3.3
  return s;
}

// ---------------------------------------------------------------------------
// KGD fracture in the toughness-storage regime: zero viscosity, zero leak-off, constant
// total injection rate, Mode I toughness K_IC. The "K-vertex" of Detournay's parametric
// space (Garagash & Detournay 2005; seed section 4.5, eqs. 4.31-4.32). The fluid
// pressure is uniform along the fracture, so the solution is exact in closed form.
//
// Inputs: E, nu (-> E'), K_IC [Pa m^0.5] -> K' = 4 sqrt(2/pi) K_IC = sqrt(32/pi) K_IC,
// Q0 total rate into both wings per metre of height [m^2/s], t since injection start [s].
// Scalings (seed eq. 4.32):
//   zeta(t) = (K' / (E' (Q0 t)^(1/4)))^(4/3)      [-]
//   psi(t)  = (E' Q0 t / K')^(2/3)                [m]
// Solution (seed eq. 4.31 with erratum 3 in docs/seed_errata.md for w0):
//   l(t)  = Gamma psi,                 Gamma  = 2 / pi^(2/3) = 0.9324
//   w0(t) = zeta psi Gamma Omega0,     Omega0 = 0.7323 (Gamma Omega0 = pi^(-1/3) = 0.6828)
//   p0(t) = zeta E' Phi0,              Phi0   = pi^(1/3) / 8 = 0.1831   (net pressure)
// Independent check (tests/test_analytical_kgd.cpp): a crack of half-length l under a
// uniform net pressure p opens as w = (4 p / E') sqrt(l^2 - x^2), so K_I = p sqrt(pi l),
// w0 = 4 p l / E' and its volume is 2 pi p l^2 / E'; K_I = K_IC and volume = Q0 t give
// the three formulas above with the exact constants.
// Growth laws: l ~ t^(2/3), w0 ~ t^(1/3), p0 ~ t^(-1/3).

/// Dimensionless K-vertex constants of the seed (section 4.5), as printed.
inline constexpr double kKgdKGamma = 0.9324;   ///< normalised half-length
inline constexpr double kKgdKOmega0 = 0.7323;  ///< normalised inlet opening (per half-length, erratum 3)
inline constexpr double kKgdKPhi0 = 0.1831;    ///< normalised inlet (uniform) net pressure

/// K' = 4 sqrt(2 / pi) K_IC [Pa m^0.5].
inline double scaled_toughness(double fracture_toughness_Pa_sqrt_m) {
  return 4.0 * std::sqrt(2.0 / std::acos(-1.0)) * fracture_toughness_Pa_sqrt_m;
}

/// Toughness matched to a tensile strength T0 [Pa] on joints of length L [m]:
/// K_IC = T0 sqrt(pi L / 2) (seed eq. 4.13; erratum 7 in docs/seed_errata.md).
inline double toughness_of_tensile_strength(double tensile_strength_Pa, double joint_length_m) {
  return tensile_strength_Pa * std::sqrt(std::acos(-1.0) * joint_length_m / 2.0);
}

/// Dimensionless toughness of a plane-strain (KGD) fracture without leak-off,
///   K_m = K' / (E'^3 mu' Q0)^(1/4),   mu' = 12 mu,
/// independent of time (Detournay 2004, Int. J. Geomech. 4(1), "Propagation regimes of
/// fluid-driven fractures in impermeable rocks"): the solution is the K-vertex above for
/// K_m >~ 4 and the viscosity-dominated M-vertex for K_m <~ 1. Between them the fluid's
/// pressure drop along the fracture is not negligible and the K-vertex is only an
/// approximation (docs/design_notes.md section 44). Q0 the total rate [m^2/s], mu [Pa s].
inline double kgd_dimensionless_toughness(double youngs_modulus_Pa, double poissons_ratio,
                                          double fracture_toughness_Pa_sqrt_m, double viscosity_Pa_s,
                                          double total_rate_m2_s) {
  const double Ep = plane_strain_modulus(youngs_modulus_Pa, poissons_ratio);
  return scaled_toughness(fracture_toughness_Pa_sqrt_m) /
         std::pow(Ep * Ep * Ep * 12.0 * viscosity_Pa_s * total_rate_m2_s, 0.25);
}

/// K-vertex KGD state at one time; every field in SI units.
struct KgdToughnessSolution {
  double time_s = 0.0;
  double plane_strain_modulus_Pa = 0.0;  ///< E'
  double scaled_toughness_Pa_sqrt_m = 0.0;  ///< K'
  double zeta = 0.0;                     ///< (K' / (E' (Q0 t)^(1/4)))^(4/3), eq. 4.32 [-]
  double psi_m = 0.0;                    ///< (E' Q0 t / K')^(2/3), eq. 4.32 [m]
  double half_length_m = 0.0;            ///< l = Gamma psi
  double inlet_width_m = 0.0;            ///< w0 = zeta psi Gamma Omega0 (erratum 3)
  double inlet_net_pressure_Pa = 0.0;    ///< p0 = zeta E' Phi0, uniform along the fracture
};

/// Zero-viscosity, zero-leak-off KGD fracture (K-vertex) at time t > 0 for toughness
/// K_IC [Pa m^0.5] and total injection rate Q0 [m^2/s] (both wings, per metre of height).
/// Seed section 4.5, eqs. 4.31-4.32, with erratum 3 in docs/seed_errata.md for w0.
inline KgdToughnessSolution kgd_toughness_storage(double youngs_modulus_Pa, double poissons_ratio,
                                                  double fracture_toughness_Pa_sqrt_m, double total_rate_m2_s,
                                                  double time_s) {
  KgdToughnessSolution s;
  const double Ep = plane_strain_modulus(youngs_modulus_Pa, poissons_ratio);
  const double Kp = scaled_toughness(fracture_toughness_Pa_sqrt_m);
  const double Qt = total_rate_m2_s * time_s;
  s.time_s = time_s;
  s.plane_strain_modulus_Pa = Ep;
  s.scaled_toughness_Pa_sqrt_m = Kp;
  s.zeta = std::pow(Kp / (Ep * std::pow(Qt, 0.25)), 4.0 / 3.0);  // eq. 4.32
  s.psi_m = std::pow(Ep * Qt / Kp, 2.0 / 3.0);                     // eq. 4.32
  s.half_length_m = kKgdKGamma * s.psi_m;                          // eq. 4.31
  s.inlet_width_m = s.zeta * s.psi_m * kKgdKGamma * kKgdKOmega0;   // eq. 4.31, erratum 3
  s.inlet_net_pressure_Pa = s.zeta * Ep * kKgdKPhi0;               // eq. 4.31
  return s;
}

}  // namespace hfdda::analytical
