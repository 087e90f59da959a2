#include "analytical/kgd_transition.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "analytical/kgd.hpp"

namespace hfdda::analytical {

namespace {

/// Root of a function increasing through zero in l, bracketed by widening [lo, hi].
double increasing_root(const std::function<double(double)>& f, double guess) {
  double lo = 0.5 * guess, hi = 2.0 * guess;
  for (int k = 0; k < 60 && f(lo) > 0.0; ++k) lo *= 0.5;
  for (int k = 0; k < 60 && f(hi) < 0.0; ++k) hi *= 2.0;
  if (f(lo) > 0.0 || f(hi) < 0.0) throw std::runtime_error("kgd_toughness_viscosity: no half-length meets the volume");
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

KgdTransitionSolution kgd_toughness_viscosity(double youngs_modulus_Pa, double poissons_ratio,
                                              double fracture_toughness_Pa_sqrt_m, double viscosity_Pa_s,
                                              double total_rate_m2_s, double time_s,
                                              const KgdTransitionSettings& settings) {
  const double K = fracture_toughness_Pa_sqrt_m, Q0 = total_rate_m2_s, t = time_s;
  if (!(youngs_modulus_Pa > 0.0) || !(poissons_ratio > -1.0 && poissons_ratio < 0.5) || !(K >= 0.0) ||
      !(viscosity_Pa_s >= 0.0) || !(K > 0.0 || viscosity_Pa_s > 0.0) || !(Q0 > 0.0) || !(t > 0.0) ||
      settings.quadrature_points < 10 * settings.modes || settings.modes < 1)
    throw std::invalid_argument("kgd_toughness_viscosity: needs E > 0, -1 < nu < 0.5, K_IC >= 0, mu >= 0 (not both 0), "
                                "Q0 > 0, t > 0, and at least 10 quadrature points per mode");
  const double pi = std::acos(-1.0);
  const double Ep = plane_strain_modulus(youngs_modulus_Pa, poissons_ratio), mup = 12.0 * viscosity_Pa_s;
  const int N = settings.quadrature_points, M = settings.modes;
  const double dth = 0.5 * pi / N;

  // Midpoints in theta (x = l cos(theta): theta = 0 at the tip, pi/2 at the inlet); per mode
  // n its sine sin((2n+1) theta) and the integral from the tip, int_0^theta sin((2n+1) s) sin(s) ds,
  // which is int_x^l w dx' / l for the opening's modes.
  Eigen::ArrayXd theta(N);
  for (int j = 0; j < N; ++j) theta[j] = (j + 0.5) * dth;
  const Eigen::ArrayXd sin_theta = theta.sin(), x_over_l = theta.cos();
  Eigen::MatrixXd mode(M + 1, N), from_tip(M + 1, N);
  for (int n = 0; n <= M; ++n)
    for (int j = 0; j < N; ++j) {
      const double s = theta[j];
      mode(n, j) = std::sin((2 * n + 1) * s);
      from_tip(n, j) = n == 0 ? 0.5 * (s - 0.5 * std::sin(2 * s))
                              : 0.5 * (std::sin(2 * n * s) / (2 * n) - std::sin((2 * n + 2) * s) / (2 * n + 2));
    }

  // Start from the vertex nearer the solution: the K-vertex (uniform pressure) with a
  // toughness, else the M-vertex's length with an opening ~ (l^2 - x^2)^(2/3).
  double l = 0.0;
  Eigen::VectorXd c = Eigen::VectorXd::Zero(M + 1);
  if (K > 0.0) {
    l = 2.0 / std::cbrt(pi * pi) * std::pow(Ep * Q0 * t / scaled_toughness(K), 2.0 / 3.0);
    c[0] = 4.0 * l * (K / std::sqrt(pi * l)) / Ep;
  } else {
    l = kKgdMGamma * std::pow(Ep * Q0 * Q0 * Q0 / mup, 1.0 / 6.0) * std::pow(t, 2.0 / 3.0);
    const Eigen::VectorXd shape = sin_theta.pow(4.0 / 3.0).matrix();
    c = (4.0 / pi) * dth * (mode * shape);
    c *= (2.0 * Q0 * t / (pi * l)) / c[0];  // volume pi l c_0 / 2 = Q0 t
  }

  KgdTransitionSolution out;
  out.time_s = t;
  out.dimensionless_toughness = kgd_dimensionless_toughness(youngs_modulus_Pa, poissons_ratio, K, viscosity_Pa_s, Q0);
  const Eigen::ArrayXd odd = Eigen::ArrayXd::LinSpaced(M + 1, 1.0, 2.0 * M + 1.0);  // 2n + 1
  double inlet_pressure = 0.0, mean_pressure = 0.0;
  for (int it = 1; it <= settings.max_iterations; ++it) {
    const Eigen::ArrayXd w = (mode.transpose() * c).array().max(1e-12 * c[0]);
    const Eigen::ArrayXd beyond = (from_tip.transpose() * c).array();
    // dp/d(x/l) from the lubrication equation, divided by l^2 (the root below chooses l);
    // its integral from the inlet (theta = pi/2) towards the tip is the pressure drop,
    // which goes to -infinity as log(theta).
    const Eigen::ArrayXd dp_dxi = -mup * (3.0 * beyond + 2.0 * x_over_l * w) / (3.0 * t * w * w * w);
    const Eigen::ArrayXd rate = dp_dxi * sin_theta * dth;  // d(drop)/d(theta) dtheta, per l^2
    Eigen::ArrayXd drop(N);
    double sum = 0.0;
    for (int j = N - 1; j >= 0; --j) {
      drop[j] = sum + 0.5 * rate[j];
      sum += rate[j];
    }
    // The drop's sine modes (per l^2), and what the toughness sees of it:
    // K_I / sqrt(pi l) = (2 / pi) int_0^{pi/2} p dtheta.
    const Eigen::VectorXd drop_modes = (4.0 / pi) * dth * (mode * (drop * sin_theta).matrix());
    const double drop_toughness = (2.0 / pi) * dth * drop.sum(), drop_volume = drop_modes[0];
    auto inlet_at = [&](double L) { return K / std::sqrt(pi * L) - L * L * drop_toughness; };
    // Volume pi l c_0 / 2 with c_0 = 4 l P_0 / E', P_0 = inlet + l^2 drop_volume.
    const double l_new = increasing_root(
        [&](double L) { return 2.0 * pi * L * L / Ep * (inlet_at(L) + L * L * drop_volume) - Q0 * t; }, l);
    inlet_pressure = inlet_at(l_new);
    mean_pressure = inlet_pressure + l_new * l_new * (drop * sin_theta).sum() * dth;  // int_0^1 p d(x / l)
    Eigen::VectorXd c_new = (4.0 * l_new * l_new * l_new / Ep) * drop_modes;
    c_new[0] += 4.0 * l_new * inlet_pressure / Ep;
    c_new.array() /= odd;
    const double change = std::abs(l_new - l) / l + (c_new - c).cwiseAbs().maxCoeff() / std::abs(c[0]);
    const double r = settings.relaxation;
    c = r * c_new + (1.0 - r) * c;
    l = r * l_new + (1.0 - r) * l;
    out.iterations = it;
    if (change < settings.tolerance) {
      out.converged = true;
      break;
    }
  }
  if (!out.converged)
    throw std::runtime_error("kgd_toughness_viscosity: the fixed point did not converge in " +
                             std::to_string(settings.max_iterations) + " iterations");
  Eigen::ArrayXd alternating(M + 1);
  for (int n = 0; n <= M; ++n) alternating[n] = n % 2 == 0 ? 1.0 : -1.0;
  out.half_length_m = l;
  out.inlet_width_m = (c.array() * alternating).sum();  // theta = pi/2: sin((2n+1) pi/2) = (-1)^n
  out.inlet_net_pressure_Pa = inlet_pressure;
  out.mean_net_pressure_Pa = mean_pressure;
  return out;
}

KgdTransitionSolution scaled_to(const KgdTransitionSolution& s, double time_s) {
  if (!(time_s > 0.0) || !(s.time_s > 0.0)) throw std::invalid_argument("scaled_to: times must be > 0");
  const double r = time_s / s.time_s;
  KgdTransitionSolution out = s;
  out.time_s = time_s;
  out.half_length_m *= std::pow(r, 2.0 / 3.0);
  out.inlet_width_m *= std::cbrt(r);
  out.inlet_net_pressure_Pa /= std::cbrt(r);
  out.mean_net_pressure_Pa /= std::cbrt(r);
  return out;
}

}  // namespace hfdda::analytical
