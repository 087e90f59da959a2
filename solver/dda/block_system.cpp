#include "dda/block_system.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <limits>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "core/errors.hpp"

namespace hfdda::dda {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Outward (right-hand) unit normal of an edge of a counter-clockwise polygon.
Vec2 outward_normal(const Vec2& from, const Vec2& to) {
  const Vec2 t = (to - from).normalized();
  return Vec2(t.y(), -t.x());
}

// Two-point Gauss rule on [0, 1]: exact for the quadratic integrand T(s)^T p(s).
constexpr double kGaussPoint[2] = {0.5 - 0.28867513459481287, 0.5 + 0.28867513459481287};

/// A contact flipping state this many times within one step is held in its state
/// (cycle detection, seed 5.1) so that the open-close iterations can settle.
constexpr int kMaxFlipsPerStep = 6;
/// Largest gap or shear left by stalled Augmented Lagrangian iterations (inconsistent
/// loops of closed contacts, see solve_alm), relative to the contact's length: 1e-6 is
/// well below the elastic strains of rock under stress (1e-4 at 2.5 MPa and 25 GPa).
constexpr double kAlmStallMismatch = 1.0e-6;

}  // namespace

BlockSystem::BlockSystem(const mesh::Mesh& mesh, std::vector<Material> materials, MechanicsSettings settings)
    : mesh_(mesh), materials_(std::move(materials)), settings_(settings) {
  const int nb = n_blocks();
  corner_offset_.assign(nb + 1, 0);
  for (int b = 0; b < nb; ++b) corner_offset_[b + 1] = corner_offset_[b] + static_cast<int>(mesh_.blocks[b].points.size());
  corners_.resize(corner_offset_[nb]);
  block_material_.resize(nb);
  for (int b = 0; b < nb; ++b) {
    const auto& block = mesh_.blocks[b];
    for (std::size_t k = 0; k < block.points.size(); ++k) corners_[corner_offset_[b] + k] = mesh_.points[block.points[k]];
    if (block.material < 0 || block.material >= static_cast<int>(materials_.size()))
      throw ModelError("block " + std::to_string(b) + " refers to material " + std::to_string(block.material) +
                       " but only " + std::to_string(materials_.size()) + " are defined");
    block_material_[b] = block.material;
  }
  initial_corners_ = corners_;
  double coordinate_scale = 0.0;
  for (const Vec2& p : corners_) coordinate_scale = std::max(coordinate_scale, p.cwiseAbs().maxCoeff());
  gap_round_off_m_ = 16.0 * std::numeric_limits<double>::epsilon() * coordinate_scale;
  stress_.assign(nb, Eigen::Vector3d::Zero());
  velocity_.assign(nb, Vec6::Zero());
  last_d_.assign(nb, Vec6::Zero());
  point_pressure_.assign(mesh_.points.size(), 0.0);
  point_pressurised_.assign(mesh_.points.size(), 0);
  joint_wetted_.assign(mesh_.joints.size(), 0);
  build_contacts();
}

// ----------------------------------------------------------------------------------
// Contact list (built once, seed 2.3 iv)

