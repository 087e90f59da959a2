// coupling::AugmentedFlowSystem against the Schur complement it stands for: on a real
// block system (a fluid-filled crack after one coupled step), the pressure part of the
// solution of [K -B D; E G A] [u; x] = [0; r] must be x = J^-1 r with J = A + E S D and
// S = G K^-1 B formed column by column from the factorised K.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "core/errors.hpp"
#include "coupling_test_support.hpp"
#include "coupling/augmented_flow_system.hpp"
#include "io/case_config.hpp"
#include "simulation/model.hpp"

namespace hfdda {
namespace {

/// The wetted joints' ends and nodes of a model, with their gaps G and unit-pressure loads B
/// built as the coupling builds them.
struct CrackOperators {
  std::vector<dda::JointEndGap> gaps;               // per end (2 per joint)
  std::vector<std::vector<coupling::NodeLoad>> loads;  // per node
  std::vector<int> node_of_end;
};

CrackOperators crack_operators(const simulation::Model& model) {
  const dda::BlockSystem& system = *model.system;
  const auto& mesh = system.mesh();
  CrackOperators ops;
  std::map<int, int> node_of_point;
  Eigen::VectorXd work = Eigen::VectorXd::Zero(6 * system.n_blocks());
  for (int j = 0; j < static_cast<int>(mesh.joints.size()); ++j) {
    if (!model.flow->wetted(j)) continue;
    const auto& joint = mesh.joints[j];
    for (int end = 0; end < 2; ++end) {
      const int point = end == 0 ? joint.point_p : joint.point_q;
      const auto [it, added] = node_of_point.emplace(point, static_cast<int>(ops.loads.size()));
      if (added) ops.loads.emplace_back();
      ops.gaps.push_back(system.joint_end_gap(j, end));
      ops.node_of_end.push_back(it->second);
      system.add_joint_pressure_load(j, end == 0 ? 1.0 : 0.0, end == 0 ? 0.0 : 1.0, work);
      for (const int b : {joint.block_a, joint.block_b}) {
        ops.loads[it->second].push_back({b, work.segment<6>(6 * b)});
        work.segment<6>(6 * b).setZero();
      }
    }
  }
  return ops;
}

TEST(AugmentedFlowSystem, PressurePartIsTheSchurComplementSolve) {
  simulation::Model model =
      simulation::build_model(io::load_case_text(coupling_tests::kFluidFilledCrackCase, "crack.yaml"));
  model.step->advance(1.0, 0);
  const dda::BlockSystem& system = *model.system;
  const CrackOperators ops = crack_operators(model);
  const int n = static_cast<int>(ops.loads.size()), ne = static_cast<int>(ops.gaps.size());
  ASSERT_GE(n, 6);

  // S = G K^-1 B, one solve per node.
  Eigen::MatrixXd s(ne, n);
  for (int i = 0; i < n; ++i) {
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(6 * system.n_blocks());
    for (const auto& l : ops.loads[i]) rhs.segment<6>(6 * l.block) += l.force;
    const Eigen::VectorXd u = system.solver().solve(rhs);
    for (int e = 0; e < ne; ++e) {
      const auto& g = ops.gaps[e];
      s(e, i) = g.row_a.dot(u.segment<6>(6 * g.block_a)) + g.row_b.dot(u.segment<6>(6 * g.block_b));
    }
  }
  // A: storage on the diagonal and a conductance along each joint; E: half a joint's
  // volume per unit aperture at its end's node (water); d: one node at zero pressure.
  std::vector<Eigen::Triplet<double>> a_entries, e_entries;
  for (int i = 0; i < n; ++i) a_entries.emplace_back(i, i, 1e-9 * (1.0 + 0.1 * i));
  for (int e = 0; e + 1 < ne; e += 2) {
    const int p = ops.node_of_end[e], q = ops.node_of_end[e + 1];
    for (const auto& [r, c, v] : {std::tuple{p, p, 1e-8}, {q, q, 1e-8}, {p, q, -1e-8}, {q, p, -1e-8}})
      a_entries.emplace_back(r, c, v);
  }
  for (int e = 0; e < ne; ++e) e_entries.emplace_back(ops.node_of_end[e], e, 500.0);
  Eigen::SparseMatrix<double> a(n, n), e(n, ne);
  a.setFromTriplets(a_entries.begin(), a_entries.end());
  e.setFromTriplets(e_entries.begin(), e_entries.end());
  Eigen::VectorXd d = Eigen::VectorXd::Ones(n);
  d[n / 2] = 0.0;
  const Eigen::MatrixXd jacobian = Eigen::MatrixXd(a) + Eigen::MatrixXd(e) * s * d.asDiagonal();
  const Eigen::VectorXd r = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  const Eigen::VectorXd expected = jacobian.fullPivLu().solve(r);

  coupling::AugmentedFlowSystem augmented(system, ops.gaps, ops.loads);
  augmented.factorize(a, e, d);
  const Eigen::VectorXd x = augmented.solve(r);
  EXPECT_LT((x - expected).norm(), 1e-8 * expected.norm());
  EXPECT_LT((jacobian * x - r).norm(), 1e-8 * r.norm());

  // New values on the same pattern: one symbolic analysis, two factorisations.
  d[n / 2] = 1.0;
  augmented.factorize(2.0 * a, e, d);
  const Eigen::MatrixXd jacobian2 = 2.0 * Eigen::MatrixXd(a) + Eigen::MatrixXd(e) * s * d.asDiagonal();
  const Eigen::VectorXd x2 = augmented.solve(r);
  EXPECT_LT((jacobian2 * x2 - r).norm(), 1e-8 * r.norm());
  EXPECT_EQ(augmented.symbolic_analyses(), 1);
  EXPECT_EQ(augmented.factorizations(), 2);
  EXPECT_GT(augmented.factor_entries(), 0.0);
}

TEST(AugmentedFlowSystem, SingularSystemIsAConvergenceErrorNamingIt) {
  // No storage, no flow and every node at zero pressure: J = 0, no pivot for the pressures.
  simulation::Model model =
      simulation::build_model(io::load_case_text(coupling_tests::kFluidFilledCrackCase, "crack.yaml"));
  model.step->advance(1.0, 0);
  const CrackOperators ops = crack_operators(model);
  const int n = static_cast<int>(ops.loads.size()), ne = static_cast<int>(ops.gaps.size());
  std::vector<Eigen::Triplet<double>> e_entries;
  for (int e = 0; e < ne; ++e) e_entries.emplace_back(ops.node_of_end[e], e, 500.0);
  Eigen::SparseMatrix<double> a(n, n), e(n, ne);
  e.setFromTriplets(e_entries.begin(), e_entries.end());
  coupling::AugmentedFlowSystem augmented(*model.system, ops.gaps, ops.loads);
  try {
    augmented.factorize(a, e, Eigen::VectorXd::Zero(n));
    FAIL() << "a singular augmented system was factorised";
  } catch (const ConvergenceError& error) {
    EXPECT_NE(std::string(error.what()).find("singular mass-balance Jacobian"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace hfdda
