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

}  // namespace hfdda::analytical
