#include "dda/block_system.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"

namespace hfdda::dda {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}
}  // namespace

BlockSystem::BlockSystem(const mesh::Mesh& mesh, std::vector<Material> materials, MechanicsSettings settings)
    : mesh_(mesh),
      materials_(std::move(materials)),
      settings_(settings),
      blocks_(mesh_, static_cast<int>(materials_.size())),
      contacts_(mesh_) {
  double coordinate_scale = 0.0;
  for (const Vec2& p : blocks_.corners) coordinate_scale = std::max(coordinate_scale, p.cwiseAbs().maxCoeff());
  gap_round_off_m_ = 16.0 * std::numeric_limits<double>::epsilon() * coordinate_scale;
  rebuild_pattern();
}

// ----------------------------------------------------------------------------------
// The step's frame: begin, factorise, commit or roll back

void BlockSystem::begin_step(double dt_s) {
  factor_of_this_step_ = false;  // the block terms change
  for (const auto& entry : assembled_terms_) terms_remembered_[entry.first] = 0;
  assembled_terms_.clear();
  logged_from_version_ = -1;
  contacts_.begin_step();
  for (auto& c : contacts_.all()) c.friction_normal_N = -1.0;
  update_block_geometry();
  assemble_block_terms(dt_s);
  linearise_contacts();
}

void BlockSystem::assemble_and_factorise(StepStatistics& stats) {
  auto start = Clock::now();
  assemble_contacts();
  log_spring_changes();
  stats.max_mechanism_blocks = std::max(stats.max_mechanism_blocks, static_cast<int>(held_blocks_.size()));
  stats.seconds_assembly += seconds_since(start);
  start = Clock::now();
  const bool modified = modify_factor(stats);
  stats.seconds_low_rank += seconds_since(start);
  if (modified) return;
  start = Clock::now();
  try {
    solver_.factorize(stiffness_.matrix());
  } catch (const ConvergenceError& e) {
    throw ConvergenceError(std::string(e.what()) + describe_unknown(solver_.failed_unknown()));
  }
  stats.seconds_factorization += seconds_since(start);
  ++stats.factorizations;
  factor_of_this_step_ = true;
  factorised_held_blocks_ = held_blocks_;
}

void BlockSystem::factorise_converged_response(StepStatistics& stats) {
  if (!settings_.converged_response()) throw std::logic_error("factorise_converged_response: the option is off");
  const double stiffening = settings_.converged_response_stiffening;
  auto start = Clock::now();
  stiffened_ = stiffness_;
  for (const auto& c : contacts_.all()) {
    if (c.state == ContactState::open || !iterated(c)) continue;
    const ContactTerms terms = contact_terms(c);  // the normal springs, and the shear ones when locked
    for (int k = 0; k < 4; ++k)
      if (terms.present[k])
        add_spring_term(stiffened_, c.springs[k / 2].slot, terms.term[k], (stiffening - 1.0) * terms.term[k].stiffness);
  }
  stats.seconds_assembly += seconds_since(start);
  start = Clock::now();
  stiffened_solver_.factorize(stiffened_.matrix());
  stats.seconds_factorization += seconds_since(start);
  ++stats.factorizations;
}

std::string BlockSystem::describe_unknown(int unknown) const {
  if (unknown < 0 || unknown >= 6 * n_blocks()) return "";
  static const char* const names[6] = {"x translation", "y translation", "rotation",
                                       "strain xx", "strain yy", "strain xy"};
  const int b = unknown / 6;
  const PolygonMoments& m = moments_[b];
  std::ostringstream where;
  where << " at the " << names[unknown % 6] << " of block " << b << " (centroid (" << m.centroid.x() << ", "
        << m.centroid.y() << ") m, signed area " << m.area << " m^2"
        << (m.area <= 0.0 ? ": the block is inverted" : "") << ", diagonal of K there "
        << stiffness_.matrix().coeff(unknown, unknown) << ")";
  return where.str();
}

void BlockSystem::commit(const Eigen::VectorXd& d, double dt_s, StepStatistics& stats) {
  for (int b = 0; b < n_blocks(); ++b) {
    const Vec6 db = d.segment<6>(6 * b);
    const Material& m = materials_[blocks_.material[b]];
    blocks_.stress[b] += plane_strain_elasticity(m.youngs_modulus_Pa, m.poissons_ratio) * db.tail<3>();
    for (int k = 0; k < n_corners(b); ++k) {
      Vec2& p = blocks_.corner(b, k);
      p += displacement_matrix(p, moments_[b].centroid) * db;
    }
    blocks_.velocity[b] = settings_.dynamic ? Vec6(2.0 / dt_s * db - blocks_.velocity[b]) : Vec6::Zero();
    blocks_.last_d[b] = db;
  }
  for (auto* list : {&loads_.fixed_points, &loads_.point_loads})
    for (auto& a : *list) a.position = displaced(a.block, a.position, d);
  for (const auto& c : contacts_.all()) stats.active_vertex_vertex += c.vertex_vertex_active;
  stats.max_active_vertex_vertex = stats.active_vertex_vertex;
  total_vv_activations_ += stats.vertex_vertex_activations;
}

void BlockSystem::roll_back() {
  contacts_.roll_back();
  rebuild_pattern();  // spring slots must point into the current pattern
}

// ----------------------------------------------------------------------------------
// Joint ends for coupled models

