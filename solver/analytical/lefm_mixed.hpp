#pragma once
// A straight crack of half-length a on the x axis (|x| < a, y = 0), traction-free, in an
// infinite plane under a uniform far-field stress (sxx, syy, sxy), tension positive; SI
// units (m, Pa). Used by the mixed-mode LEFM case (seed 4.4, verification/lefm_mixed/).
//
// - Stress intensity factors K_I = syy sqrt(pi a), K_II = sxy sqrt(pi a) (seed eq. 4.27).
// - Failure stress of the G-criterion K_I^2 + K_II^2 = K_IC^2 with K_IC = T0 sqrt(pi L / 2)
//   (seed eqs. 4.13, 4.28) for the far field of a uniaxial tension s at angle beta to the
//   crack (seed eq. 4.26): s^2 = T0^2 L / (2 a cos^2 beta) (erratum 5), and the seed's
//   eq. 4.30 as printed, which has the extra factor 1 + 2 sin(beta) cos(beta) in the
//   denominator.
// - Kink angle of the maximum hoop stress criterion (Erdogan and Sih), measured from the
//   crack's direction ahead of the tip, counter-clockwise positive in the tip's axes
//   (x' ahead of the tip, y' = x' turned by +90 degrees; K_II > 0 for sx'y' > 0).
// - The exact (not only near-tip) stress field, from the Westergaard functions
//   Z = s z / sqrt(z^2 - a^2) of Mode I and Mode II plus the uniform sxx - syy that the
//   crack does not disturb, and the normal force on a straight joint leaving a tip: the
//   DDA's criterion at the scale of one joint (seed 4.2, eqs. 4.8-4.12) with the whole
//   field instead of its singular term, so that a -> 0 gives the uniform stress.

#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

