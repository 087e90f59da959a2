// The fracture-network flow model (seed 2.1) on its own: apertures given directly as
// an affine model of the pressures, checked against closed-form storage, flow and
// leak-off balances.

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "fluid/flow_network.hpp"

namespace {

using hfdda::fluid::FlowNetwork;
using hfdda::fluid::FluidProperties;
using hfdda::fluid::FlowSettings;
using hfdda::fluid::Fracture;

FluidProperties water() {
  FluidProperties f;
  f.density_kg_m3 = 1000.0;
  f.bulk_modulus_Pa = 2.2e9;
  f.viscosity_Pa_s = 1.0e-3;
  return f;
}

/// A chain of `n` fractures of length `length` along points 0..n.
FlowNetwork chain(int n, double length, FluidProperties fluid = water(), FlowSettings settings = {}) {
  std::vector<Fracture> fractures;
  for (int k = 0; k < n; ++k) fractures.push_back({k, k + 1, length});
  return FlowNetwork(n + 1, fractures, fluid, settings);
}

/// Rigid walls: every wetted end keeps aperture `w` whatever the pressure.
void solve_rigid(FlowNetwork& net, double w) {
  const int ends = 2 * static_cast<int>(net.trial_fractures().size());
  const int nodes = static_cast<int>(net.trial_nodes().size());
  net.solve(Eigen::VectorXd::Constant(ends, w), Eigen::MatrixXd::Zero(ends, nodes));
}

TEST(FlowNetwork, CompressibleStorageOfRigidFracture) {
  // One 1 m fracture, 1 mm open, full at p = 0; inject 1e-3 kg over 1 s. At
  // equilibrium both nodes share p with rho(p) V = rho0 V + injected.
  FlowNetwork net = chain(1, 1.0);
  net.fill_initially(0, 1e-3);
  net.add_injection({0, 1e-3, 0.0});
  net.begin_step(1.0);
  solve_rigid(net, 1e-3);
  net.commit();
  const double volume = 1e-3;  // 1 m x 1 mm
  // Implicit flow between the nodes does not equalise them completely in one step,
  // but the mean pressure is fixed by the total mass (eq. 2.6 is linear in p).
  const double mean_p = 0.5 * (net.pressure(0) + net.pressure(1));
  const double expected = 2.2e9 * (1e-3 / (1000.0 * volume));
  EXPECT_NEAR(mean_p, expected, 1e-9 * expected);
  EXPECT_GT(net.pressure(0), net.pressure(1));  // fluid flows away from the inlet
  EXPECT_LT(net.mass_balance_error(), 1e-14);
}

TEST(FlowNetwork, ImplicitFlowBetweenTwoNodesMatchesClosedForm) {
  // Two nodes, incompressible-limit check with a stiff fluid: the inflow over the step
  // equals dt * eta * (p0 - p1) with eta from the cubic law (eq. 2.2).
  FlowNetwork net = chain(1, 2.0);
  net.fill_initially(0, 1e-4);
  net.add_injection({0, 1e-4, 0.0});
  net.begin_step(0.5);
  solve_rigid(net, 1e-4);
  net.commit();
  const double p0 = net.pressure(0), p1 = net.pressure(1);
  const double rho = 0.5 * (water().density(p0) + water().density(p1));
  const double eta = rho * 1e-12 / (12.0 * 1e-3 * 2.0);
  // Node 1 received exactly what flowed through the fracture.
  const double received = water().density(p1) * 1e-4 - 1000.0 * 1e-4;
  EXPECT_NEAR(received, 0.5 * eta * (p0 - p1), 1e-9 * received);
}

TEST(FlowNetwork, CarterLeakOffIsChargedOverBothWalls) {
  // Rigid fracture wetted from t = 0: leaked volume per node over [0, t] is
  // C_L L 2 sqrt(t) (both walls, half the fracture per node), two nodes.
  FluidProperties fluid = water();
  fluid.leak_off_coefficient_m_sqrt_s = 2e-5;
  FlowNetwork net = chain(1, 1.0, fluid);
  net.fill_initially(0, 1e-3);
  net.add_injection({0, 0.05, 0.0});
  for (int step = 0; step < 4; ++step) {
    net.begin_step(0.25);
    solve_rigid(net, 1e-3);
    net.commit();
  }
  const double leaked_volume = 2.0 * 2e-5 * 1.0 * 2.0 * std::sqrt(1.0);
  // The leak is charged at each node's density, within 1e-4 of rho0 here.
  EXPECT_NEAR(net.leaked_mass(), 1000.0 * leaked_volume, 2e-3 * 1000.0 * leaked_volume);
  EXPECT_LT(net.mass_balance_error(), 1e-13);
}

TEST(FlowNetwork, NegativePressureBecomesZeroPressureNodeAndMassIsKept) {
  // The far node's aperture grows with its own pressure... and also opens by itself
  // (base aperture larger than the fluid it holds): it must not go below p = 0.
  FlowNetwork net = chain(2, 1.0);
  net.fill_initially(0, 1e-4);
  net.fill_initially(1, 1e-4);
  net.add_injection({0, 1e-6, 0.0});
  net.begin_step(1.0);
  // Ends: (f0,p0) (f0,p1) (f1,p1) (f1,p2); the end at point 2 opens to 1 mm.
  Eigen::VectorXd base(4);
  base << 1e-4, 1e-4, 1e-4, 1e-3;
  const Eigen::MatrixXd s = Eigen::MatrixXd::Zero(4, 3);
  const auto stats = net.solve(base, s);
  net.commit();
  EXPECT_GE(stats.zero_pressure_nodes, 1);
  EXPECT_TRUE(net.zero_pressure(2));
  EXPECT_EQ(net.pressure(2), 0.0);
  for (int p = 0; p < 3; ++p) EXPECT_GE(net.pressure(p), 0.0);
  EXPECT_LT(net.mass_balance_error(), 1e-13);
}

TEST(FlowNetwork, ElasticWallsScalarRootMatches) {
  // One fracture, both ends open as w = w0 + c p, both nodes injected equally: by
  // symmetry p solves rho(p) L (w0 + c p) = M0 + I exactly.
  FlowNetwork net = chain(1, 1.0);
  net.fill_initially(0, 1e-5);
  net.add_injection({0, 1e-3, 0.0});
  net.add_injection({1, 1e-3, 0.0});
  net.begin_step(1.0);
  const double c = 1e-11;  // m/Pa
  Eigen::MatrixXd s(2, 2);
  s << c, 0, 0, c;
  net.solve(Eigen::VectorXd::Constant(2, 1e-5), s);
  net.commit();
  const double p = net.pressure(0);
  const double mass = 1000.0 * 1e-5 + 2e-3;
  EXPECT_NEAR(water().density(p) * (1e-5 + c * p), mass, 1e-12 * mass);
  EXPECT_NEAR(net.pressure(1), p, 1e-9 * p);
  EXPECT_NEAR(net.aperture(0, 0), 1e-5 + c * p, 1e-12);
}

TEST(FlowNetwork, AperturesCloseAtMostFivePercentPerStep) {
  FlowNetwork net = chain(1, 1.0);
  net.fill_initially(0, 1e-3);
  net.add_injection({0, 1e-9, 0.0});
  net.begin_step(1.0);
  solve_rigid(net, 1e-6);  // the mechanics would close it to 1 um
  net.commit();
  EXPECT_NEAR(net.aperture(0, 0), 0.95e-3, 1e-15);
  EXPECT_NEAR(net.aperture(0, 1), 0.95e-3, 1e-15);
}

TEST(FlowNetwork, MinimumWidthsAtTipsAndInside) {
  // Chain of two fractures: point 1 joins two wetted fractures (0.5 um), points 0 and
  // 2 are tips (0.1 um). The mechanics closes everything.
  FlowNetwork net = chain(2, 1.0);
  net.fill_initially(0, 0.0);
  net.fill_initially(1, 0.0);
  net.add_injection({1, 1e-9, 0.0});
  for (int step = 0; step < 200; ++step) {  // 0.95^200 ~ 3.5e-5: the floors take over
    net.begin_step(1.0);
    solve_rigid(net, -1e-3);
    net.commit();
  }
  EXPECT_NEAR(net.aperture(0, 0), 0.1e-6, 1e-18);
  EXPECT_NEAR(net.aperture(0, 1), 0.5e-6, 1e-18);
  EXPECT_NEAR(net.aperture(1, 1), 0.1e-6, 1e-18);
  EXPECT_LT(net.mass_balance_error(), 1e-12);
}

TEST(FlowNetwork, InjectionOutsideTheNetworkIsAnError) {
  FlowNetwork net = chain(2, 1.0);
  net.fill_initially(0, 1e-4);
  net.add_injection({2, 1.0, 0.0});
  EXPECT_THROW(net.begin_step(1.0), hfdda::ModelError);
}

TEST(FlowNetwork, WettingAddsNodesAndStartsArrivalClock) {
  FlowNetwork net = chain(2, 1.0);
  net.fill_initially(0, 1e-4);
  net.add_injection({0, 1e-3, 0.0});
  net.begin_step(1.0);
  EXPECT_EQ(net.trial_nodes().size(), 2u);
  EXPECT_TRUE(net.wet(1));
  EXPECT_FALSE(net.wet(1));
  EXPECT_EQ(net.trial_nodes().size(), 3u);
  solve_rigid(net, 1e-4);
  net.commit();
  EXPECT_TRUE(net.wetted(1));
  // The new fracture holds far more than the 1 g injected: its far node partly fills
  // at zero pressure (seed Figure 2.2).
  EXPECT_TRUE(net.zero_pressure(2));
  EXPECT_EQ(net.pressure(2), 0.0);
  EXPECT_LT(net.mass_balance_error(), 1e-13);
}

}  // namespace