JointEndGap BlockSystem::joint_end_gap(int joint, int end) const {
  // Spring 0: corner of a against the edge of b; spring 1: corner of b against edge of a.
  const Contact& c = contacts_[2 * joint + end];
  const auto& s0 = c.springs[0];
  const auto& s1 = c.springs[1];
  JointEndGap g;
  g.block_a = s0.vertex_block;
  g.block_b = s0.edge_block;
  g.row_a = 0.5 * (s0.gap_vertex + s1.gap_edge);
  g.row_b = 0.5 * (s0.gap_edge + s1.gap_vertex);
  g.gap0_m = 0.5 * (s0.gap0 + s1.gap0);
  return g;
}

BlockSystem::FaceOverlap BlockSystem::largest_face_overlap(const Eigen::VectorXd& d) const {
  FaceOverlap worst;
  for (int j = 0; j < static_cast<int>(mesh_.joints.size()); ++j) {
    const mesh::Joint& joint = mesh_.joints[j];
    const double length = (mesh_.points[joint.point_q] - mesh_.points[joint.point_p]).norm();
    for (int end = 0; end < 2; ++end) {
      const JointEndGap g = joint_end_gap(j, end);
      const double overlap = -(g.gap0_m + g.row_a.dot(d.segment<6>(6 * g.block_a)) +
                               g.row_b.dot(d.segment<6>(6 * g.block_b)));
      if (overlap > worst.fraction_of_length * length) worst = {overlap, overlap / length, j, end};
    }
  }
  return worst;
}

double BlockSystem::largest_unbonded_tension_Pa(const Eigen::VectorXd& d) const {
  double largest = 0.0;
  for (int ci = 0; ci < contacts_.n_joint_contacts(); ++ci) {
    const Contact& c = contacts_[ci];
    if (c.state == ContactState::open || c.bonded || c.length_m <= 0.0) continue;
    StepStatistics unused;  // the query records nothing in the step's statistics
    largest = std::max(largest, trial_traction(c, d, unused).normal_N / c.length_m);  // tension positive
  }
  return largest;
}

BlockSystem::BlockStrain BlockSystem::largest_step_strain(const Eigen::VectorXd& d) const {
  BlockStrain worst;
  for (int b = 0; b < n_blocks(); ++b) {
    // Principal strains of (exx, eyy, gxy): centre +- radius of Mohr's circle.
    const double exx = d[6 * b + 3], eyy = d[6 * b + 4], gxy = d[6 * b + 5];
    const double radius = std::hypot(0.5 * (exx - eyy), 0.5 * gxy);
    const double largest = std::abs(0.5 * (exx + eyy)) + radius;
    if (worst.block < 0 || largest > worst.strain) worst = {largest, b};
  }
  return worst;
}

// ----------------------------------------------------------------------------------
// Queries at the committed state

double BlockSystem::joint_gap(int joint, int end) const {
  const Contact& c = contacts_[2 * joint + end];
  double gap = 0.0;
  for (int k = 0; k < c.n_springs; ++k) {
    const auto& s = c.springs[k];
    const Vec2 p1 = corner(s.vertex_block, s.vertex_corner);
    const Vec2 p2 = corner(s.edge_block, s.edge_corner);
    const Vec2 p3 = blocks_.next_corner(s.edge_block, s.edge_corner);
    gap += (p1 - p2).dot(outward_normal(p2, p3)) / c.n_springs;
  }
  return gap;
}

Vec2 BlockSystem::joint_end_separation(int joint, int end, const Eigen::VectorXd& d) const {
  // Block a runs the joint p -> q from corner_a, block b runs it q -> p from corner_b.
  const mesh::Joint& j = mesh_.joints[joint];
  const int corner_a = (j.corner_a + end) % n_corners(j.block_a);
  const int corner_b = (j.corner_b + 1 - end) % n_corners(j.block_b);
  auto moved = [&](int block, int local) {
    const Vec2 now = d.size() == 0 ? corner(block, local) : displaced(block, corner(block, local), d);
    return Vec2(now - initial_corner(block, local));
  };
  return moved(j.block_b, corner_b) - moved(j.block_a, corner_a);
}

std::pair<double, double> BlockSystem::contact_forces(int contact) const {
  const Contact& c = contacts_[contact];
  if (c.state == ContactState::open) return {0.0, 0.0};
  const double kn = normal_stiffness(c), ks = shear_stiffness(c);
  double normal = 0.0, shear = 0.0;
  const double w = 1.0 / c.n_springs;
  for (int k = 0; k < c.n_springs; ++k) {
    const auto& s = c.springs[k];
    const Vec2 p1 = corner(s.vertex_block, s.vertex_corner);
    const Vec2 p2 = corner(s.edge_block, s.edge_corner);
    const Vec2 p3 = blocks_.next_corner(s.edge_block, s.edge_corner);
    const Vec2 t = (p3 - p2).normalized();
    normal += w * (s.normal_multiplier_N + kn * (p1 - p2).dot(Vec2(t.y(), -t.x())));
    shear += w * (s.shear_multiplier_N + ks * (p1 - (p2 + s.reference_ratio * (p3 - p2))).dot(t));
  }
  if (c.state == ContactState::sliding)
    shear = c.friction_sign * (c.cohesion_Pa * c.length_m * c.bonded + std::max(-normal, 0.0) * c.tan_friction);
  return {normal, shear};
}

}  // namespace hfdda::dda
