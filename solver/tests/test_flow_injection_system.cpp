// The injection system's compliance (fluid::Injection::system_compliance_m2_Pa): the
// pump, lines and borehole upstream of the fracture hold rho(0) C p more fluid at
// pressure p than at zero. And the initial fill of a fracture with a hydraulic width
// w0, which fills w0 as well. Apertures given directly (rigid walls).

#include <gtest/gtest.h>

#include <string>

#include "core/errors.hpp"
#include "flow_test_support.hpp"
#include "fluid/flow_network.hpp"
#include "io/case_config.hpp"
#include "simulation/model.hpp"

namespace {

using hfdda::fluid::FlowNetwork;
using hfdda::fluid::FlowSettings;
using hfdda::fluid::FluidProperties;
using hfdda::fluid::Fracture;
using hfdda::fluid::Injection;
using hfdda::fluid::testing::solve_rigid;
using hfdda::fluid::testing::water;

TEST(FlowInjectionSystem, CompliancePressurisesAsItsClosedForm) {
  // One rigid fracture of 1 m, 1 mm wide, full at zero pressure, sealed. Over one step
  // of dt the pump delivers q dt; at a pressure p nearly uniform (the fracture is wide)
  // the fluid stores rho(0) p V / K_f more and the system rho(0) C p:
  // p = q dt / (rho(0) (V / K_f + C)). Without the system's term p would be 23 times higher.
  const double w = 1e-3, q = 1e-3, dt = 1.0, compliance = 1e-11;
  const FluidProperties f = water();
  FlowNetwork net(2, {Fracture{0, 1, 1.0}}, f, FlowSettings{});
  net.fill_initially(0, w);
  Injection pump{0, q, 0.0};
  pump.system_compliance_m2_Pa = compliance;
  net.add_injection(pump);
  net.begin_step(dt);
  solve_rigid(net, w);
  net.commit();
  const double expected = q * dt / (f.density(0.0) * (1.0 * w / f.bulk_modulus_Pa + compliance));
  EXPECT_NEAR(net.pressure(0), expected, 1e-3 * expected);
  EXPECT_NEAR(net.pressure(1), expected, 1e-3 * expected);
  EXPECT_LT(net.mass_balance_error(), 1e-12);
  EXPECT_LT(net.volume_balance_error(), 1e-9) << "the system's mass is part of what the state holds";
}

TEST(FlowInjectionSystem, SystemGivesBackWhatItHeldWhenThePressureFalls) {
  // Points 0 - 1 - 2, a vent at 2. The pump delivers 0.2 kg over 2 s into a system
  // that stores most of it; once the pump stops the pressure falls and the system
  // empties through the fractures: in the end everything pumped has left by the vent.
  const double w = 1e-4, compliance = 1e-9;
  FlowNetwork net(3, {Fracture{0, 1, 1.0}, Fracture{1, 2, 1.0}}, water(), FlowSettings{});
  net.set_vents({0, 0, 1});
  net.fill_initially(0, w);
  net.fill_initially(1, w);
  Injection pump{0, 0.1, 0.0, 0.2};
  pump.system_compliance_m2_Pa = compliance;
  net.add_injection(pump);
  double peak = 0.0;
  for (int step = 0; step < 400; ++step) {
    net.begin_step(step < 20 ? 0.1 : 1.0);
    solve_rigid(net, w);
    net.commit();
    peak = std::max(peak, net.pressure(0));
    ASSERT_LT(net.volume_balance_error(), 1e-9) << "step " << step;
  }
  EXPECT_GT(peak, 0.5 * 0.2 / (1000.0 * compliance)) << "the system held most of the pumped mass";
  EXPECT_LT(net.pressure(0), 1e-3 * peak);
  EXPECT_NEAR(net.vented_mass(), 0.2, 1e-3 * 0.2);
  EXPECT_LT(net.mass_balance_error(), 1e-12);
}

TEST(FlowInjectionSystem, StartsOnlyAtZeroPressure) {
  FlowNetwork net(2, {Fracture{0, 1, 1.0}}, water(), FlowSettings{});
  net.fill_initially(0, 1e-4, 1.0e6);
  Injection pump{0, 1e-3, 0.0};
  pump.system_compliance_m2_Pa = 1e-11;
  EXPECT_THROW(net.add_injection(pump), std::invalid_argument);
  pump.system_compliance_m2_Pa = 0.0;
  EXPECT_NO_THROW(net.add_injection(pump));
}

TEST(FlowInjectionSystem, CaseWithACompliantSystemAtAPressurisedStartIsRefused) {
  const std::string text = R"(title: compliant pump into a pressurised notch
domain: {outer: {xmin: -2, xmax: 2, ymin: -2, ymax: 2}}
mesh: {type: structured, cell_size: 0.5, split: two}
materials: [{youngs_modulus: 1.0e9, poissons_ratio: 0.25}]
fractures:
  - {from: [-0.5, 0], to: [0.5, 0], initially_open: true, fluid_filled: true, initial_pressure: 1.0e5}
fluid: {}
injections:
  - {name: pump, at: [0, 0], mass_rate: 1.0e-3, system_compliance: 1.0e-11}
fixed_points: [[-2, -2], [2, 2]]
)";
  try {
    hfdda::simulation::build_model(hfdda::io::load_case_text(text, "pump.yaml"));
    FAIL() << "no error";
  } catch (const hfdda::ModelError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("injection 'pump' (line 9)"), std::string::npos) << message;
    EXPECT_NE(message.find("system_compliance needs the fluid at its point to start at zero pressure"),
              std::string::npos)
        << message;
  }
}

TEST(FlowInitialFill, FillsTheHydraulicWidthToo) {
  // A fluid-filled fracture open by 2 um with w0 = 100 um starts full: it holds
  // rho(0) L (w + w0), and a step in which nothing moves leaves it full at zero pressure
  // (filling only w, it would become a zero-pressure node filled to 2 %). Closed, with
  // w0 alone, it holds rho(0) L w0.
  const double w0 = 1e-4, w = 2e-6;
  const FluidProperties f = water();
  FlowNetwork net(2, {Fracture{0, 1, 1.0, w0}}, f, FlowSettings{});
  net.fill_initially(0, w);
  EXPECT_NEAR(net.initial_mass(), f.density(0.0) * 1.0 * (w + w0), 1e-12);
  net.begin_step(1.0);
  solve_rigid(net, w);  // the walls stay 2 um apart; the flow adds w0
  net.commit();
  EXPECT_FALSE(net.zero_pressure(0));
  EXPECT_FALSE(net.zero_pressure(1));
  EXPECT_LE(net.pressure(0), hfdda::fluid::MassBalance::kPressureRounding) << "zero, within the rounding of max(y, 0)";
  EXPECT_LT(net.volume_balance_error(), 1e-9);

  FlowNetwork closed(2, {Fracture{0, 1, 1.0, w0}}, f, FlowSettings{});
  closed.fill_initially(0, 0.0);
  EXPECT_NEAR(closed.initial_mass(), f.density(0.0) * 1.0 * w0, 1e-12);
}

}  // namespace