void BlockSystem::build_contacts() {
  const int n_joints = static_cast<int>(mesh_.joints.size());
  contacts_.clear();
  contacts_.reserve(2 * n_joints);
  couplings_.clear();
  couplings_.reserve(n_joints);

  auto n_of = [&](int b) { return static_cast<int>(mesh_.blocks[b].points.size()); };
  for (int j = 0; j < n_joints; ++j) {
    const mesh::Joint& joint = mesh_.joints[j];
    const int a = joint.block_a, b = joint.block_b;
    const int a_at_p = joint.corner_a, a_at_q = (joint.corner_a + 1) % n_of(a);
    const int b_at_q = joint.corner_b, b_at_p = (joint.corner_b + 1) % n_of(b);
    const double length = (mesh_.points[joint.point_q] - mesh_.points[joint.point_p]).norm();
    const auto& props = joint.properties;
    for (int end = 0; end < 2; ++end) {
      Contact c;
      c.joint = j;
      c.end = end;
      c.point = end == 0 ? joint.point_p : joint.point_q;
      c.n_springs = 2;
      // Symmetric pair (eq. 2.21): each block's corner against the other block's edge.
      // Edge a runs p -> q, edge b runs q -> p: the shared point sits at ratio 0 or 1.
      c.springs[0] = {a, end == 0 ? a_at_p : a_at_q, b, joint.corner_b};
      c.springs[0].reference_ratio = end == 0 ? 1.0 : 0.0;
      c.springs[1] = {b, end == 0 ? b_at_p : b_at_q, a, joint.corner_a};
      c.springs[1].reference_ratio = end == 0 ? 0.0 : 1.0;
      c.length_m = 0.5 * length;
      c.breakable = props.breakable;
      c.tensile_strength_Pa = props.tensile_strength_Pa;
      c.cohesion_Pa = props.cohesion_Pa;
      c.tan_friction = std::tan(props.friction_angle_rad);
      c.bonded = !props.initially_open;
      c.state = props.initially_open ? ContactState::open : ContactState::locked;
      contacts_.push_back(c);
    }
    couplings_.emplace_back(a, b);
  }

  // Vertex-vertex candidates: blocks sharing a point but no joint ending there.
  std::vector<std::vector<std::pair<int, int>>> blocks_at_point(mesh_.points.size());
  for (int b = 0; b < n_blocks(); ++b)
    for (int k = 0; k < n_of(b); ++k) blocks_at_point[mesh_.blocks[b].points[k]].emplace_back(b, k);
  std::set<std::tuple<int, int, int>> joined;  // (point, min block, max block)
  for (const auto& joint : mesh_.joints) {
    const int lo = std::min(joint.block_a, joint.block_b), hi = std::max(joint.block_a, joint.block_b);
    joined.emplace(joint.point_p, lo, hi);
    joined.emplace(joint.point_q, lo, hi);
  }
  for (int p = 0; p < static_cast<int>(blocks_at_point.size()); ++p) {
    const auto& around = blocks_at_point[p];
    for (std::size_t i = 0; i < around.size(); ++i)
      for (std::size_t k = i + 1; k < around.size(); ++k) {
        const auto [ba, ka] = around[i];
        const auto [bc, kc] = around[k];
        if (joined.count({p, std::min(ba, bc), std::max(ba, bc)})) continue;
        Contact c;
        c.point = p;
        c.n_springs = 1;
        c.state = ContactState::open;
        c.bonded = false;
        c.breakable = true;
        c.block_a = ba, c.corner_a = ka, c.block_c = bc, c.corner_c = kc;
        contacts_.push_back(c);
      }
  }
  // Vertex-vertex pairs enter K's pattern only once one activates: they would
  // otherwise multiply the off-diagonal blocks (and the fill) several times over.
  rebuild_pattern();

  // Joint contacts by point, for the propagation rule (seed 2.3 i).
  contacts_at_point_offset_.assign(mesh_.points.size() + 1, 0);
  for (int ci = 0; ci < 2 * n_joints; ++ci) ++contacts_at_point_offset_[contacts_[ci].point + 1];
  for (std::size_t p = 0; p < mesh_.points.size(); ++p) contacts_at_point_offset_[p + 1] += contacts_at_point_offset_[p];
  contacts_at_point_.assign(2 * n_joints, 0);
  std::vector<int> fill(contacts_at_point_offset_.begin(), contacts_at_point_offset_.end() - 1);
  for (int ci = 0; ci < 2 * n_joints; ++ci) contacts_at_point_[fill[contacts_[ci].point]++] = ci;
}

void BlockSystem::rebuild_pattern() {
  stiffness_ = BlockSparseMatrix(n_blocks(), couplings_);
  solver_.reset_pattern();
  for (auto& c : contacts_)
    if (c.joint >= 0 || c.vertex_vertex_active)
      for (int k = 0; k < c.n_springs; ++k)
        c.springs[k].slot = stiffness_.coupling_slot(c.springs[k].vertex_block, c.springs[k].edge_block);
  pattern_changed_ = false;
}

// ----------------------------------------------------------------------------------
// Loads and constraints

int BlockSystem::block_containing(const Vec2& p) const {
  double best_distance = std::numeric_limits<double>::max();
  int best = -1;
  for (int b = 0; b < n_blocks(); ++b) {
    const int n = n_corners(b);
    bool inside = true;
    double distance = std::numeric_limits<double>::max();
    for (int k = 0; k < n; ++k) {
      const Vec2 u = corner(b, k), v = corner(b, (k + 1) % n);
      if (cross2(u, v, p) < -1e-9 * (v - u).squaredNorm()) inside = false;
      distance = std::min(distance, point_segment_distance(p, u, v));
    }
    if (inside) return b;
    if (distance < best_distance) best_distance = distance, best = b;
  }
  return best;
}

void BlockSystem::add_fixed_point(const Vec2& at) {
  fixed_points_.push_back({block_containing(at), at, at, Vec2::Zero()});
}

void BlockSystem::add_point_load(const Vec2& at, const Vec2& force_N) {
  point_loads_.push_back({block_containing(at), at, at, force_N});
}

void BlockSystem::add_boundary_stress(int boundary_edge, const Eigen::Matrix2d& stress_Pa) {
  boundary_stresses_.push_back({boundary_edge, stress_Pa});
}

void BlockSystem::set_in_situ_stress(const Eigen::Matrix2d& sigma) {
  for (auto& st : stress_) st = Eigen::Vector3d(sigma(0, 0), sigma(1, 1), sigma(0, 1));
  // Each joint end carries the traction of its half joint (trapezoidal rule, exact for
  // a uniform stress): normal force (n.sigma.n) Lc and shear force (t.sigma.n) Lc in
  // the spring's sign conventions (n: outward normal of the edge block, t along it).
  for (auto& c : contacts_) {
    if (c.joint < 0 || c.state == ContactState::open) continue;
    for (int k = 0; k < c.n_springs; ++k) {
      auto& s = c.springs[k];
      const Vec2 p2 = corner(s.edge_block, s.edge_corner);
      const Vec2 p3 = corner(s.edge_block, (s.edge_corner + 1) % n_corners(s.edge_block));
      const Vec2 t = (p3 - p2).normalized();
      const Vec2 n(t.y(), -t.x());
      s.normal_multiplier_N = n.dot(sigma * n) * c.length_m;
      s.shear_multiplier_N = t.dot(sigma * n) * c.length_m;
    }
  }
}

