// Unit tests of the DDA mechanics (docs/formulation.md section 3.4 "tests that pin the mechanics down").

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <memory>
#include <random>
#include <string>

#include "core/errors.hpp"
#include "coupling/coupled_step.hpp"
#include "dda/block_kinematics.hpp"
#include "dda/block_sparse_matrix.hpp"
#include "dda/block_system.hpp"
#include "dda/contacts.hpp"
#include "dda_test_support.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::dda {
namespace {

using test_support::alm_settings;
using test_support::small_mesh;
using test_support::step;

/// Traction sigma . n on every boundary edge (n outward).
void apply_uniform_stress(BlockSystem& system, const Eigen::Matrix2d& sigma) {
  for (int e = 0; e < static_cast<int>(system.mesh().boundary_edges.size()); ++e) system.add_boundary_stress(e, sigma);
}

TEST(DdaKinematics, RigidBodyMotionHasNoStrainEnergy) {
  const std::vector<Vec2> tri{{0.3, -0.2}, {1.7, 0.1}, {0.5, 1.4}};
  const PolygonMoments g = polygon_moments(tri);
  Mat6 k = Mat6::Zero();
  k.block<3, 3>(3, 3) = g.area * plane_strain_elasticity(25e9, 0.25);
  Vec6 rigid;
  rigid << 0.01, -0.02, 1e-3, 0.0, 0.0, 0.0;
  EXPECT_EQ(rigid.dot(k * rigid), 0.0);
  // T reproduces a rigid rotation to first order: distances between corners are kept.
  Vec6 rotation = Vec6::Zero();
  rotation(2) = 1e-6;
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {
      const Vec2 ui = displacement_matrix(tri[i], g.centroid) * rotation;
      const Vec2 uj = displacement_matrix(tri[j], g.centroid) * rotation;
      EXPECT_NEAR((ui - uj).dot(tri[i] - tri[j]), 0.0, 1e-18);
    }
  // Strains produce the displacement gradient they name (erratum 1 in docs/seed_errata.md).
  Vec6 strain = Vec6::Zero();
  strain << 0, 0, 0, 1e-3, -2e-3, 4e-3;
  const Vec2 u = displacement_matrix(g.centroid + Vec2(1.0, 0.0), g.centroid) * strain;
  const Vec2 v = displacement_matrix(g.centroid + Vec2(0.0, 1.0), g.centroid) * strain;
  EXPECT_NEAR(u.x(), 1e-3, 1e-15);        // du/dx = ex
  EXPECT_NEAR(v.y(), -2e-3, 1e-15);       // dv/dy = ey
  EXPECT_NEAR(u.y() + v.x(), 4e-3, 1e-15);  // dv/dx + du/dy = gxy
}

TEST(DdaKinematics, RigidTranslationOfWholeSystemCostsNothingInTheContacts) {
  // A step with no loads on a bonded mesh leaves every block unstrained and at rest.
  const mesh::Mesh m = small_mesh(3, 2, 1.0, mesh::CellSplit::two);
  BlockSystem system(m, {Material{}}, alm_settings(25e9));
  system.add_fixed_point({0.0, 0.0});
  step(system, 1.0);
  for (int b = 0; b < system.n_blocks(); ++b) EXPECT_EQ(system.last_step_displacement()[b].norm(), 0.0);
}

class UniformStressPatch : public ::testing::TestWithParam<mesh::CellSplit> {};

TEST_P(UniformStressPatch, IsReproducedInEveryBlock) {
  const mesh::Mesh m = small_mesh(4, 3, 0.5, GetParam());
  BlockSystem system(m, {Material{}}, alm_settings(25e9));
  system.add_fixed_point({0.0, 0.0});
  Eigen::Matrix2d sigma;
  sigma << -3e6, 1e6, 1e6, -5e6;
  apply_uniform_stress(system, sigma);
  for (int k = 0; k < 3; ++k) step(system, 1.0);
  // Inertia (static analysis) delays equilibrium by rho h^2 / (E dt^2) ~ 1e-8 per step.
  for (int b = 0; b < system.n_blocks(); ++b) {
    const auto& s = system.stress(b);
    EXPECT_NEAR(s(0), -3e6, 1.0) << "block " << b;
    EXPECT_NEAR(s(1), -5e6, 1.0) << "block " << b;
    EXPECT_NEAR(s(2), 1e6, 1.0) << "block " << b;
  }
}

INSTANTIATE_TEST_SUITE_P(Splits, UniformStressPatch,
                         ::testing::Values(mesh::CellSplit::two, mesh::CellSplit::four, mesh::CellSplit::none));

/// Linear-triangle (CST) finite elements on the same mesh: the oracle for a DDA mesh
/// whose joints are all locked with a converged ALM (conforming linear fields).
struct CstSolution {
  std::vector<Eigen::Vector3d> strain;  // (ex, ey, gxy) per triangle
};

CstSolution solve_cst(const mesh::Mesh& m, const Material& mat, double dt, double penalty,
                      const std::vector<Vec2>& fixed, const std::vector<std::pair<Vec2, Vec2>>& loads) {
  const int n = 2 * static_cast<int>(m.points.size());
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  const Eigen::Matrix3d c = plane_strain_elasticity(mat.youngs_modulus_Pa, mat.poissons_ratio);
  std::vector<Eigen::Matrix<double, 3, 6>> b_matrices;
  for (const auto& block : m.blocks) {
    const Vec2 p[3] = {m.points[block.points[0]], m.points[block.points[1]], m.points[block.points[2]]};
    const double area = 0.5 * cross2(p[0], p[1], p[2]);
    Eigen::Matrix<double, 3, 6> b = Eigen::Matrix<double, 3, 6>::Zero();
    for (int i = 0; i < 3; ++i) {
      const Vec2& pj = p[(i + 1) % 3];
      const Vec2& pk = p[(i + 2) % 3];
      const double dndx = (pj.y() - pk.y()) / (2 * area), dndy = (pk.x() - pj.x()) / (2 * area);
      b(0, 2 * i) = dndx;
      b(1, 2 * i + 1) = dndy;
      b(2, 2 * i) = dndy;
      b(2, 2 * i + 1) = dndx;
    }
    b_matrices.push_back(b);
    Eigen::Matrix<double, 6, 6> ke = area * b.transpose() * c * b;
    // Consistent mass: the DDA inertia term integrates the same linear field.
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int d = 0; d < 2; ++d)
          ke(2 * i + d, 2 * j + d) += 2.0 / (dt * dt) * mat.density_kg_m3 * area / 12.0 * (i == j ? 2.0 : 1.0);
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) k(2 * block.points[i / 2] + i % 2, 2 * block.points[j / 2] + j % 2) += ke(i, j);
  }
  auto nearest = [&](const Vec2& x) { return mesh::nearest_point(m, x); };
  for (const Vec2& x : fixed) {
    const int p = nearest(x);
    k(2 * p, 2 * p) += penalty;
    k(2 * p + 1, 2 * p + 1) += penalty;
  }
  for (const auto& [x, force] : loads) f.segment<2>(2 * nearest(x)) += force;
  const Eigen::VectorXd u = k.ldlt().solve(f);
  CstSolution s;
  for (std::size_t e = 0; e < m.blocks.size(); ++e) {
    Eigen::Matrix<double, 6, 1> ue;
    for (int i = 0; i < 6; ++i) ue(i) = u(2 * m.blocks[e].points[i / 2] + i % 2);
    s.strain.push_back(b_matrices[e] * ue);
  }
  return s;
}

