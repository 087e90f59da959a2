#pragma once
// Block contacts of the DDA (seed section 2.3, docs/formulation.md section 3).
//
// Every joint (edge shared by two blocks) gives two contacts, one at each end. A
// joint-end contact carries the seed's symmetric pair of vertex-edge springs
// (eqs. 2.21-2.22): the corner of block a against the edge of block b and the corner
// of block b against the edge of block a, each spring with weight 1/2, so the
// contact force is the mean of the two spring forces. Blocks meeting only at a point
// give vertex-vertex candidates that become one-spring contacts only once a corner
// penetrates the other block by more than a tolerance (seed 2.3 vi).
//
// Sign conventions: gap g > 0 is separation; spring forces N = lambda + k g are
// tension positive; the ALM multipliers lambda carry the contact forces between
// iterations and steps (seed eq. 2.19).

#include <array>
#include <cstdint>
#include <vector>

#include "dda/block_kinematics.hpp"

namespace hfdda::dda {

enum class ContactState : std::uint8_t { open = 0, sliding = 1, locked = 2 };

const char* to_string(ContactState state);

/// Corner `vertex_corner` of `vertex_block` against the edge of `edge_block` that
/// starts at its corner `edge_corner` (counter-clockwise, so its outward normal is
/// the right-hand normal of the edge direction).
struct VertexEdgeSpring {
  int vertex_block = -1, vertex_corner = -1;
  int edge_block = -1, edge_corner = -1;
  int slot = -1;                      ///< coupling slot of (vertex_block, edge_block) in K
  double reference_ratio = 0.0;       ///< shear reference point on the edge's line (0, 1: its ends)
  double normal_multiplier_N = 0.0;   ///< ALM normal force, tension positive [N per m thickness]
  double shear_multiplier_N = 0.0;    ///< ALM shear force [N per m thickness]

  // Linearisation about the geometry at the start of the step:
  //   g(D) = gap0 + gap_vertex . D_vertex + gap_edge . D_edge      (normal gap)
  //   s(D) = shear0 + shear_vertex . D_vertex + shear_edge . D_edge (shear displacement)
  double gap0 = 0.0, shear0 = 0.0;
  Row6 gap_vertex = Row6::Zero(), gap_edge = Row6::Zero();
  Row6 shear_vertex = Row6::Zero(), shear_edge = Row6::Zero();
  double edge_length_m = 0.0;
};

struct Contact {
  int joint = -1;          ///< joint id; -1 for a vertex-vertex contact
  int end = 0;             ///< joint end: 0 at the joint's point p, 1 at point q
  int point = -1;          ///< geometric point where the contact sits
  int n_springs = 2;       ///< 2 for a joint end, 1 for an active vertex-vertex contact
  std::array<VertexEdgeSpring, 2> springs;
  double length_m = 0.0;   ///< contact length Lc (half the joint length)
  ContactState state = ContactState::locked;
  bool bonded = true;      ///< bond intact: T0 and C0 act (its strength: fracture/)
  double cohesion_Pa = 0.0, tan_friction = 0.0;  ///< of the sliding law (C0 while bonded)
  double friction_sign = 1.0;  ///< sense of the sliding friction force
  /// Compressive normal force [N per m thickness] that the friction of a sliding contact
  /// with held springs (penalty, or two-tier's unbonded contacts) acts with: the normal
  /// force at the last contact iterate (eq. 2.16 at the step's solution). Negative until
  /// the first iterate in this state: the normal force at the step's start.
  double friction_normal_N = -1.0;

  // Vertex-vertex candidates only: the two blocks and their corners at `point`.
  bool vertex_vertex_active = false;
  bool ever_active = false;  ///< its block pair is in K's pattern
  int block_a = -1, corner_a = -1, block_c = -1, corner_c = -1;
};

/// Fills the spring's gap0/shear0 and their gradients for corner p1 of the vertex
/// block against edge p2 -> p3 of the edge block (current geometry, centroids of the
/// two blocks). The gap is twice the signed area of (p1, p2, p3) over the edge length,
/// linearised in the motion of all three points with the length held (Shi 1988).
void linearise_vertex_edge(const Vec2& p1, const Vec2& p2, const Vec2& p3, const Vec2& vertex_centroid,
                           const Vec2& edge_centroid, VertexEdgeSpring& spring);

/// Exact normal gap of p1 from the line of edge p2 -> p3 (> 0 on the outward side).
double vertex_edge_gap(const Vec2& p1, const Vec2& p2, const Vec2& p3);

}  // namespace hfdda::dda