void BlockSystem::set_fluid_pressure(std::vector<double> point_pressure_Pa, std::vector<char> joint_wetted) {
  if (point_pressure_Pa.size() != mesh_.points.size() || joint_wetted.size() != mesh_.joints.size())
    throw std::invalid_argument("set_fluid_pressure: sizes do not match the mesh");
  point_pressure_ = std::move(point_pressure_Pa);
  joint_wetted_ = std::move(joint_wetted);
  std::fill(point_pressurised_.begin(), point_pressurised_.end(), 0);
  for (std::size_t j = 0; j < mesh_.joints.size(); ++j) {
    if (!joint_wetted_[j]) continue;
    const auto& joint = mesh_.joints[j];
    if (point_pressure_[joint.point_p] > 0.0) point_pressurised_[joint.point_p] = 1;
    if (point_pressure_[joint.point_q] > 0.0) point_pressurised_[joint.point_q] = 1;
  }
}

// ----------------------------------------------------------------------------------
// Per-step block terms

void BlockSystem::update_block_geometry() {
  moments_.resize(n_blocks());
  for (int b = 0; b < n_blocks(); ++b)
    moments_[b] = polygon_moments(std::span<const Vec2>(corners_.data() + corner_offset_[b], n_corners(b)));
}

void BlockSystem::assemble_block_terms(double dt_s) {
  const int nb = n_blocks();
  block_matrix_.resize(nb);
  load_vector_.setZero(6 * nb);
  for (int b = 0; b < nb; ++b) {
    const Material& m = materials_[block_material_[b]];
    const PolygonMoments& g = moments_[b];
    Mat6 k = Mat6::Zero();
    // Strain energy A/2 eps^T C eps (eq. 2.13-2.14).
    k.block<3, 3>(3, 3) = g.area * plane_strain_elasticity(m.youngs_modulus_Pa, m.poissons_ratio);
    // Inertia (2/dt^2) M with M = rho int T^T T dA: also keeps K definite for a free block.
    const Mat6 mass = m.density_kg_m3 * displacement_matrix_gram(g);
    k += (2.0 / (dt_s * dt_s)) * mass;
    block_matrix_[b] = k;
    auto f = load_vector_.segment<6>(6 * b);
    // Initial (accumulated) stress: potential A sigma^T eps gives F = -A sigma.
    f.segment<3>(3) -= g.area * stress_[b];
    if (settings_.dynamic) f += (2.0 / dt_s) * mass * velocity_[b];
    f.head<2>() += g.area * body_force_;
  }
  const double kf = settings_.fixed_point_stiffness_N_m;
  for (const auto& fp : fixed_points_) {
    const Mat26 t = displacement_matrix(fp.position, moments_[fp.block].centroid);
    block_matrix_[fp.block] += kf * t.transpose() * t;
    load_vector_.segment<6>(6 * fp.block) += kf * t.transpose() * (fp.anchor - fp.position);
  }
  for (const auto& pl : point_loads_)
    load_vector_.segment<6>(6 * pl.block) += displacement_matrix(pl.position, moments_[pl.block].centroid).transpose() * pl.force_N;
  for (const auto& bs : boundary_stresses_) {
    const auto& e = mesh_.boundary_edges[bs.boundary_edge];
    const Vec2 u = corner(e.block, e.corner), v = corner(e.block, (e.corner + 1) % n_corners(e.block));
    // T is linear along the edge: the midpoint rule integrates T^T t exactly.
    const Mat26 t = displacement_matrix(0.5 * (u + v), moments_[e.block].centroid);
    load_vector_.segment<6>(6 * e.block) += (v - u).norm() * t.transpose() * (bs.stress_Pa * outward_normal(u, v));
  }
  // Fluid pressure on both faces of wetted joints, trapezoidal along each face (seed 2.4).
  for (std::size_t j = 0; j < mesh_.joints.size(); ++j) {
    if (!joint_wetted_[j]) continue;
    const auto& joint = mesh_.joints[j];
    add_joint_pressure_load(static_cast<int>(j), point_pressure_[joint.point_p], point_pressure_[joint.point_q],
                            load_vector_);
  }
}

void BlockSystem::add_joint_pressure_load(int j, double pressure_p_Pa, double pressure_q_Pa,
                                          Eigen::VectorXd& forces) const {
  const auto& joint = mesh_.joints[j];
  auto add_face = [&](int block, int start_corner, double p_start, double p_end) {
    const Vec2 u = corner(block, start_corner), v = corner(block, (start_corner + 1) % n_corners(block));
    const Vec2 n = outward_normal(u, v);
    const double length = (v - u).norm();
    for (double s : kGaussPoint) {
      const double p = (1.0 - s) * p_start + s * p_end;
      const Mat26 t = displacement_matrix(u + s * (v - u), moments_[block].centroid);
      forces.segment<6>(6 * block) += 0.5 * length * t.transpose() * (-p * n);
    }
  };
  add_face(joint.block_a, joint.corner_a, pressure_p_Pa, pressure_q_Pa);  // a runs p -> q
  add_face(joint.block_b, joint.corner_b, pressure_q_Pa, pressure_p_Pa);  // b runs q -> p
}

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

// ----------------------------------------------------------------------------------
// Contact springs