struct StrainComparison {
  double max_error = 0.0, max_strain = 0.0;
  std::unique_ptr<BlockSystem> system;  // after its step, for further checks
};

/// One step of a 4 x 2 two-triangle mesh under point loads, fixed at two points, with
/// its block strains compared to the CST oracle.
StrainComparison compare_with_cst(const MechanicsSettings& settings,
                                  const std::vector<std::pair<Vec2, Vec2>>& loads) {
  const mesh::Mesh m = small_mesh(4, 2, 1.0, mesh::CellSplit::two);
  const Material mat{25e9, 0.25, 2650.0};
  const std::vector<Vec2> fixed{{0.0, 0.0}, {0.0, 2.0}};
  auto last = std::make_unique<BlockSystem>(m, std::vector<Material>{mat}, settings);
  for (const auto& x : fixed) last->add_fixed_point(x);
  for (const auto& [x, force] : loads) last->add_point_load(x, force);
  step(*last, 1.0);
  const CstSolution oracle = solve_cst(m, mat, 1.0, settings.fixed_point_stiffness_N_m, fixed, loads);
  StrainComparison c;
  for (int b = 0; b < last->n_blocks(); ++b) {
    c.max_strain = std::max(c.max_strain, oracle.strain[b].cwiseAbs().maxCoeff());
    c.max_error = std::max(c.max_error,
                           (last->last_step_displacement()[b].tail<3>() - oracle.strain[b]).cwiseAbs().maxCoeff());
  }
  c.system = std::move(last);
  return c;
}

