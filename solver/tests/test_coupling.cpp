// The coupled hydro-mechanical step (seed 2.4) and the in-situ stress state: the
// Newton solve through the factorised K must give the same blocks as the mechanics
// loaded by the same pressures directly, and a stressed rock at rest must stay at rest.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "coupling/coupled_step.hpp"
#include "coupling_test_support.hpp"
#include "coupling/prescribed_pressure.hpp"
#include "dda/block_system.hpp"
#include "io/case_config.hpp"
#include "simulation/model.hpp"

namespace hfdda {
namespace {

using coupling_tests::kFluidFilledCrackCase;

TEST(CoupledStep, MatchesMechanicsLoadedByTheSolvedPressures) {
  io::CaseConfig config = io::load_case_text(kFluidFilledCrackCase, "crack.yaml");
  simulation::Model coupled = simulation::build_model(config);
  coupled.step->advance(1.0, 0);
  const fluid::FlowNetwork& flow = *coupled.flow;
  const auto& mesh = coupled.system->mesh();

  // The same mesh loaded by the pressures the coupled step found, without a network.
  io::CaseConfig dry = config;
  dry.fluid.reset();
  dry.injections.clear();
  dry.fractures[0].fluid_filled = false;
  simulation::Model loaded = simulation::build_model(dry);
  std::vector<double> pressure(mesh.points.size(), 0.0);
  std::vector<char> wetted(mesh.joints.size(), 0);
  int crack_joints = 0;
  for (std::size_t j = 0; j < mesh.joints.size(); ++j) {
    if (!flow.wetted(static_cast<int>(j))) continue;
    ++crack_joints;
    wetted[j] = 1;
    pressure[mesh.joints[j].point_p] = flow.pressure(mesh.joints[j].point_p);
    pressure[mesh.joints[j].point_q] = flow.pressure(mesh.joints[j].point_q);
  }
  ASSERT_EQ(crack_joints, 6);
  coupling::PrescribedPressure prescribed(loaded.system->mesh(), pressure, wetted);
  coupling::CoupledStep(*loaded.system, {&prescribed}).advance(1.0, 0);

  double max_gap = 0.0, max_difference = 0.0;
  for (std::size_t j = 0; j < mesh.joints.size(); ++j) {
    if (!wetted[j]) continue;
    for (int end = 0; end < 2; ++end) {
      const double a = coupled.system->joint_gap(static_cast<int>(j), end);
      const double b = loaded.system->joint_gap(static_cast<int>(j), end);
      max_gap = std::max(max_gap, a);
      max_difference = std::max(max_difference, std::abs(a - b));
      // The flow's aperture is the blocks' separation where it is above the floors.
      if (a > 1e-5) EXPECT_NEAR(flow.aperture(static_cast<int>(j), end), a, 1e-6 * a);
    }
  }
  EXPECT_GT(max_gap, 1e-5);                      // the crack did open
  EXPECT_LT(max_difference, 1e-7 * max_gap);     // same blocks, to the ALM tolerance
  // The injected mass is stored, nothing else.
  EXPECT_NEAR(flow.injected_mass(), 0.5, 1e-15);
  EXPECT_LT(flow.mass_balance_error(), 1e-12);
}

/// Largest pressure and aperture of the wetted joints of `reference`, and the largest
/// differences from `other` (the same case run on another flow-Jacobian path).
struct FlowPathDifference {
  double max_pressure = 0.0, max_aperture = 0.0, pressure = 0.0, aperture = 0.0;
};
FlowPathDifference flow_path_difference(const simulation::Model& reference, const simulation::Model& other) {
  const auto& mesh = reference.system->mesh();
  FlowPathDifference d;
  for (int j = 0; j < static_cast<int>(mesh.joints.size()); ++j) {
    EXPECT_EQ(reference.flow->wetted(j), other.flow->wetted(j)) << "joint " << j;
    if (!reference.flow->wetted(j)) continue;
    for (int end = 0; end < 2; ++end) {
      const int point = end == 0 ? mesh.joints[j].point_p : mesh.joints[j].point_q;
      d.max_pressure = std::max(d.max_pressure, reference.flow->pressure(point));
      d.pressure = std::max(d.pressure, std::abs(reference.flow->pressure(point) - other.flow->pressure(point)));
      d.max_aperture = std::max(d.max_aperture, reference.flow->aperture(j, end));
      d.aperture = std::max(d.aperture, std::abs(reference.flow->aperture(j, end) - other.flow->aperture(j, end)));
    }
  }
  return d;
}

TEST(CoupledStep, KrylovPathGivesTheDenseSolution) {
  // The same steps with S formed densely and with S as an operator (GMRES, two-level
  // preconditioner): the pressures and apertures agree to the flow tolerance, and the
  // Krylov path never forms S (its products are counted).
  io::CaseConfig config = io::load_case_text(kFluidFilledCrackCase, "crack.yaml");
  config.numerics.flow_jacobian = io::FlowJacobianKind::dense;
  simulation::Model dense = simulation::build_model(config);
  config.numerics.flow_jacobian = io::FlowJacobianKind::krylov;
  simulation::Model krylov = simulation::build_model(config);
  StepStatistics krylov_stats;
  for (int step = 0; step < 3; ++step) {
    dense.step->advance(1.0, 0);
    krylov_stats = krylov.step->advance(1.0, 0);
  }
  const FlowPathDifference d = flow_path_difference(dense, krylov);
  EXPECT_GT(d.max_pressure, 1e5);
  EXPECT_LT(d.pressure, 1e-6 * d.max_pressure);
  EXPECT_LT(d.aperture, 1e-6 * d.max_aperture);
  EXPECT_GT(krylov.coupling->statistics().sensitivity_products, 0);
  EXPECT_EQ(dense.coupling->statistics().sensitivity_products, 0);
  EXPECT_LT(krylov.flow->mass_balance_error(), 1e-12);
  EXPECT_LT(krylov.flow->volume_balance_error(), 1e-8);
}

TEST(CoupledStep, AugmentedPathGivesTheDenseSolution) {
  // The flow Newton's steps from one sparse LU of [K -B D; E G A] solve J x = r exactly,
  // as the dense LU does: the same Newton iterations, the pressures and apertures to far
  // below the flow tolerance, no Krylov iteration, S never formed.
  io::CaseConfig config = io::load_case_text(kFluidFilledCrackCase, "crack.yaml");
  config.numerics.flow_jacobian = io::FlowJacobianKind::dense;
  simulation::Model dense = simulation::build_model(config);
  config.numerics.flow_jacobian = io::FlowJacobianKind::augmented;
  simulation::Model augmented = simulation::build_model(config);
  int newton[2] = {0, 0};
  long krylov = 0;
  for (int step = 0; step < 3; ++step) {
    newton[0] += dense.step->advance(1.0, 0).flow_newton_iterations;
    const StepStatistics stats = augmented.step->advance(1.0, 0);
    newton[1] += stats.flow_newton_iterations;
    krylov += stats.flow_krylov_iterations;
  }
  const FlowPathDifference d = flow_path_difference(dense, augmented);
  std::printf("Newton iterations over 3 steps: %d dense, %d augmented; pressures within %.2e of %.3e Pa\n",
              newton[0], newton[1], d.pressure, d.max_pressure);
  EXPECT_GT(d.max_pressure, 1e5);
  EXPECT_EQ(newton[1], newton[0]);  // the steps' Jacobian: a wrong one still converges, in more iterations
  EXPECT_LT(d.pressure, 1e-9 * d.max_pressure);
  EXPECT_LT(d.aperture, 1e-9 * d.max_aperture);
  EXPECT_EQ(krylov, 0);
  EXPECT_GT(augmented.coupling->statistics().sensitivity_products, 0);  // apertures as S p, S not formed
  EXPECT_LT(augmented.flow->mass_balance_error(), 1e-12);
}

TEST(CoupledStep, AutomaticFlowJacobianTakesTheAugmentedPathFromItsSize) {
  // flow_jacobian: auto (the default) below kOperatorFromNodes wetted nodes is the dense
  // path; with the bound lowered under the crack's node count, the augmented path (S as
  // an operator, no GMRES), to the same solution.
  io::CaseConfig config = io::load_case_text(kFluidFilledCrackCase, "crack.yaml");
  ASSERT_EQ(config.numerics.flow_jacobian, io::FlowJacobianKind::automatic);
  double inlet_Pa[2] = {0.0, 0.0};
  long products[2] = {0, 0}, krylov[2] = {0, 0};
  for (const int from_nodes : {coupling::HydroMechanicalCoupling::kOperatorFromNodes, 1}) {
    const int k = from_nodes == 1 ? 1 : 0;
    simulation::Model model = simulation::build_model(config);
    model.coupling->set_operator_from_nodes(from_nodes);
    krylov[k] = model.step->advance(1.0, 0).flow_krylov_iterations;
    products[k] = model.coupling->statistics().sensitivity_products;
    inlet_Pa[k] = model.flow->pressure(mesh::nearest_point(model.system->mesh(), Vec2(0, 0)));
  }
  EXPECT_EQ(products[0], 0);  // dense: S formed, no products with the operator
  EXPECT_GT(products[1], 0);
  EXPECT_EQ(krylov[1], 0);    // the augmented LU, not GMRES
  EXPECT_GT(inlet_Pa[0], 1e5);
  EXPECT_NEAR(inlet_Pa[1], inlet_Pa[0], 1e-6 * inlet_Pa[0]);
}

TEST(CoupledStep, NearFieldOfTheElasticCouplingCutsTheKrylovIterations) {
  // The Krylov path's preconditioner with the probed near field of S in its local part,
  // and without it (A alone): the same Newton iterates, fewer GMRES iterations. Linear
  // solves to 1e-10 throughout, so that the iterates do not depend on the preconditioner.
  io::CaseConfig config = io::load_case_text(kFluidFilledCrackCase, "crack.yaml");
  config.numerics.flow_jacobian = io::FlowJacobianKind::krylov;
  config.numerics.inexact_flow_solves = false;
  long gmres[2] = {0, 0};
  int newton[2] = {0, 0};
  double inlet_Pa[2] = {0.0, 0.0};
  for (const int hops : {0, coupling::ApertureOperator::kNearHops}) {
    const int k = hops == 0 ? 0 : 1;
    simulation::Model model = simulation::build_model(config);
    model.coupling->set_near_field_hops(hops);
    for (int step = 0; step < 3; ++step) {
      const StepStatistics stats = model.step->advance(1.0, 0);
      gmres[k] += stats.flow_krylov_iterations;
      newton[k] += stats.flow_newton_iterations;
    }
    inlet_Pa[k] = model.flow->pressure(mesh::nearest_point(model.system->mesh(), Vec2(0, 0)));
  }
  std::printf("GMRES iterations over 3 steps: %ld without the near field, %ld with it (%d, %d Newton)\n", gmres[0],
              gmres[1], newton[0], newton[1]);
  EXPECT_EQ(newton[0], newton[1]);
  EXPECT_NEAR(inlet_Pa[1], inlet_Pa[0], 1e-8 * inlet_Pa[0]);
  EXPECT_GT(gmres[1], 0);
  EXPECT_LT(gmres[1], 0.8 * gmres[0]);  // measured 0.67
}

TEST(CoupledStep, InexactFlowSolvesCutTheKrylovIterations) {
  // GMRES stopped at 1e-4 while the flow Newton converges well, against every solve to
  // 1e-10: fewer GMRES iterations, no more Newton iterations than a few, and the same
  // pressures to the flow tolerance (docs/design_notes.md section 43).
  io::CaseConfig config = io::load_case_text(kFluidFilledCrackCase, "crack.yaml");
  config.numerics.flow_jacobian = io::FlowJacobianKind::krylov;
  long gmres[2] = {0, 0};
  int newton[2] = {0, 0};
  double inlet_Pa[2] = {0.0, 0.0};
  for (const bool inexact : {false, true}) {
    const int k = inexact ? 1 : 0;
    config.numerics.inexact_flow_solves = inexact;
    simulation::Model model = simulation::build_model(config);
    for (int step = 0; step < 3; ++step) {
      const StepStatistics stats = model.step->advance(1.0, 0);
      gmres[k] += stats.flow_krylov_iterations;
      newton[k] += stats.flow_newton_iterations;
    }
    inlet_Pa[k] = model.flow->pressure(mesh::nearest_point(model.system->mesh(), Vec2(0, 0)));
  }
  std::printf("GMRES iterations over 3 steps: %ld exact, %ld inexact (%d, %d Newton)\n", gmres[0], gmres[1],
              newton[0], newton[1]);
  EXPECT_LE(newton[1], newton[0] + 3);
  EXPECT_NEAR(inlet_Pa[1], inlet_Pa[0], 1e-7 * inlet_Pa[0]);
  EXPECT_LT(gmres[1], 0.9 * gmres[0]);  // measured 0.78
}

TEST(CoupledStep, ClosedCrackFillsAndOpensStepAfterStep) {
  // The inlet pressure may fall once the early viscous gradient relaxes, and the crack
  // first opens faster than the fluid arrives (its ends fill at zero pressure); its
  // volume must rise while fluid keeps coming, and the ends fill up in the end.
  io::CaseConfig config = io::load_case_text(kFluidFilledCrackCase, "crack.yaml");
  simulation::Model model = simulation::build_model(config);
  const auto& mesh = model.system->mesh();
  const int far_end = mesh::nearest_point(mesh, Vec2(2, 0));
  double last_volume = 0.0, volume = 0.0;
  for (int step = 0; step < 8; ++step) {
    model.step->advance(1.0, 0);
    volume = 0.0;
    for (int j = 0; j < model.flow->n_fractures(); ++j)
      if (model.flow->wetted(j))
        volume += 0.5 * model.flow->fracture(j).length_m * (model.flow->aperture(j, 0) + model.flow->aperture(j, 1));
    EXPECT_GT(volume, last_volume);
    EXPECT_LE(model.flow->stored_mass(), 1000.0 * (1.0 + 1e-2) * volume);  // never over-full (p < 22 MPa)
    last_volume = volume;
  }
  EXPECT_GT(model.flow->pressure(far_end), 0.0);
  // Full: the stored mass is rho(p) V (p ~ 1 MPa changes rho by 0.05 %).
  EXPECT_NEAR(model.flow->stored_mass() / 1000.0, volume, 0.01 * volume);
  EXPECT_LT(model.flow->mass_balance_error(), 1e-12);
}

TEST(InSituStress, StressedRockAtRestStaysAtRest) {
  const char* text = R"(
title: "in-situ"
domain: {outer: {xmin: -5, xmax: 5, ymin: -5, ymax: 5}}
mesh: {type: structured, cell_size: 1.0, split: four}
far_field: {sxx: -5.0e6, syy: -10.0e6, sxy: 2.0e6, in_situ: true}
fixed_points: [[-5, -5]]
time: {dt: 1.0, end_time: 1.0}
)";
  simulation::Model model = simulation::build_model(io::load_case_text(text, "insitu.yaml"));
  const auto stats = model.step->advance(1.0, 0);
  EXPECT_EQ(stats.state_changes, 0);
  double max_d = 0.0;
  for (const auto& d : model.system->last_step_displacement()) max_d = std::max(max_d, d.head<2>().cwiseAbs().maxCoeff());
  EXPECT_LT(max_d, 1e-12);
  for (int b = 0; b < model.system->n_blocks(); ++b) {
    EXPECT_NEAR(model.system->stress(b)[0], -5.0e6, 1.0);
    EXPECT_NEAR(model.system->stress(b)[1], -10.0e6, 1.0);
    EXPECT_NEAR(model.system->stress(b)[2], 2.0e6, 1.0);
  }
}

TEST(InSituStress, BoundaryLoadingFromRestWithFixedCornersIsNotUniform) {
  // The seed's way (tractions from rest, corners pinned) leaves part of the load on
  // the pins: the contrast that made `in_situ` necessary.
  const char* text = R"(
title: "boundary"
domain: {outer: {xmin: -5, xmax: 5, ymin: -5, ymax: 5}}
mesh: {type: structured, cell_size: 1.0, split: four}
far_field: {sxx: -5.0e6, syy: -5.0e6, sxy: 0, sides: [left, right, bottom, top]}
fixed_points: [[-5, -5], [5, -5], [5, 5], [-5, 5]]
time: {dt: 1.0, end_time: 1.0}
)";
  simulation::Model model = simulation::build_model(io::load_case_text(text, "boundary.yaml"));
  model.step->advance(1.0, 0);
  double max_deviation = 0.0;
  for (int b = 0; b < model.system->n_blocks(); ++b)
    max_deviation = std::max(max_deviation, std::abs(model.system->stress(b)[0] + 5.0e6));
  EXPECT_GT(max_deviation, 0.2e6);
}

}  // namespace
}  // namespace hfdda