void BlockSystem::linearise_spring(VertexEdgeSpring& s) const {
  linearise_vertex_edge(corner(s.vertex_block, s.vertex_corner), corner(s.edge_block, s.edge_corner),
                        corner(s.edge_block, (s.edge_corner + 1) % n_corners(s.edge_block)),
                        moments_[s.vertex_block].centroid, moments_[s.edge_block].centroid, s);
}

void BlockSystem::linearise_contacts() {
  for (auto& c : contacts_) {
    if (c.joint < 0 && !c.vertex_vertex_active) continue;
    for (int k = 0; k < c.n_springs; ++k) linearise_spring(c.springs[k]);
  }
}

void BlockSystem::assemble_contacts() {
  stiffness_.set_zero();
  for (int b = 0; b < n_blocks(); ++b) stiffness_.add_diagonal(b, block_matrix_[b]);
  const double kn = settings_.normal_stiffness_N_m, ks = settings_.shear_stiffness_N_m;
  for (const auto& c : contacts_) {
    if (c.state == ContactState::open) continue;
    const double w = 1.0 / c.n_springs;
    for (int k = 0; k < c.n_springs; ++k) {
      const auto& s = c.springs[k];
      auto add = [&](double stiffness, const Row6& ev, const Row6& ee) {
        stiffness_.add_diagonal(s.vertex_block, w * stiffness * ev.transpose() * ev);
        stiffness_.add_diagonal(s.edge_block, w * stiffness * ee.transpose() * ee);
        stiffness_.add_coupling(s.slot, s.vertex_block, s.edge_block, w * stiffness * ev.transpose() * ee);
      };
      add(kn, s.gap_vertex, s.gap_edge);
      if (c.state == ContactState::locked) add(ks, s.shear_vertex, s.shear_edge);
    }
  }
}

double BlockSystem::spring_gap(const VertexEdgeSpring& s, const Eigen::VectorXd& d) const {
  return s.gap0 + s.gap_vertex.dot(d.segment<6>(6 * s.vertex_block)) + s.gap_edge.dot(d.segment<6>(6 * s.edge_block));
}

double BlockSystem::spring_shear(const VertexEdgeSpring& s, const Eigen::VectorXd& d) const {
  return s.shear0 + s.shear_vertex.dot(d.segment<6>(6 * s.vertex_block)) +
         s.shear_edge.dot(d.segment<6>(6 * s.edge_block));
}

void BlockSystem::add_spring_to_rhs(const VertexEdgeSpring& s, double weight, double force_normal, double force_shear,
                                    bool normal, bool shear) {
  // Pi = w (lambda g + k/2 g^2) with g = g0 + e.D gives F -= w (lambda + k g0) e^T.
  auto fv = load_vector_.segment<6>(6 * s.vertex_block);
  auto fe = load_vector_.segment<6>(6 * s.edge_block);
  if (normal) {
    fv -= weight * force_normal * s.gap_vertex.transpose();
    fe -= weight * force_normal * s.gap_edge.transpose();
  }
  if (shear) {
    fv -= weight * force_shear * s.shear_vertex.transpose();
    fe -= weight * force_shear * s.shear_edge.transpose();
  }
}

