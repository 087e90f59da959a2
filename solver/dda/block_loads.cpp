// Block terms and loads of a step: elasticity, inertia, initial stress, body force,
// fixed points, point loads, boundary tractions and joint pressures (seed 2.2, 2.4).

#include <limits>

#include "dda/block_system.hpp"

namespace hfdda::dda {

namespace {
// Two-point Gauss rule on [0, 1]: exact for the quadratic integrand T(s)^T p(s).
constexpr double kGaussPoint[2] = {0.5 - 0.28867513459481287, 0.5 + 0.28867513459481287};
}  // namespace

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
  loads_.fixed_points.push_back({block_containing(at), at, at, Vec2::Zero()});
}

void BlockSystem::add_point_load(const Vec2& at, const Vec2& force_N) {
  loads_.point_loads.push_back({block_containing(at), at, at, force_N});
}

void BlockSystem::add_boundary_stress(int boundary_edge, const Eigen::Matrix2d& stress_Pa) {
  loads_.boundary_stresses.push_back({boundary_edge, stress_Pa});
}

void BlockSystem::add_ramped_boundary_stress(int boundary_edge, const Eigen::Matrix2d& stress_per_Pa) {
  loads_.ramped_boundary_stresses.push_back({boundary_edge, stress_per_Pa});
}

void BlockSystem::set_in_situ_stress(const Eigen::Matrix2d& sigma) {
  for (auto& st : blocks_.stress) st = Eigen::Vector3d(sigma(0, 0), sigma(1, 1), sigma(0, 1));
  // Each joint end carries the traction of its half joint (trapezoidal rule, exact for
  // a uniform stress): normal force (n.sigma.n) Lc and shear force (t.sigma.n) Lc in
  // the spring's sign conventions (n: outward normal of the edge block, t along it).
  for (auto& c : contacts_.all()) {
    if (c.joint < 0 || c.state == ContactState::open) continue;
    for (int k = 0; k < c.n_springs; ++k) {
      auto& s = c.springs[k];
      const Vec2 p2 = corner(s.edge_block, s.edge_corner);
      const Vec2 p3 = blocks_.next_corner(s.edge_block, s.edge_corner);
      const Vec2 t = (p3 - p2).normalized();
      const Vec2 n(t.y(), -t.x());
      s.normal_multiplier_N = n.dot(sigma * n) * c.length_m;
      s.shear_multiplier_N = t.dot(sigma * n) * c.length_m;
    }
  }
}

void BlockSystem::update_block_geometry() {
  moments_.resize(n_blocks());
  for (int b = 0; b < n_blocks(); ++b) moments_[b] = polygon_moments(blocks_.corners_of(b));
}

void BlockSystem::assemble_block_terms(double dt_s) {
  const int nb = n_blocks();
  step_dt_s_ = dt_s;
  block_matrix_.resize(nb);
  step_loads_.setZero(6 * nb);
  for (int b = 0; b < nb; ++b) {
    const Material& m = materials_[blocks_.material[b]];
    const PolygonMoments& g = moments_[b];
    Mat6 k = Mat6::Zero();
    // Strain energy A/2 eps^T C eps (eq. 2.13-2.14).
    k.block<3, 3>(3, 3) = g.area * plane_strain_elasticity(m.youngs_modulus_Pa, m.poissons_ratio);
    // Inertia (2/dt^2) M with M = rho int T^T T dA: also keeps K definite for a free block.
    const Mat6 mass = m.density_kg_m3 * displacement_matrix_gram(g);
    k += (2.0 / (dt_s * dt_s)) * mass;
    block_matrix_[b] = k;
    auto f = step_loads_.segment<6>(6 * b);
    // Initial (accumulated) stress: potential A sigma^T eps gives F = -A sigma.
    f.segment<3>(3) -= g.area * blocks_.stress[b];
    if (settings_.dynamic) f += (2.0 / dt_s) * mass * blocks_.velocity[b];
    f.head<2>() += g.area * loads_.body_force;
  }
  add_attachment_loads();
}

void BlockSystem::add_attachment_loads() {
  const double kf = settings_.fixed_point_stiffness_N_m;
  for (const auto& fp : loads_.fixed_points) {
    const Mat26 t = displacement_matrix(fp.position, moments_[fp.block].centroid);
    block_matrix_[fp.block] += kf * t.transpose() * t;
    step_loads_.segment<6>(6 * fp.block) += kf * t.transpose() * (fp.anchor - fp.position);
  }
  for (const auto& pl : loads_.point_loads)
    step_loads_.segment<6>(6 * pl.block) +=
        displacement_matrix(pl.position, moments_[pl.block].centroid).transpose() * pl.force_N;
  auto add_traction = [&](const ExternalLoads::BoundaryStress& bs, double scale) {
    const auto& e = mesh_.boundary_edges[bs.boundary_edge];
    const Vec2 u = corner(e.block, e.corner), v = blocks_.next_corner(e.block, e.corner);
    // T is linear along the edge: the midpoint rule integrates T^T t exactly.
    const Mat26 t = displacement_matrix(0.5 * (u + v), moments_[e.block].centroid);
    step_loads_.segment<6>(6 * e.block) +=
        (v - u).norm() * t.transpose() * (scale * (bs.stress_Pa * outward_normal(u, v)));
  };
  for (const auto& bs : loads_.boundary_stresses) add_traction(bs, 1.0);
  for (const auto& bs : loads_.ramped_boundary_stresses) add_traction(bs, loads_.ramp_level_Pa);
}

void BlockSystem::add_joint_pressure_load(int j, double pressure_p_Pa, double pressure_q_Pa,
                                          Eigen::VectorXd& forces) const {
  // Fluid pressure on both faces of a joint, trapezoidal along each face (seed 2.4).
  const auto& joint = mesh_.joints[j];
  auto add_face = [&](int block, int start_corner, double p_start, double p_end) {
    const Vec2 u = corner(block, start_corner), v = blocks_.next_corner(block, start_corner);
    const Vec2 n = outward_normal(u, v);
    const double length = (v - u).norm();
    if (settings_.lumped_fluid_load) {
      // Trapezoidal rule: each end's pressure as a force L p / 2 at its corner, the load
      // work-conjugate to the network's lumped nodal volumes L w / 2 (seed 2.1), which
      // keeps d(volume)/d(pressure) symmetric (design notes section 19).
      const Vec2 c = moments_[block].centroid;
      forces.segment<6>(6 * block) += 0.5 * length * (displacement_matrix(u, c).transpose() * (-p_start * n) +
                                                      displacement_matrix(v, c).transpose() * (-p_end * n));
      return;
    }
    for (double s : kGaussPoint) {
      const double p = (1.0 - s) * p_start + s * p_end;
      const Mat26 t = displacement_matrix(u + s * (v - u), moments_[block].centroid);
      forces.segment<6>(6 * block) += 0.5 * length * t.transpose() * (-p * n);
    }
  };
  add_face(joint.block_a, joint.corner_a, pressure_p_Pa, pressure_q_Pa);  // a runs p -> q
  add_face(joint.block_b, joint.corner_b, pressure_q_Pa, pressure_p_Pa);  // b runs q -> p
}

}  // namespace hfdda::dda
