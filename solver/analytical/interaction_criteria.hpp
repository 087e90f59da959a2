#pragma once
// Analytical criteria for a hydraulic fracture meeting a frictional natural fracture
// (docs/interaction_criteria.md restates them with their assumptions). Stresses are
// compression positive here, as in the sources, in Pa; the hydraulic fracture runs
// along sigma_H (its plane is normal to sigma_h) and meets the natural fracture at the
// approach angle theta (90 degrees: orthogonal).

#include <cmath>
#include <limits>

namespace hfdda::analytical {

/// Normal and shear stress on a natural fracture at approach angle theta [rad] to the
/// sigma_H direction: sigma_n = sigma_H sin^2 theta + sigma_h cos^2 theta,
/// tau = (sigma_H - sigma_h) sin theta cos theta (Warpinski and Teufel 1987, eq. 1-2).
struct PlaneStress {
  double normal_Pa = 0.0, shear_Pa = 0.0;
};
inline PlaneStress stress_on_natural_fracture(double theta_rad, double sigma_H_Pa, double sigma_h_Pa) {
  const double s = std::sin(theta_rad), c = std::cos(theta_rad);
  return {sigma_H_Pa * s * s + sigma_h_Pa * c * c, (sigma_H_Pa - sigma_h_Pa) * s * c};
}

/// Renshaw and Pollard (1995), orthogonal approach: the fracture crosses a cohesionless
/// frictional interface (friction coefficient mu) when
///     sigma_H / (T0 + sigma_h) > (0.35 + 0.35 / mu) / 1.06,
/// sigma_H the remote compression normal to the interface, sigma_h the one parallel to
/// it (normal to the hydraulic fracture), T0 the rock's tensile strength.
inline double renshaw_pollard_ratio(double friction_coefficient) {
  return (0.35 + 0.35 / friction_coefficient) / 1.06;
}
inline bool renshaw_pollard_crosses(double sigma_H_Pa, double sigma_h_Pa, double tensile_strength_Pa,
                                    double friction_coefficient) {
  return sigma_H_Pa / (tensile_strength_Pa + sigma_h_Pa) > renshaw_pollard_ratio(friction_coefficient);
}
/// The differential stress sigma_H - sigma_h above which Renshaw and Pollard predict crossing.
inline double renshaw_pollard_critical_differential_stress(double sigma_h_Pa, double tensile_strength_Pa,
                                                           double friction_coefficient) {
  return renshaw_pollard_ratio(friction_coefficient) * (tensile_strength_Pa + sigma_h_Pa) - sigma_h_Pa;
}

/// Warpinski and Teufel (1987): with fluid at pressure p in the natural fracture, it
/// opens when p > sigma_n. With p = sigma_h + net pressure, the natural fracture opens
/// for differential stresses below net / sin^2 theta (+infinity at theta = 0).
inline double warpinski_teufel_opening_differential_stress(double theta_rad, double net_pressure_Pa) {
  const double s = std::sin(theta_rad);
  return s == 0.0 ? std::numeric_limits<double>::infinity() : net_pressure_Pa / (s * s);
}

/// Warpinski and Teufel (1987): the natural fracture, closed (sigma_n > p), slips when
/// |tau| > c + mu (sigma_n - p), with p = sigma_h + net pressure the fluid pressure in it.
/// (With p >= sigma_n it opens instead: warpinski_teufel_opening_differential_stress.)
inline bool warpinski_teufel_slips(double theta_rad, double differential_stress_Pa, double sigma_h_Pa,
                                   double net_pressure_Pa, double friction_coefficient, double cohesion_Pa) {
  const PlaneStress on = stress_on_natural_fracture(theta_rad, sigma_h_Pa + differential_stress_Pa, sigma_h_Pa);
  const double effective_normal_Pa = on.normal_Pa - sigma_h_Pa - net_pressure_Pa;
  return effective_normal_Pa > 0.0 && std::abs(on.shear_Pa) > cohesion_Pa + friction_coefficient * effective_normal_Pa;
}

}  // namespace hfdda::analytical