Eigen::VectorXd BlockSystem::solve_alm(StepStatistics& stats) {
  const double kn = settings_.normal_stiffness_N_m, ks = settings_.shear_stiffness_N_m;
  const Eigen::VectorXd block_loads = load_vector_;
  Eigen::VectorXd d, d_previous;
  double displacement_change = 0.0;
  const int max_iterations = settings_.augmented_lagrangian ? settings_.max_alm_iterations : 1;
  double error = 0.0, scale = 0.0;
  int worst_contact = -1;
  // Per contact: k g and k s of its mean gap and shear [N], the multiplier update of
  // this iteration and of the last (for the stall test).
  std::vector<double>& correction = alm_corrections_;
  std::vector<double>& previous = alm_previous_corrections_;
  correction.assign(2 * contacts_.size(), 0.0);
  previous.assign(2 * contacts_.size(), 0.0);
  for (int it = 0; it < max_iterations; ++it) {
    load_vector_ = block_loads;
    for (const auto& c : contacts_) {
      if (c.state == ContactState::open) continue;
      const double w = 1.0 / c.n_springs;
      // Sliding: constant friction force opposing slip (Mohr-Coulomb limit) instead of a shear spring.
      double friction = 0.0;
      if (c.state == ContactState::sliding) {
        double normal = 0.0;
        for (int k = 0; k < c.n_springs; ++k) normal += w * (c.springs[k].normal_multiplier_N + kn * c.springs[k].gap0);
        friction = c.friction_sign * (c.cohesion_Pa * c.length_m * c.bonded + std::max(-normal, 0.0) * c.tan_friction);
      }
      for (int k = 0; k < c.n_springs; ++k) {
        const auto& s = c.springs[k];
        const bool locked = c.state == ContactState::locked;
        add_spring_to_rhs(s, w, s.normal_multiplier_N + kn * s.gap0,
                          locked ? s.shear_multiplier_N + ks * s.shear0 : friction, true, true);
      }
    }
    const auto start = Clock::now();
    d_previous.swap(d);
    d = solver_.solve(load_vector_);
    if (coupling_) d = coupling_->solve(*this, solver_, d);
    stats.seconds_solve += seconds_since(start);
    ++stats.alm_iterations;
    if (!settings_.augmented_lagrangian) break;
    // ||D(m+1) - D(m)|| / ||D(m+1)|| of the inner iterations (NOTES erratum 2), reported.
    const double d_norm = d.norm();
    displacement_change = it == 0 || d_norm == 0.0 ? 0.0 : (d - d_previous).norm() / d_norm;

    // Uzawa update of the multipliers (eq. 2.19); stop when the corrections are
    // negligible against the contact forces themselves. A contact is one normal and
    // one shear constraint: its springs (one per orientation at a joint end) are driven
    // by their mean gap and mean shear. Once the two faces meet at an angle, the two
    // springs' own gaps or shears differ by a geometric offset that no displacement
    // removes, and per-spring updates would pull them apart for ever.
    error = 0.0, scale = 0.0;
    previous.swap(correction);
    double change = 0.0;    // largest change of a correction since the last iteration [N]
    double mismatch = 0.0;  // largest |gap| or |shear| over the contact's length
    for (const auto& c : contacts_) {
      if (c.state == ContactState::open) continue;
      const double w = 1.0 / c.n_springs;
      const double error_before = error;
      double gap = 0.0, shear = 0.0;
      for (int k = 0; k < c.n_springs; ++k) {
        const auto& s = c.springs[k];
        gap += w * spring_gap(s, d);
        scale = std::max(scale, std::abs(s.normal_multiplier_N));
        if (c.state == ContactState::locked) {
          shear += w * spring_shear(s, d);
          scale = std::max(scale, std::abs(s.shear_multiplier_N));
        }
      }
      error = std::max({error, std::abs(kn * gap), std::abs(ks * shear)});
      const double length = c.joint >= 0 ? c.length_m : c.springs[0].edge_length_m;
      mismatch = std::max(mismatch, std::max(std::abs(gap), std::abs(shear)) / length);
      const int ci = static_cast<int>(&c - contacts_.data());
      if (error > error_before) worst_contact = ci;
      correction[2 * ci] = kn * gap;
      correction[2 * ci + 1] = ks * shear;
      change = std::max({change, std::abs(correction[2 * ci] - previous[2 * ci]),
                         std::abs(correction[2 * ci + 1] - previous[2 * ci + 1])});
    }
    // Gaps cannot be resolved below the round-off of the coordinates they come from.
    const double round_off_force = std::max(kn, ks) * gap_round_off_m_;
    if (error <= settings_.alm_force_tolerance * scale + round_off_force) break;
    // Stalled: the corrections no longer change, so the multiplier updates no longer
    // move the blocks. Around a point where every joint is closed, the contacts form a
    // loop of constraints; once some of them slipped and re-locked, the rotations of
    // the blocks leave their reference points inconsistent by a few nanometres, and no
    // displacement closes every gap. The remaining gaps are that geometric mismatch:
    // accept them if they are small against the contacts' lengths (kAlmStallMismatch),
    // and count the stall and its mismatch.
    if (it > 0 && change <= settings_.alm_force_tolerance * scale + round_off_force &&
        mismatch <= kAlmStallMismatch) {
      ++stats.alm_stalls;
      stats.max_alm_stall_mismatch = std::max(stats.max_alm_stall_mismatch, mismatch);
      break;
    }
    for (auto& c : contacts_) {
      if (c.state == ContactState::open) continue;
      const int ci = static_cast<int>(&c - contacts_.data());
      for (int k = 0; k < c.n_springs; ++k) {
        c.springs[k].normal_multiplier_N += correction[2 * ci];
        c.springs[k].shear_multiplier_N += correction[2 * ci + 1];  // 0 unless locked
      }
    }
    if (it + 1 == max_iterations) {
      load_vector_ = block_loads;
      std::ostringstream msg;
      msg << "Augmented Lagrangian iterations did not converge in " << max_iterations
          << " iterations: largest spring force correction " << error << " N against contact forces of "
          << scale << " N (tolerance " << settings_.alm_force_tolerance << ")";
      if (worst_contact >= 0) {
        const Contact& c = contacts_[worst_contact];
        const Vec2& at = mesh_.points[c.point];
        msg << "; largest at the " << to_string(c.state) << " contact of joint " << c.joint << " at point "
            << c.point << " (" << at.x() << ", " << at.y() << ") m";
      }
      throw ConvergenceError(msg.str());
    }
  }
  load_vector_ = block_loads;
  stats.max_alm_displacement_change = std::max(stats.max_alm_displacement_change, displacement_change);
  return d;
}

// ----------------------------------------------------------------------------------
// Open-close checks

Vec2 BlockSystem::displaced(int block, const Vec2& p, const Eigen::VectorXd& d) const {
  return p + displacement_matrix(p, moments_[block].centroid) * d.segment<6>(6 * block);
}

void BlockSystem::reset_shear_reference(VertexEdgeSpring& s, const Eigen::VectorXd& d) const {
  // New reference = where the corner projects on the edge now: no shear at locking.
  const Vec2 p1 = displaced(s.vertex_block, corner(s.vertex_block, s.vertex_corner), d);
  const Vec2 p2 = displaced(s.edge_block, corner(s.edge_block, s.edge_corner), d);
  const Vec2 p3 = displaced(s.edge_block, corner(s.edge_block, (s.edge_corner + 1) % n_corners(s.edge_block)), d);
  // Not clamped to the edge: a corner that closes just beyond the end of the edge (a
  // joint end after opening) would otherwise start with a shear offset.
  s.reference_ratio = (p1 - p2).dot(p3 - p2) / (p3 - p2).squaredNorm();
  s.shear_multiplier_N = 0.0;
}