TEST(DdaAgainstCst, LockedJointsWithConvergedAlmGiveCstStrains) {
  const StrainComparison c = compare_with_cst(
      alm_settings(25e9), {{{4.0, 2.0}, {2e6, -1e6}}, {{4.0, 0.0}, {1e6, 0.0}}, {{2.0, 2.0}, {0.0, -3e6}}});
  ASSERT_GT(c.max_strain, 1e-5);
  EXPECT_LT(c.max_error, 1e-6 * c.max_strain) << "max strain " << c.max_strain;
  for (const auto& contact : c.system->contacts())
    if (contact.joint >= 0) EXPECT_EQ(contact.state, ContactState::locked);
}

TEST(DdaAgainstCst, PenaltyMethodIsOnlyApproximate) {
  // Without multiplier updates the joints stay compliant (1/k): the same problem
  // deviates from the conforming solution. This guards the ALM test above against a
  // vacuous pass.
  MechanicsSettings settings = alm_settings(25e9);
  settings.augmented_lagrangian = false;
  settings.normal_stiffness_N_m = settings.shear_stiffness_N_m = 10.0 * 25e9;
  const StrainComparison c = compare_with_cst(settings, {{{4.0, 2.0}, {2e6, -1e6}}});
  EXPECT_GT(c.max_error, 1e-3 * c.max_strain);
}

TEST(DdaContacts, LinearisationMatchesFiniteDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec2 p1(0.4, 0.05), p2(0.0, 0.0), p3(1.0, 0.1);
  const Vec2 cv(0.5, 0.6), ce(0.4, -0.5);
  VertexEdgeSpring s;
  s.reference_ratio = 0.35;
  linearise_vertex_edge(p1, p2, p3, cv, ce, s);
  EXPECT_NEAR(s.gap0, vertex_edge_gap(p1, p2, p3), 1e-15);
  for (int trial = 0; trial < 20; ++trial) {
    Vec6 dv, de;
    for (int i = 0; i < 6; ++i) dv(i) = u(rng), de(i) = u(rng);
    // The linearisation error must shrink like eps^2 (first-order exact).
    double previous_error = 0.0;
    for (double eps : {1e-3, 1e-4}) {
      const Vec2 q1 = p1 + displacement_matrix(p1, cv) * (eps * dv);
      const Vec2 q2 = p2 + displacement_matrix(p2, ce) * (eps * de);
      const Vec2 q3 = p3 + displacement_matrix(p3, ce) * (eps * de);
      const double exact = vertex_edge_gap(q1, q2, q3);
      const double linear = s.gap0 + eps * (s.gap_vertex.dot(dv) + s.gap_edge.dot(de));
      const double error = std::abs(exact - linear);
      EXPECT_LT(error, 20.0 * eps * eps) << "eps " << eps;
      if (previous_error > 1e-14) EXPECT_LT(error, previous_error * 0.05);
      previous_error = error;
      // Shear: position of the corner along the (moved) edge relative to the moved reference point.
      const Vec2 q0 = q2 + s.reference_ratio * (q3 - q2);
      const double exact_shear = (q1 - q0).dot((q3 - q2).normalized());
      const double linear_shear = s.shear0 + eps * (s.shear_vertex.dot(dv) + s.shear_edge.dot(de));
      EXPECT_LT(std::abs(exact_shear - linear_shear), 20.0 * eps * eps);
    }
  }
}

