// KGD viscosity-storage (M-vertex) reference solution, analytical/kgd.hpp: the two
// published forms of the inlet width and pressure agree, the growth laws hold, and one
// value computed by hand (seed 3.2 parameters) is reproduced.

#include <gtest/gtest.h>

#include <cmath>

#include "analytical/kgd.hpp"

namespace hfdda::analytical {
namespace {

// Seed section 3.2 / Table 3.1: E = 25 GPa, nu = 0.25, mu = 1 mPa s, Q0 = 4 kg/s / 1000 kg/m^3.
constexpr double kE = 25.0e9, kNu = 0.25, kMu = 1.0e-3, kQ0 = 4.0e-3;

KgdViscositySolution at(double t) { return kgd_viscosity_storage(kE, kNu, kMu, kQ0, t); }

TEST(AnalyticalKgd, HandComputedValuesAtTenSeconds) {
  // By hand: E' = 25e9 / 0.9375 = 26.667 GPa, mu' = 0.012 Pa s,
  // psi = (26.667e9 * 6.4e-8 / 0.012)^(1/6) * 10^(2/3) = 7.2249 * 4.6416 = 33.535 m,
  // l = 0.61524 * 33.535 = 20.632 m; zeta = (0.012 / 2.6667e11)^(1/3) = 3.5569e-5;
  // w0 = sqrt(2.1 * sqrt(1.8e-15) * 20.632) = 1.3558 mm; p0 = 0.62 * sqrt(1.28e6) / w0 = 0.51737 MPa.
  const KgdViscositySolution s = at(10.0);
  EXPECT_NEAR(s.plane_strain_modulus_Pa, 26.6667e9, 1e5);
  EXPECT_DOUBLE_EQ(s.scaled_viscosity_Pa_s, 0.012);
  EXPECT_NEAR(s.zeta, 3.5569e-5, 1e-9);
  EXPECT_NEAR(s.psi_m, 33.535, 1e-3);
  EXPECT_NEAR(s.half_length_m, 20.632, 1e-3);
  EXPECT_NEAR(s.inlet_width_m, 1.3558e-3, 1e-7);
  EXPECT_NEAR(s.inlet_net_pressure_Pa, 0.51737e6, 10.0);
  EXPECT_NEAR(s.inlet_width_seed_form_m, 1.3431e-3, 1e-7);
  EXPECT_NEAR(s.inlet_net_pressure_seed_form_Pa, 0.51689e6, 10.0);
}

TEST(AnalyticalKgd, SeedFormAndClosedFormsAgree) {
  // w0: 2.1 against Gamma Omega0^2 = 2.0608, i.e. sqrt(2.1 / 2.0608) - 1 = +0.946 % at every t;
  // p0: (0.62 / (Gamma Omega0 Phi0)) / 1.00946 - 1 = +0.093 %.
  const double width_ratio = std::sqrt(kKgdMWidthSquaredCoefficient / (kKgdMGamma * kKgdMOmega0 * kKgdMOmega0));
  const double pressure_ratio =
      kKgdMWidthPressureCoefficient / (kKgdMGamma * kKgdMOmega0 * kKgdMPhi0) / width_ratio;
  EXPECT_NEAR(width_ratio - 1.0, 0.00946, 5e-5);
  EXPECT_NEAR(pressure_ratio - 1.0, 0.00093, 5e-5);
  for (double t : {0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 100.0}) {
    const KgdViscositySolution s = at(t);
    EXPECT_NEAR(s.inlet_width_m / s.inlet_width_seed_form_m, width_ratio, 1e-12) << "t = " << t;
    EXPECT_NEAR(s.inlet_net_pressure_Pa / s.inlet_net_pressure_seed_form_Pa, pressure_ratio, 1e-12) << "t = " << t;
    // The brief's tolerance: the two forms within 1 % (w0) and 0.1 % (p0).
    EXPECT_LT(std::abs(s.inlet_width_m / s.inlet_width_seed_form_m - 1.0), 0.01);
    EXPECT_LT(std::abs(s.inlet_net_pressure_Pa / s.inlet_net_pressure_seed_form_Pa - 1.0), 0.001);
  }
}

TEST(AnalyticalKgd, GrowthLaws) {
  const KgdViscositySolution a = at(1.0), b = at(8.0);  // factor 8: 8^(1/3) = 2 exactly
  EXPECT_NEAR(b.half_length_m / a.half_length_m, 4.0, 1e-12);          // l ~ t^(2/3)
  EXPECT_NEAR(b.inlet_width_m / a.inlet_width_m, 2.0, 1e-12);          // w0 ~ t^(1/3)
  EXPECT_NEAR(b.inlet_net_pressure_Pa / a.inlet_net_pressure_Pa, 0.5, 1e-12);  // p0 ~ t^(-1/3)
  EXPECT_NEAR(b.inlet_width_seed_form_m / a.inlet_width_seed_form_m, 2.0, 1e-12);
  EXPECT_NEAR(b.inlet_net_pressure_seed_form_Pa / a.inlet_net_pressure_seed_form_Pa, 0.5, 1e-12);
}

TEST(AnalyticalKgd, VolumeBalanceGivesAPlausibleProfile) {
  // No leak-off, incompressible fluid: the fracture volume 2 l w0 c equals Q0 t, where c is
  // the mean opening over the inlet opening. Self-similarity makes c time independent, and
  // the M-vertex profile (w ~ (1 - xi)^(2/3) at the tip) lies between a triangle (c = 1/2)
  // and an ellipse (c = pi/4). Here c = 0.715.
  const KgdViscositySolution a = at(0.5), b = at(10.0);
  const double ca = kQ0 * 0.5 / (2.0 * a.half_length_m * a.inlet_width_m);
  const double cb = kQ0 * 10.0 / (2.0 * b.half_length_m * b.inlet_width_m);
  EXPECT_NEAR(ca, cb, 1e-12 * cb);
  EXPECT_GT(cb, 0.5);
  EXPECT_LT(cb, std::acos(-1.0) / 4.0);
}

}  // namespace
}  // namespace hfdda::analytical