bool BlockSystem::may_fail(const Contact& c) const {
  if (!c.breakable) return false;
  if (!settings_.failure_needs_open_neighbour_and_fluid) return true;
  // Seed 2.3 (i): next to an open contact of the same joint or at the same point, and
  // next to a pressurised point.
  if (c.joint < 0) return true;
  const auto& joint = mesh_.joints[c.joint];
  const int other_point = c.end == 0 ? joint.point_q : joint.point_p;
  const std::vector<char>& pressurised = coupling_ ? coupling_->pressurised_points() : point_pressurised_;
  if (!pressurised[c.point] && !pressurised[other_point]) return false;
  const Contact& other_end = contacts_[2 * c.joint + (1 - c.end)];
  if (other_end.state == ContactState::open) return true;
  for (int k = contacts_at_point_offset_[c.point]; k < contacts_at_point_offset_[c.point + 1]; ++k) {
    const Contact& n = contacts_[contacts_at_point_[k]];
    if (&n != &c && n.state == ContactState::open) return true;
  }
  return false;
}

bool BlockSystem::joined_by_closed_joints(int point, int block_a, int block_c,
                                          const std::vector<ContactState>& joint_state) const {
  // Breadth-first search over the blocks around the point (at most a dozen).
  std::array<int, 32> reached{};
  int n_reached = 0, next = 0;
  reached[n_reached++] = block_a;
  while (next < n_reached) {
    const int from = reached[next++];
    for (int k = contacts_at_point_offset_[point]; k < contacts_at_point_offset_[point + 1]; ++k) {
      const Contact& j = contacts_[contacts_at_point_[k]];
      if (joint_state[contacts_at_point_[k]] == ContactState::open) continue;
      const int a = j.springs[0].vertex_block, b = j.springs[0].edge_block;
      const int to = a == from ? b : b == from ? a : -1;
      if (to < 0 || std::find(reached.begin(), reached.begin() + n_reached, to) != reached.begin() + n_reached) continue;
      if (to == block_c) return true;
      if (n_reached == static_cast<int>(reached.size())) return false;
      reached[n_reached++] = to;
    }
  }
  return false;
}

std::optional<VertexEdgeSpring> BlockSystem::vertex_vertex_spring(const Contact& c, const Eigen::VectorXd& d,
                                                                   double& max_penetration) const {
  // Depth of a corner inside the other block's angle at the shared point: the smaller
  // of its distances behind the two edges meeting there (the way out of the block).
  auto try_orientation = [&](int vb, int vc, int eb, int ec) -> std::optional<VertexEdgeSpring> {
    const int n = n_corners(eb);
    const Vec2 p = displaced(vb, corner(vb, vc), d);
    const Vec2 here = displaced(eb, corner(eb, ec), d);
    const Vec2 next = displaced(eb, corner(eb, (ec + 1) % n), d);
    const Vec2 prev = displaced(eb, corner(eb, (ec + n - 1) % n), d);
    const double d_next = (p - here).dot(outward_normal(here, next));   // edge ec -> ec+1
    const double d_prev = (p - prev).dot(outward_normal(prev, here));   // edge ec-1 -> ec
    if (d_next >= 0.0 || d_prev >= 0.0) return std::nullopt;
    const double depth = std::min(-d_next, -d_prev);
    max_penetration = std::max(max_penetration, depth);
    if (depth <= settings_.vertex_vertex_activation_m) return std::nullopt;
    VertexEdgeSpring s;
    s.vertex_block = vb, s.vertex_corner = vc, s.edge_block = eb;
    s.edge_corner = -d_next < -d_prev ? ec : (ec + n - 1) % n;  // the nearer edge is the reference line
    return s;
  };
  if (auto s = try_orientation(c.block_a, c.corner_a, c.block_c, c.corner_c)) return s;
  return try_orientation(c.block_c, c.corner_c, c.block_a, c.corner_a);
}