TEST(DdaSparse, CholmodSolveMatchesDenseSolve) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int nb = 5;
  const std::vector<std::pair<int, int>> couplings{{0, 1}, {1, 2}, {3, 1}, {4, 0}, {2, 4}};
  BlockSparseMatrix k(nb, couplings);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(6 * nb, 6 * nb);
  for (auto [i, j] : couplings) {
    Mat6 m;
    for (int a = 0; a < 36; ++a) m.data()[a] = u(rng);
    k.add_coupling(k.coupling_slot(i, j), i, j, m);
    dense.block<6, 6>(6 * i, 6 * j) += m;
    dense.block<6, 6>(6 * j, 6 * i) += m.transpose();
  }
  for (int b = 0; b < nb; ++b) {
    Mat6 r;
    for (int a = 0; a < 36; ++a) r.data()[a] = u(rng);
    const Mat6 spd = r * r.transpose() + 40.0 * Mat6::Identity();
    k.add_diagonal(b, spd);
    dense.block<6, 6>(6 * b, 6 * b) += spd;
  }
  Eigen::VectorXd x(6 * nb), rhs(6 * nb);
  for (int i = 0; i < 6 * nb; ++i) x(i) = u(rng), rhs(i) = u(rng);
  EXPECT_LT((k.multiply(x) - dense * x).norm(), 1e-12 * (dense * x).norm());
  SpdSolver solver;
  solver.factorize(k.matrix());
  const Eigen::VectorXd sparse_solution = solver.solve(rhs);
  const Eigen::VectorXd dense_solution = dense.llt().solve(rhs);
  EXPECT_LT((sparse_solution - dense_solution).norm(), 1e-12 * dense_solution.norm());
  // Refactorising new values reuses the symbolic analysis and stays correct.
  k.add_diagonal(0, 10.0 * Mat6::Identity());
  dense.block<6, 6>(0, 0) += 10.0 * Mat6::Identity();
  solver.factorize(k.matrix());
  EXPECT_LT((solver.solve(rhs) - dense.llt().solve(rhs)).norm(), 1e-12 * dense_solution.norm());
  EXPECT_EQ(solver.factorizations(), 2);
}

TEST(DdaSparse, IndefiniteMatrixIsReportedWithItsUnknown) {
  // Three blocks, positive definite but for the rotation (unknown 2) of block 1: the
  // failure names that unknown, whatever order CHOLMOD factorises in.
  BlockSparseMatrix k(3, {});
  for (int b = 0; b < 3; ++b) {
    Mat6 d = Mat6::Identity();
    if (b == 1) d(2, 2) = -1.0;
    k.add_diagonal(b, d);
  }
  SpdSolver solver;
  EXPECT_THROW(solver.factorize(k.matrix()), ConvergenceError);
  EXPECT_EQ(solver.failed_unknown(), 6 * 1 + 2);
}

/// K of a chain of blocks joined by stiff springs (k = 30 E, E = 25 GPa), with the spring
/// terms; the blocks' own terms are of order E.
struct SpringChain {
  BlockSparseMatrix k;
  std::vector<SpringTerm> springs;
};

SpringChain spring_chain(int n_blocks, int springs_per_pair, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::pair<int, int>> pairs;
  for (int b = 0; b + 1 < n_blocks; ++b) pairs.emplace_back(b, b + 1);
  SpringChain chain{BlockSparseMatrix(n_blocks, pairs), {}};
  const double youngs_modulus = 25e9;
  for (int b = 0; b < n_blocks; ++b) {
    Mat6 r;
    for (int a = 0; a < 36; ++a) r.data()[a] = u(rng);
    chain.k.add_diagonal(b, youngs_modulus * (r * r.transpose() + Mat6::Identity()));
  }
  for (auto [a, b] : pairs)
    for (int s = 0; s < springs_per_pair; ++s) {
      SpringTerm t{a, b, Row6::Zero(), Row6::Zero(), 30.0 * youngs_modulus};
      for (int i = 0; i < 6; ++i) t.row_a[i] = u(rng), t.row_b[i] = u(rng);
      chain.springs.push_back(t);
    }
  return chain;
}

void add_springs(BlockSparseMatrix& k, const std::vector<SpringTerm>& springs) {
  for (const SpringTerm& t : springs) {
    k.add_diagonal(t.block_a, t.stiffness * t.row_a.transpose() * t.row_a);
    k.add_diagonal(t.block_b, t.stiffness * t.row_b.transpose() * t.row_b);
    k.add_coupling(k.coupling_slot(t.block_a, t.block_b), t.block_a, t.block_b,
                   t.stiffness * t.row_a.transpose() * t.row_b);
  }
}