namespace hfdda::analytical {

/// Far-field stress per unit magnitude (sxx, syy, sxy) of a uniaxial tension at angle
/// beta [rad] to the crack, in the crack's axes (seed eq. 4.26).
struct StressPattern {
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
};
inline StressPattern inclined_tension(double beta_rad) {
  const double s = std::sin(beta_rad), c = std::cos(beta_rad);
  return {s * s, c * c, s * c};
}

/// Corrected mixed-mode failure stress [Pa] (erratum 5): s = T0 sqrt(L / (2 a cos^2 beta)).
inline double mixed_mode_failure_stress_g(double tensile_strength_Pa, double joint_length_m, double half_length_m,
                                          double beta_rad) {
  const double c = std::cos(beta_rad);
  return tensile_strength_Pa * std::sqrt(joint_length_m / (2.0 * half_length_m * c * c));
}

/// The seed's eq. 4.30 as printed: s^2 = T0^2 L / (2 a cos^2 beta (1 + 2 sin beta cos beta)).
inline double mixed_mode_failure_stress_eq430(double tensile_strength_Pa, double joint_length_m,
                                              double half_length_m, double beta_rad) {
  const double s = std::sin(beta_rad), c = std::cos(beta_rad);
  return tensile_strength_Pa * std::sqrt(joint_length_m / (2.0 * half_length_m * c * c * (1.0 + 2.0 * s * c)));
}

/// Kink angle [rad] of the maximum hoop stress criterion:
/// theta = 2 atan[(K_I - sqrt(K_I^2 + 8 K_II^2)) / (4 K_II)] (0 when K_II = 0).
inline double max_hoop_stress_kink_angle(double k_i, double k_ii) {
  if (k_ii == 0.0) return 0.0;
  return 2.0 * std::atan((k_i - std::sqrt(k_i * k_i + 8.0 * k_ii * k_ii)) / (4.0 * k_ii));
}

/// Hoop stress near a tip, sigma_theta_theta sqrt(2 pi r), at angle theta [rad].
inline double hoop_stress_factor(double k_i, double k_ii, double theta_rad) {
  const double h = std::cos(0.5 * theta_rad);
  return h * (k_i * h * h - 1.5 * k_ii * std::sin(theta_rad));
}

struct Stress {
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
};

/// Exact stress [per unit of the far-field pattern] at (x, y) off the crack line segment
/// |x| <= a, y = 0 (a = 0: the uniform far field).
inline Stress crack_stress(double x_m, double y_m, double half_length_m, const StressPattern& far) {
  if (half_length_m <= 0.0) return {far.sxx, far.syy, far.sxy};
  using C = std::complex<double>;
  const C z(x_m, y_m);
  const double a = half_length_m;
  const C root = std::sqrt(z - a) * std::sqrt(z + a);  // branch cut on [-a, a] only
  const C f = z / root;                                // Z / s
  const C fp = -a * a / (root * root * root);          // Z' / s
  const double y = y_m;
  Stress s;
  // Mode I, Z = syy f: sxx = Re Z - y Im Z', syy = Re Z + y Im Z', sxy = -y Re Z'.
  s.sxx = far.syy * (f.real() - y * fp.imag());
  s.syy = far.syy * (f.real() + y * fp.imag());
  s.sxy = far.syy * (-y * fp.real());
  // Mode II, Z = sxy f: sxx = 2 Im Z + y Re Z', syy = -y Re Z', sxy = Re Z - y Im Z'.
  s.sxx += far.sxy * (2.0 * f.imag() + y * fp.real());
  s.syy += far.sxy * (-y * fp.real());
  s.sxy += far.sxy * (f.real() - y * fp.imag());
  // Mode I carries sxx = syy far away; the rest of sxx is uniform and undisturbed.
  s.sxx += far.sxx - far.syy;
  return s;
}

/// Normal force [N/m per unit of the far-field pattern] on the straight joint from the tip
/// (a, 0) at angle theta [rad] (counter-clockwise from +x) and of length L: the integral
/// of n . sigma . n over the joint, with s = u^2 removing the 1 / sqrt(s) singularity at
/// the tip (Gauss-Legendre, 48 points). By symmetry the same at the tip (-a, 0) for the
/// joint turned by 180 degrees.
inline double joint_normal_force(double half_length_m, const StressPattern& far, double theta_rad,
                                 double joint_length_m) {
  // Nodes and weights of the 48-point Gauss-Legendre rule on [-1, 1], computed once.
  constexpr int n = 48;
  static const auto rule = [] {
    std::array<std::array<double, 2>, n> r{};
    for (int i = 0; i < n; ++i) {  // Newton on P_n from the Chebyshev guess
      double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = x;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (x * p1 - p0) / (x * x - 1.0);
        const double dx = p1 / dp;
        x -= dx;
        if (std::abs(dx) < 1e-15) break;
      }
      r[i] = {x, 2.0 / ((1.0 - x * x) * dp * dp)};
    }
    return r;
  }();
  const double tx = std::cos(theta_rad), ty = std::sin(theta_rad);
  const double nx = -ty, ny = tx;
  const double v_max = std::sqrt(joint_length_m);
  double force = 0.0;
  for (const auto& [xi, w] : rule) {
    const double v = 0.5 * (xi + 1.0) * v_max;
    const double s = v * v;
    const Stress st = crack_stress(half_length_m + s * tx, s * ty, half_length_m, far);
    const double normal = nx * nx * st.sxx + ny * ny * st.syy + 2.0 * nx * ny * st.sxy;
    force += w * 0.5 * v_max * 2.0 * v * normal;
  }
  return force;
}

/// Far-field magnitude [Pa] at which the normal force on that joint reaches T0 L (the
/// whole joint's strength, seed eq. 4.12); infinite if the joint is not pulled.
inline double joint_failure_stress(double tensile_strength_Pa, double half_length_m, const StressPattern& far,
                                   double theta_rad, double joint_length_m) {
  const double f = joint_normal_force(half_length_m, far, theta_rad, joint_length_m);
  return f > 0.0 ? tensile_strength_Pa * joint_length_m / f : std::numeric_limits<double>::infinity();
}

}  // namespace hfdda::analytical