int BlockSystem::update_states(const Eigen::VectorXd& d, StepStatistics& stats) {
  const double kn = settings_.normal_stiffness_N_m, ks = settings_.shear_stiffness_N_m;
  struct Change {
    int contact;
    ContactState to;
    bool breaks_bond;
    std::optional<VertexEdgeSpring> vertex_vertex;  // spring of an activated vertex-vertex contact
  };
  std::vector<Change> changes;
  std::vector<std::pair<double, int>> tension_failures;  // (normal stress, contact)

  // Joint contacts and active vertex-vertex springs: the open-close rules.
  auto check_contact = [&](int ci) {
    Contact& c = contacts_[ci];
    const double w = 1.0 / c.n_springs;
    double gap = 0.0, normal = 0.0, shear = 0.0;
    for (int k = 0; k < c.n_springs; ++k) {
      const auto& s = c.springs[k];
      const double g = spring_gap(s, d);
      gap += w * g;
      normal += w * (s.normal_multiplier_N + kn * g);
      shear += w * (s.shear_multiplier_N + ks * spring_shear(s, d));
    }
    stats.max_penetration_m = std::max(stats.max_penetration_m, -gap);
    const double friction_limit = std::max(-normal, 0.0) * c.tan_friction;
    switch (c.state) {
      case ContactState::open:
        if (gap < 0.0) changes.push_back({ci, ContactState::locked, false, std::nullopt});
        break;
      case ContactState::locked:
        if (c.bonded) {
          if (normal > c.tensile_strength_Pa * c.length_m) {
            if (may_fail(c)) tension_failures.emplace_back(normal / c.length_m, ci);
          } else if (settings_.shear_failure_of_intact_joints &&
                     std::abs(shear) > c.cohesion_Pa * c.length_m + friction_limit && may_fail(c)) {
            c.friction_sign = shear >= 0.0 ? 1.0 : -1.0;
            changes.push_back({ci, ContactState::sliding, true, std::nullopt});
          }
        } else if (normal > 0.0) {
          changes.push_back({ci, ContactState::open, false, std::nullopt});
        } else if (std::abs(shear) > friction_limit) {
          c.friction_sign = shear >= 0.0 ? 1.0 : -1.0;
          changes.push_back({ci, ContactState::sliding, false, std::nullopt});
        }
        break;
      case ContactState::sliding: {
        // Slip since locking, in the sense of the friction force; reversal re-locks.
        double slip = 0.0;
        for (int k = 0; k < c.n_springs; ++k) slip += w * spring_shear(c.springs[k], d);
        if (normal > 0.0)
          changes.push_back({ci, ContactState::open, false, std::nullopt});
        else if (c.joint >= 0 && slip * c.friction_sign < 0.0)
          changes.push_back({ci, ContactState::locked, false, std::nullopt});
        break;
      }
    }
  };
  const int n_joint_contacts = 2 * static_cast<int>(mesh_.joints.size());
  for (int ci = 0; ci < n_joint_contacts; ++ci) check_contact(ci);

  // Seed 2.3 (iii): of the bonds over their tensile strength, only the most stressed
  // fails (all within the tie tolerance of it fail together).
  if (!tension_failures.empty()) {
    const double top = std::max_element(tension_failures.begin(), tension_failures.end())->first;
    for (auto [stress, ci] : tension_failures)
      if (stress >= top - settings_.tie_tolerance * std::abs(top)) changes.push_back({ci, ContactState::open, true, std::nullopt});
  }

  // Vertex-vertex contacts (frictionless normal springs, state "sliding") come last,
  // judged on the joint states this round leads to. With the Augmented Lagrangian, two
  // blocks joined at the point by a chain of closed joint contacts cannot penetrate
  // each other there (the wedges between them are in contact and their gaps are driven
  // to zero): a vertex-vertex spring would be a redundant constraint with its own
  // geometric offset, which the iterations cannot satisfy. With penalty springs the
  // joints do overlap, and the seed's vertex-vertex springs (3.1) stay.
  next_joint_state_.resize(n_joint_contacts);
  for (int ci = 0; ci < n_joint_contacts; ++ci) next_joint_state_[ci] = contacts_[ci].state;
  for (const Change& ch : changes) next_joint_state_[ch.contact] = ch.to;
  for (int ci = n_joint_contacts; ci < static_cast<int>(contacts_.size()); ++ci) {
    Contact& c = contacts_[ci];
    const bool joined = settings_.augmented_lagrangian &&
                        joined_by_closed_joints(c.point, c.block_a, c.block_c, next_joint_state_);
    if (!c.vertex_vertex_active) {
      if (!joined)
        if (auto s = vertex_vertex_spring(c, d, stats.max_penetration_m))
          changes.push_back({ci, ContactState::sliding, false, s});
    } else if (joined) {
      changes.push_back({ci, ContactState::open, false, std::nullopt});
    } else {
      check_contact(ci);
    }
  }

  int applied = 0;
  last_change_.clear();
  for (const Change& ch : changes) {
    Contact& c = contacts_[ch.contact];
    if (last_change_.empty()) {
      const Vec2& at = mesh_.points[c.point];
      std::ostringstream where;
      where << (c.joint >= 0 ? "joint " + std::to_string(c.joint) : std::string("vertex-vertex contact")) << " at ("
            << at.x() << ", " << at.y() << "): " << to_string(c.state) << " -> " << to_string(ch.to);
      last_change_ = where.str();
    }
    // Cycle detection: a contact that keeps flipping keeps its state for this step.
    if (++flips_[ch.contact] > kMaxFlipsPerStep && !ch.breaks_bond) continue;
    ++applied;
    if (ch.breaks_bond) {
      c.bonded = false;
      ++stats.bonds_broken;
    }
    if (ch.vertex_vertex) {
      c.springs[0] = *ch.vertex_vertex;
      if (!c.ever_active) {  // first activation: its block pair joins K's pattern
        couplings_.emplace_back(c.block_a, c.block_c);
        c.ever_active = true;
        pattern_changed_ = true;
      }
      c.vertex_vertex_active = true;
      c.friction_sign = 0.0;
      ++stats.vertex_vertex_activations;
    }
    if (c.joint < 0 && ch.to == ContactState::open) c.vertex_vertex_active = false;
    c.state = ch.to;
    for (int k = 0; k < c.n_springs; ++k) {
      auto& s = c.springs[k];
      if (ch.to == ContactState::open) {
        s.normal_multiplier_N = s.shear_multiplier_N = 0.0;
      } else {
        reset_shear_reference(s, d);  // slip and shear are measured from the closing point
        linearise_spring(s);
      }
    }
  }
  if (pattern_changed_) rebuild_pattern();
  stats.state_changes += applied;
  return applied;
}