TEST(DdaSparse, LowRankChangesOfKSolveLikeANewFactorisation) {
  // Contact-state changes within a step: stiff springs removed (downdates, where digits
  // can be lost) and new ones added, applied to the factor of K by either method; the
  // solve must satisfy the changed K as well as a factorisation of it does.
  std::mt19937 rng(7);
  SpringChain chain = spring_chain(30, 4, rng);
  BlockSparseMatrix before = chain.k;
  add_springs(before, chain.springs);
  // Changes: the springs of pairs 10-14 removed, new springs on pairs 20-22.
  std::vector<SpringTerm> changes;
  for (std::size_t s = 40; s < 60; ++s) {
    changes.push_back(chain.springs[s]);
    changes.back().stiffness = -changes.back().stiffness;
  }
  const SpringChain added = spring_chain(30, 4, rng);
  changes.insert(changes.end(), added.springs.begin() + 80, added.springs.begin() + 92);
  std::vector<SpringTerm> after_springs(chain.springs.begin(), chain.springs.begin() + 40);
  after_springs.insert(after_springs.end(), chain.springs.begin() + 60, chain.springs.end());
  after_springs.insert(after_springs.end(), added.springs.begin() + 80, added.springs.begin() + 92);
  BlockSparseMatrix after = chain.k;
  add_springs(after, after_springs);

  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd rhs(6 * 30);
  for (int i = 0; i < rhs.size(); ++i) rhs[i] = 1e9 * u(rng);
  SpdSolver fresh;
  fresh.factorize(after.matrix());
  const Eigen::VectorXd expected = fresh.solve(rhs);
  const double fresh_residual = (after.multiply(expected) - rhs).norm() / rhs.norm();
  for (LowRankMethod method : {LowRankMethod::updown, LowRankMethod::woodbury}) {
    SCOPED_TRACE(method == LowRankMethod::updown ? "updown" : "woodbury");
    SpdSolver solver;
    solver.factorize(before.matrix());
    // In two rounds, as two open-close iterations would.
    ASSERT_TRUE(solver.modify({changes.begin(), changes.begin() + 8}, method));
    ASSERT_TRUE(solver.modify({changes.begin() + 8, changes.end()}, method));
    EXPECT_EQ(solver.modified_rank(), 32);
    EXPECT_EQ(solver.factorizations(), 1);
    const Eigen::VectorXd x = solver.solve(rhs);
    const double residual = (after.multiply(x) - rhs).norm() / rhs.norm();
    EXPECT_LT(residual, std::max(100.0 * fresh_residual, 1e-12));
    EXPECT_LT((x - expected).norm(), 1e-8 * expected.norm());
    // Several right-hand sides at once, as S = J K^-1 B is built.
    Eigen::MatrixXd rhs3(rhs.size(), 3);
    rhs3 << rhs, 2.0 * rhs, -rhs;
    EXPECT_LT((solver.solve(rhs3).col(2) + expected).norm(), 1e-8 * expected.norm());
    // A new factorisation forgets the changes.
    solver.factorize(after.matrix());
    EXPECT_EQ(solver.modified_rank(), 0);
    EXPECT_LT((solver.solve(rhs) - expected).norm(), 1e-12 * expected.norm());
  }
}

TEST(DdaContacts, LowRankUpdatesOfKSolveLikeNewFactorisations) {
  // Contact-state changes within a step (a joint opened, one end of another sliding,
  // then locked again with a new shear reference): with low_rank_updates they are
  // applied to the step's factorisation, and the solves of the contact iterations must
  // match those of new factorisations. (Whole open-close sequences are not compared:
  // contacts at a zero-strength limit flip on round-off either way.)
  const mesh::Mesh m = small_mesh(2, 2, 1.0, mesh::CellSplit::none);
  std::vector<std::vector<Eigen::VectorXd>> solutions;
  for (bool low_rank : {false, true}) {
    MechanicsSettings settings = alm_settings(25e9);
    settings.low_rank_updates = low_rank;
    BlockSystem system(m, {Material{}}, settings);
    system.add_fixed_point({0.0, 0.0});
    system.add_fixed_point({2.0, 0.0});
    system.add_point_load({0.0, 2.0}, {0.0, 1e6});
    system.add_point_load({2.0, 2.0}, {0.0, 1e6});
    system.begin_step(1.0);
    StepStatistics stats;
    system.assemble_and_factorise(stats);
    std::vector<Eigen::VectorXd> d{system.solver().solve(system.contact_rhs())};
    const auto [open_p, open_q] = system.joint_contacts(0);
    const int slipping = system.joint_contacts(1)[0];
    const std::vector<std::vector<ContactChange>> rounds{
        {ContactChange{open_p, ContactState::open, true}, ContactChange{open_q, ContactState::open, true},
         ContactChange{slipping, ContactState::sliding, true, 1.0}},
        {ContactChange{slipping, ContactState::locked}}};
    for (const auto& changes : rounds) {
      system.apply_state_changes(d.back(), changes, stats);
      system.assemble_and_factorise(stats);
      d.push_back(system.solver().solve(system.contact_rhs()));
    }
    EXPECT_EQ(stats.factorizations, low_rank ? 1 : 3);
    EXPECT_EQ(stats.low_rank_updates, low_rank ? 2 : 0);
    EXPECT_EQ(stats.low_rank_terms, low_rank ? 8 + 2 + 2 : 0);  // opened 8, slipping 2, locked 2 anew
    solutions.push_back(d);
  }
  for (std::size_t i = 0; i < solutions[0].size(); ++i)
    EXPECT_LT((solutions[1][i] - solutions[0][i]).norm(), 1e-10 * solutions[0][i].norm()) << "solve " << i;
}

