#pragma once
// Analytical criteria for a hydraulic fracture meeting a frictional natural fracture
// (docs/interaction_criteria.md restates them with their assumptions). Stresses are
// compression positive here, as in the sources, in Pa; the hydraulic fracture runs
// along sigma_H (its plane is normal to sigma_h) and meets the natural fracture at the
// approach angle theta (90 degrees: orthogonal).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

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

/// The Renshaw-Pollard construction at any approach angle, as Gu and Weng (2010) extended
/// it (docs/interaction_criteria.md). The hydraulic fracture's tip touches the interface;
/// its singular mode I field, of amplitude s = K_I / sqrt(2 pi r), is superposed on the
/// remote stresses. Along the interface (the two rays from the tip at polar angles theta
/// and theta - pi), the fracture re-initiates on the far side where the stress normal to
/// its plane reaches T0; this happens first (at the smallest s, i.e. the largest r) on
/// one of the two rays. It crosses if, at that r, the interface holds on both rays:
/// |tau| < c + mu sigma_n. At theta = 90 degrees this is Renshaw and Pollard's formula
/// with their coefficients unrounded (0.3536 for 0.35, 1.0607 for 1.06).
struct InterfaceLoad {
  double initiation_amplitude_Pa = std::numeric_limits<double>::infinity();  ///< s at re-initiation
  double slip_margin_Pa = 0.0;  ///< min over both rays of c + mu sigma_n - |tau| at that s (> 0: holds)
};
inline InterfaceLoad gu_weng_interface_load(double theta_rad, double sigma_H_Pa, double sigma_h_Pa,
                                            double tensile_strength_Pa, double friction_coefficient,
                                            double cohesion_Pa = 0.0) {
  // Crack along -x with its tip at the origin; x along sigma_H. Tension positive below.
  struct Field {
    double xx, yy, xy;
  };
  const auto tip_field = [](double phi) {  // Williams' mode I terms per unit s
    const double c = std::cos(phi / 2), s = std::sin(phi / 2), s3 = std::sin(1.5 * phi), c3 = std::cos(1.5 * phi);
    return Field{c * (1 - s * s3), c * (1 + s * s3), s * c * c3};
  };
  const double rays[2] = {theta_rad, theta_rad - std::numbers::pi};
  InterfaceLoad out;
  for (double phi : rays) {
    const double g = tip_field(phi).yy;  // the stress opening a continuation of the fracture
    if (g > 0.0) out.initiation_amplitude_Pa = std::min(out.initiation_amplitude_Pa, (tensile_strength_Pa + sigma_h_Pa) / g);
  }
  if (!std::isfinite(out.initiation_amplitude_Pa)) return out;
  const double nx = -std::sin(theta_rad), ny = std::cos(theta_rad);  // interface normal
  const double tx = std::cos(theta_rad), ty = std::sin(theta_rad);   // and direction
  out.slip_margin_Pa = std::numeric_limits<double>::infinity();
  for (double phi : rays) {
    const Field f = tip_field(phi);
    const double sxx = -sigma_H_Pa + out.initiation_amplitude_Pa * f.xx;
    const double syy = -sigma_h_Pa + out.initiation_amplitude_Pa * f.yy;
    const double sxy = out.initiation_amplitude_Pa * f.xy;
    const double normal = nx * nx * sxx + 2 * nx * ny * sxy + ny * ny * syy;  // tension positive
    const double shear = tx * nx * sxx + (tx * ny + ty * nx) * sxy + ty * ny * syy;
    out.slip_margin_Pa = std::min(out.slip_margin_Pa, cohesion_Pa - friction_coefficient * normal - std::abs(shear));
  }
  return out;
}
inline bool gu_weng_crosses(double theta_rad, double sigma_H_Pa, double sigma_h_Pa, double tensile_strength_Pa,
                            double friction_coefficient, double cohesion_Pa = 0.0) {
  const InterfaceLoad l = gu_weng_interface_load(theta_rad, sigma_H_Pa, sigma_h_Pa, tensile_strength_Pa,
                                                 friction_coefficient, cohesion_Pa);
  return std::isfinite(l.initiation_amplitude_Pa) && l.slip_margin_Pa > 0.0;
}
/// The smallest differential stress in [0, max] at which gu_weng_crosses holds, to
/// `resolution_Pa` (scan, then bisection); none if it never crosses there. Raising sigma_H
/// clamps the interface but also shears it at theta < 90 degrees, so the crossing range
/// is searched for rather than assumed to be a half-line.
inline std::optional<double> gu_weng_critical_differential_stress(double theta_rad, double sigma_h_Pa,
                                                                  double tensile_strength_Pa,
                                                                  double friction_coefficient,
                                                                  double max_differential_Pa,
                                                                  double resolution_Pa = 1e3) {
  const auto crosses = [&](double ds) {
    return gu_weng_crosses(theta_rad, sigma_h_Pa + ds, sigma_h_Pa, tensile_strength_Pa, friction_coefficient);
  };
  const int scan = 2000;
  double below = 0.0;
  if (crosses(0.0)) return 0.0;
  for (int k = 1; k <= scan; ++k) {
    const double ds = max_differential_Pa * k / scan;
    if (!crosses(ds)) {
      below = ds;
      continue;
    }
    double above = ds;
    while (above - below > resolution_Pa) {
      const double mid = 0.5 * (below + above);
      (crosses(mid) ? above : below) = mid;
    }
    return above;
  }
  return std::nullopt;
}

}  // namespace hfdda::analytical