// ----------------------------------------------------------------------------------
// The step

StepStatistics BlockSystem::step(double dt_s, StepCoupling* coupling) {
  const auto step_start = Clock::now();
  StepStatistics stats;
  const std::vector<Contact> contacts_at_start = contacts_;
  flips_.assign(contacts_.size(), 0);
  coupling_ = coupling;
  try {
    auto start = Clock::now();
    update_block_geometry();
    assemble_block_terms(dt_s);
    linearise_contacts();
    if (coupling_) coupling_->begin_step(*this, dt_s);
    stats.seconds_assembly += seconds_since(start);
    bool stiffness_changed = true;
    for (int oc = 1; oc <= settings_.max_open_close_iterations; ++oc) {
      stats.open_close_iterations = oc;
      if (stiffness_changed) {
        start = Clock::now();
        assemble_contacts();
        stats.seconds_assembly += seconds_since(start);
        start = Clock::now();
        solver_.factorize(stiffness_.matrix());
        stats.seconds_factorization += seconds_since(start);
        ++stats.factorizations;
      }
      if (coupling_) {
        start = Clock::now();
        coupling_->prepare(*this, solver_, stiffness_changed);
        stats.seconds_solve += seconds_since(start);
      }
      const Eigen::VectorXd d = solve_alm(stats);
      const int contact_changes = update_states(d, stats);
      const int coupled_changes = coupling_ ? coupling_->update_states(*this) : 0;
      stats.coupled_state_changes += coupled_changes;
      if (contact_changes + coupled_changes == 0) {
        commit(d, dt_s);
        if (coupling_) coupling_->commit(*this);
        coupling_ = nullptr;
        for (const auto& c : contacts_) stats.active_vertex_vertex += c.vertex_vertex_active;
        stats.max_active_vertex_vertex = stats.active_vertex_vertex;
        total_vv_activations_ += stats.vertex_vertex_activations;
        stats.seconds_total = seconds_since(step_start);
        return stats;
      }
      stiffness_changed = contact_changes > 0;
    }
    std::ostringstream msg;
    msg << "open-close iterations did not converge in " << settings_.max_open_close_iterations
        << " iterations: contacts still changing state, e.g. " << last_change_;
    throw ConvergenceError(msg.str());
  } catch (...) {
    contacts_ = contacts_at_start;
    rebuild_pattern();  // spring slots must point into the current pattern
    if (coupling_) coupling_->abort();
    coupling_ = nullptr;
    throw;
  }
}

void BlockSystem::commit(const Eigen::VectorXd& d, double dt_s) {
  for (int b = 0; b < n_blocks(); ++b) {
    const Vec6 db = d.segment<6>(6 * b);
    const Material& m = materials_[block_material_[b]];
    stress_[b] += plane_strain_elasticity(m.youngs_modulus_Pa, m.poissons_ratio) * db.tail<3>();
    for (int k = 0; k < n_corners(b); ++k) {
      Vec2& p = corners_[corner_offset_[b] + k];
      p += displacement_matrix(p, moments_[b].centroid) * db;
    }
    velocity_[b] = settings_.dynamic ? Vec6(2.0 / dt_s * db - velocity_[b]) : Vec6::Zero();
    last_d_[b] = db;
  }
  for (auto* list : {&fixed_points_, &point_loads_})
    for (auto& a : *list) a.position = displaced(a.block, a.position, d);
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
    const Vec2 p3 = corner(s.edge_block, (s.edge_corner + 1) % n_corners(s.edge_block));
    gap += (p1 - p2).dot(outward_normal(p2, p3)) / c.n_springs;
  }
  return gap;
}

std::pair<double, double> BlockSystem::contact_forces(int contact) const {
  const Contact& c = contacts_[contact];
  if (c.state == ContactState::open) return {0.0, 0.0};
  const double kn = settings_.normal_stiffness_N_m, ks = settings_.shear_stiffness_N_m;
  double normal = 0.0, shear = 0.0;
  const double w = 1.0 / c.n_springs;
  for (int k = 0; k < c.n_springs; ++k) {
    const auto& s = c.springs[k];
    const Vec2 p1 = corner(s.vertex_block, s.vertex_corner);
    const Vec2 p2 = corner(s.edge_block, s.edge_corner);
    const Vec2 p3 = corner(s.edge_block, (s.edge_corner + 1) % n_corners(s.edge_block));
    const Vec2 t = (p3 - p2).normalized();
    normal += w * (s.normal_multiplier_N + kn * (p1 - p2).dot(Vec2(t.y(), -t.x())));
    shear += w * (s.shear_multiplier_N + ks * (p1 - (p2 + s.reference_ratio * (p3 - p2))).dot(t));
  }
  if (c.state == ContactState::sliding)
    shear = c.friction_sign * (c.cohesion_Pa * c.length_m * c.bonded + std::max(-normal, 0.0) * c.tan_friction);
  return {normal, shear};
}

}  // namespace hfdda::dda