TEST(DdaContacts, SpringLogGivesHowKChangedBetweenVersions) {
  // The spring terms logged between two assemblies of a step add up to the difference
  // of the two assembled K (a coupled model updates its K^-1 B with them,
  // docs/design_notes.md section 37); a new step's block terms end the log.
  const mesh::Mesh m = small_mesh(2, 2, 1.0, mesh::CellSplit::none);
  BlockSystem system(m, {Material{}}, alm_settings(25e9));
  system.add_fixed_point({0.0, 0.0});
  system.add_fixed_point({2.0, 0.0});
  system.add_point_load({0.0, 2.0}, {0.0, 1e6});
  system.begin_step(1.0);
  StepStatistics stats;
  system.assemble_and_factorise(stats);
  const int first = system.stiffness_version();
  const Eigen::MatrixXd k_first = Eigen::MatrixXd(system.stiffness().matrix()).selfadjointView<Eigen::Lower>();
  const Eigen::VectorXd d = system.solver().solve(system.contact_rhs());
  const auto [open_p, open_q] = system.joint_contacts(0);
  const int slipping = system.joint_contacts(1)[0];
  system.apply_state_changes(d, {ContactChange{open_p, ContactState::open, true}, ContactChange{open_q, ContactState::open, true}}, stats);
  system.assemble_and_factorise(stats);
  system.apply_state_changes(d, {ContactChange{slipping, ContactState::sliding, true, 1.0}}, stats);
  system.assemble_and_factorise(stats);
  EXPECT_EQ(system.stiffness_version(), first + 2);
  const Eigen::MatrixXd k_last = Eigen::MatrixXd(system.stiffness().matrix()).selfadjointView<Eigen::Lower>();
  std::vector<SpringTerm> changes;
  ASSERT_TRUE(system.spring_changes_since(first, changes));
  EXPECT_EQ(changes.size(), 8u + 2u);  // the opened joint's normal and shear terms, the slipping end's shear
  Eigen::MatrixXd k_sum = k_first;
  for (const SpringTerm& t : changes) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(k_first.rows());
    e.segment<6>(6 * t.block_a) += t.row_a.transpose();
    e.segment<6>(6 * t.block_b) += t.row_b.transpose();
    k_sum += t.stiffness * e * e.transpose();
  }
  EXPECT_LT((k_sum - k_last).norm(), 1e-12 * k_last.norm());
  EXPECT_GT((k_first - k_last).norm(), 1e-3 * k_last.norm());
  ASSERT_TRUE(system.spring_changes_since(first + 1, changes));
  EXPECT_EQ(changes.size(), 2u);
  EXPECT_FALSE(system.spring_changes_since(first - 1, changes));  // before the step's first K
  system.begin_step(1.0);
  system.assemble_and_factorise(stats);
  EXPECT_FALSE(system.spring_changes_since(first + 2, changes));  // the block terms changed
}

TEST(DdaFracture, BondFailsInTensionOnlyNextToAnOpenPressurisedJoint) {
  // Two rows of blocks bonded along y = 1; pulling the top apart breaks the bonds only
  // when rule (i) of seed 2.3 is satisfied.
  const mesh::Mesh m = small_mesh(2, 2, 1.0, mesh::CellSplit::none);
  for (bool rule : {true, false}) {
    fracture::FractureRules rules;
    rules.failure_needs_open_neighbour_and_fluid = rule;
    BlockSystem system(m, {Material{}}, alm_settings(25e9));
    system.add_fixed_point({0.0, 0.0});
    system.add_fixed_point({2.0, 0.0});
    system.add_point_load({0.0, 2.0}, {0.0, 1e6});
    system.add_point_load({2.0, 2.0}, {0.0, 1e6});
    step(system, 1.0, rules);
    int open = 0;
    for (const auto& c : system.contacts()) open += c.joint >= 0 && c.state == ContactState::open;
    if (rule)
      EXPECT_EQ(open, 0);  // no fluid anywhere: T0 = 0 bonds hold
    else
      EXPECT_GT(open, 0);
  }
}

}  // namespace
}  // namespace hfdda::dda
