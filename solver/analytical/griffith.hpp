#pragma once
// Griffith (Sneddon) crack opened by a uniform net pressure in an infinite plane-strain
// medium: seed eq. 3.1,
//   w(x) = 4 (1 - nu^2) (p_f - sigma_0) L / E * sqrt(1 - x^2 / L^2),  |x| <= L,
// with L the half-length, p_f the fluid pressure and sigma_0 the compressive
// background stress normal to the crack (both positive in compression).

#include <cmath>

namespace hfdda::analytical {

/// Opening width [m] at distance x [m] from the crack centre; 0 beyond the tips.
inline double griffith_width(double x_m, double half_length_m, double net_pressure_Pa, double youngs_modulus_Pa,
                             double poissons_ratio) {
  const double r = x_m / half_length_m;
  if (std::abs(r) >= 1.0) return 0.0;
  return 4.0 * (1.0 - poissons_ratio * poissons_ratio) * net_pressure_Pa * half_length_m / youngs_modulus_Pa *
         std::sqrt(1.0 - r * r);
}

}  // namespace hfdda::analytical
