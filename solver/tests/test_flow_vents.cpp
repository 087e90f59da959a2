// Vents of the flow network: nodes where the network meets a free edge of the rock,
// held at zero pressure, passing on what they cannot hold (docs/design_notes.md
// section 27). Apertures given directly (rigid walls), checked against the steady
// Poiseuille flow of a chain and against the mass ledger.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "flow_test_support.hpp"
#include "fluid/flow_network.hpp"

namespace {

using hfdda::fluid::FlowNetwork;
using hfdda::fluid::FlowSettings;
using hfdda::fluid::FluidProperties;
using hfdda::fluid::Fracture;
using hfdda::fluid::testing::solve_rigid;
using hfdda::fluid::testing::water;

/// Points 0 - 1 - 2 joined by two fractures of 1 m; a vent at point 2.
FlowNetwork vented_chain() {
  FlowNetwork net(3, {Fracture{0, 1, 1.0}, Fracture{1, 2, 1.0}}, water(), FlowSettings{});
  net.set_vents({0, 0, 1});
  return net;
}

TEST(FlowVents, SteadyChainVentsWhatIsInjectedAtZeroOutletPressure) {
  // Rigid fractures 100 um open, 1 g/s injected at point 0. Once the stored mass stops
  // changing, all of it leaves through the vent: each fracture carries q = eta dp with
  // eta from the cubic law (eq. 2.2) at the mean density of its ends, the vent at p = 0.
  const double w = 1e-4, q = 1e-3, dt = 1.0;
  FlowNetwork net = vented_chain();
  net.fill_initially(0, w);
  net.fill_initially(1, w);
  net.add_injection({0, q, 0.0});
  double vented_before = 0.0;
  for (int step = 0; step < 30; ++step) {
    vented_before = net.vented_mass();
    net.begin_step(dt);
    solve_rigid(net, w);
    net.commit();
  }
  const double p0 = net.pressure(0), p1 = net.pressure(1);
  EXPECT_EQ(net.pressure(2), 0.0);
  EXPECT_GT(p1, 0.0);
  const FluidProperties f = water();
  auto eta = [&](double pa, double pb) { return 0.5 * (f.density(pa) + f.density(pb)) * w * w * w / (12.0e-3 * 1.0); };
  EXPECT_NEAR(eta(p1, 0.0) * p1, q, 1e-6 * q);
  EXPECT_NEAR(eta(p0, p1) * (p0 - p1), q, 1e-6 * q);
  EXPECT_NEAR(net.vented_mass() - vented_before, q * dt, 1e-6 * q * dt);
  EXPECT_LT(net.mass_balance_error(), 1e-12);
  EXPECT_LT(net.volume_balance_error(), 1e-9);
}

TEST(FlowVents, VentFillsAtZeroPressureBeforeItVents) {
  // Fracture 0-1 starts full at zero pressure, fracture 1-2 (ending at the vent) dry.
  // The first 0.1 kg fill the dry fracture's two halves without venting any; what comes
  // after the vent node is full leaves through it, and nothing ever flows in from it.
  const double w = 1e-4;  // each fracture holds 0.1 kg, each half 0.05 kg
  FlowNetwork net = vented_chain();
  net.fill_initially(0, w);
  net.add_injection({0, 0.03, 0.0});
  double last_vented = 0.0;
  bool vented_once = false;
  for (int step = 0; step < 12; ++step) {
    net.begin_step(1.0);
    net.wet(1);
    solve_rigid(net, w);
    EXPECT_FALSE(net.trial_pressurised(2));
    net.commit();
    EXPECT_GE(net.vented_mass(), last_vented) << "step " << step;
    if (step < 3) EXPECT_EQ(net.vented_mass(), 0.0) << "the vent is not full yet (step " << step << ")";
    vented_once = vented_once || net.vented_mass() > 0.0;
    last_vented = net.vented_mass();
    EXPECT_EQ(net.pressure(2), 0.0);
    EXPECT_LT(net.mass_balance_error(), 1e-12);
    EXPECT_LT(net.volume_balance_error(), 1e-9) << "step " << step;
  }
  EXPECT_TRUE(vented_once);
  // Injected 0.36 kg; the network holds its 0.2 kg full volume plus compression.
  EXPECT_GT(net.vented_mass(), 0.1);
}

TEST(FlowVents, InjectionAtAVentIsRejected) {
  FlowNetwork net(2, {Fracture{0, 1, 1.0}}, water(), FlowSettings{});
  net.add_injection({1, 1e-3, 0.0});
  EXPECT_THROW(net.set_vents({0, 1}), std::invalid_argument);
  EXPECT_THROW(net.set_vents({0}), std::invalid_argument);
  FlowNetwork vented(2, {Fracture{0, 1, 1.0}}, water(), FlowSettings{});
  vented.set_vents({0, 1});
  EXPECT_THROW(vented.add_injection({1, 1e-3, 0.0}), std::invalid_argument);
}

}  // namespace
