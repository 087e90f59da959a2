#pragma once
// KGD (plane-strain, bi-wing) hydraulic fracture with both a fracture toughness and a
// viscous fluid: the edge between the M-vertex (K_IC = 0) and the K-vertex (mu = 0) of
// Detournay's parametric space, no leak-off, no fluid lag, constant total injection rate
// (Detournay 2004, Int. J. Geomech. 4(1); Garagash & Detournay 2005). Computed, not in
// closed form: the inputs and units are those of kgd.hpp (E, nu, K_IC [Pa m^0.5],
// mu [Pa s], Q0 the total rate into both wings [m^2/s], t since injection [s]).
//
// The solution is self-similar (l ~ t^(2/3), w ~ t^(1/3), p ~ t^(-1/3)) and depends on the
// dimensionless toughness K_m alone (kgd_dimensionless_toughness). At one time t it solves,
// for the half-length l and the opening w(x) (x = l cos(theta), 0 <= theta <= pi/2):
//   elasticity   w = sum_n c_n sin((2n+1) theta),  p = (E' / 4 l) sum_n (2n+1) c_n
//                sin((2n+1) theta) / sin(theta)  (the Chebyshev pairs sqrt(1 - x^2) U_2n(x)
//                and (2n+1) U_2n(x) of a crack's finite Hilbert transform);
//   lubrication  dp/dx = -mu' q / w^3 with the flux of the self-similar opening,
//                q(x) = (l / 3t) [3 int_x^l w dx' / l + 2 (x / l) w(x)], mu' = 12 mu;
//   toughness    K_I = 2 sqrt(l / pi) int_0^l p / sqrt(l^2 - x^2) dx = K_IC;
//   volume       int_{-l}^{l} w dx = Q0 t.
// A fixed point: the pressure drop along the fracture from the current opening, then the
// inlet pressure and l that meet the toughness and the volume (a root in l), then the
// opening of that pressure, relaxed. The toughness is taken as the integral of the
// pressure on the quadrature grid, not as the truncated sum of the series, whose tail
// converges slowly where K_IC is small. Checked against both vertices
// (tests/test_analytical_kgd.cpp): mu -> 0 gives the K-vertex, K_IC = 0 the M-vertex's
// published constants, each within 1e-3.

namespace hfdda::analytical {

/// Discretisation of kgd_toughness_viscosity: quadrature points on 0 < theta < pi/2
/// and the number of sine modes (the modes must stay well resolved by the points).
struct KgdTransitionSettings {
  int quadrature_points = 4000;
  int modes = 400;
  double relaxation = 0.5;          ///< of l and the opening between fixed-point iterations
  int max_iterations = 500;
  double tolerance = 1e-10;         ///< relative change of l and of the opening's modes
};

/// KGD state at one time with toughness and viscosity; SI units.
struct KgdTransitionSolution {
  double time_s = 0.0;
  double dimensionless_toughness = 0.0;  ///< K_m = K' / (E'^3 mu' Q0)^(1/4) (kgd.hpp)
  double half_length_m = 0.0;
  double inlet_width_m = 0.0;
  double inlet_net_pressure_Pa = 0.0;
  double mean_net_pressure_Pa = 0.0;     ///< mean over the fracture's length (below the inlet's)
  int iterations = 0;
  bool converged = false;
};

/// The toughness-and-viscosity KGD fracture at time t > 0. K_IC >= 0 and mu >= 0, not both
/// zero; throws std::invalid_argument otherwise, and std::runtime_error if the fixed point
/// does not converge.
KgdTransitionSolution kgd_toughness_viscosity(double youngs_modulus_Pa, double poissons_ratio,
                                              double fracture_toughness_Pa_sqrt_m, double viscosity_Pa_s,
                                              double total_rate_m2_s, double time_s,
                                              const KgdTransitionSettings& settings = {});

/// The same solution at another time, by its self-similarity (l ~ t^(2/3), w ~ t^(1/3),
/// p ~ t^(-1/3)), without solving again.
KgdTransitionSolution scaled_to(const KgdTransitionSolution& solution, double time_s);

}  // namespace hfdda::analytical
