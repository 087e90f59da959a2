#pragma once
// Block mesh of the DDA model: polygonal blocks (triangles or quadrilaterals) that
// share geometric points, the joints between them (every edge shared by two blocks,
// seed section 2.3) and the free boundary edges where far-field tractions act.
//
// Geometric points are the future fluid nodes (one node per point, docs/formulation.md
// section 4.1); each block keeps its own copy of its corners in the mechanics, so
// blocks can separate while the mesh topology stays fixed (contact list built once,
// seed 2.3 iv).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry.hpp"

namespace hfdda::mesh {

/// Strength and flags of one joint (bond between two blocks). SI units.
struct JointProperties {
  double tensile_strength_Pa = 0.0;   ///< T0, Rankine limit of the bond
  /// K_IC [Pa m^0.5]; set, it replaces T0 by K_IC / sqrt(pi L / 2), L the joint's length (seed eq. 4.13)
  std::optional<double> fracture_toughness_Pa_sqrt_m;
  double cohesion_Pa = 0.0;           ///< C0, Mohr-Coulomb cohesion of the bond
  double friction_angle_rad = 0.0;    ///< phi
  /// w0: width through which fluid flows while the joint is mechanically closed; the
  /// hydraulic width is the mechanical opening plus w0 (seed 5.2, Table 5.1) [m]
  double hydraulic_width_m = 0.0;
  bool initially_open = false;        ///< bond already broken at t = 0 (initial fracture)
  bool natural = false;               ///< belongs to a natural (pre-existing) fracture
  bool breakable = true;              ///< false: the bond never fails ("may not break")
  double prescribed_pressure_Pa = -1; ///< >= 0: fluid pressure prescribed on both faces
};

struct Block {
  std::vector<int> points;  ///< geometric point ids, counter-clockwise
  int material = 0;         ///< index into the case's material list
};

/// A joint: the edge shared by blocks a and b. Block a runs the edge p -> q starting
/// at its local corner `corner_a`; block b runs it q -> p starting at `corner_b`.
struct Joint {
  int block_a = -1, corner_a = -1;
  int block_b = -1, corner_b = -1;
  int point_p = -1, point_q = -1;
  JointProperties properties;
};

/// An edge on the outer boundary of the block assembly (one block only), p -> q
/// counter-clockwise around the block, starting at local corner `corner`.
struct BoundaryEdge {
  int block = -1, corner = -1;
  int point_p = -1, point_q = -1;
};

/// A mesh edge lying on a line feature of a Delaunay mesh: `feature` indexes
/// DelaunayMeshSpec::constraints. An edge on two overlapping features appears twice.
struct FeatureEdge {
  int point_p = -1, point_q = -1;
  int feature = -1;
};

/// A line-feature end moved onto another feature (or a side of the domain) because it
/// missed it by less than the snap tolerance: a digitised near-miss made to meet exactly.
struct FeatureSnap {
  std::string feature;  ///< name of the feature whose end moved
  int end = 0;          ///< 0: its `from` end, 1: its `to` end
  Vec2 from{0, 0}, to{0, 0};
  double moved_m = 0.0;  ///< |to - from| [m]
};

struct Mesh {
  std::vector<Vec2> points;
  /// Delaunay meshes: every edge of every line feature, from the constraint the
  /// triangulation kept for it while refining (no geometric search). Sorted by feature.
  std::vector<FeatureEdge> feature_edges;
  bool has_feature_edges = false;  ///< feature_edges is authoritative (a Delaunay mesh)
  /// Delaunay meshes: line-feature ends snapped onto other features or the domain's
  /// sides (join_line_features), each with where it was and where it went.
  std::vector<FeatureSnap> feature_snaps;
  double feature_snap_tolerance_m = 0.0;  ///< the tolerance they were snapped with [m]
  std::vector<Block> blocks;
  std::vector<Joint> joints;
  std::vector<BoundaryEdge> boundary_edges;
};

/// A straight line feature of the model (initial fracture, natural fracture,
/// prescribed path, material interface). Delaunay meshes use it as a constraint
/// segment split into pieces no longer than `segment_length_m` (0: mesh size);
/// structured meshes require it to follow grid lines.
struct LineFeature {
  std::string name;
  Vec2 from{0, 0}, to{0, 0};
  double segment_length_m = 0.0;
};

enum class CellSplit { none, two, four };  ///< quadrilaterals, 2 or 4 triangles per cell

/// Structured mesh: square cells of `cell_size_m` inside `inner` (or the whole
/// domain when no inner rectangle), cells growing geometrically by `outer_growth`
/// from the inner rectangle to the outer boundary (tensor-product grid).
struct StructuredMeshSpec {
  Rect outer;
  bool has_inner = false;
  Rect inner;
  double cell_size_m = 1.0;
  double outer_growth = 1.2;
  CellSplit split = CellSplit::two;
};

/// Constrained Delaunay mesh (CGAL): triangles no larger than max_area_inner_m2
/// inside `inner` (or everywhere) and max_area_outer_m2 outside it, minimum angle
/// bound for quality, and constraint segments (inner boundary + line features).
struct DelaunayMeshSpec {
  Rect outer;
  bool has_inner = false;
  Rect inner;
  double max_area_inner_m2 = 1.0;
  double max_area_outer_m2 = 10.0;
  double min_angle_deg = 25.0;
  /// Feature ends closer than this to another feature or to a side of the domain are
  /// snapped onto it [m]; 0: 5e-7 of the outer rectangle's diagonal (rounding only).
  double snap_tolerance_m = 0.0;
  std::vector<LineFeature> constraints;
};

/// Line features made to meet exactly (feature_crossings.cpp): every feature end within
/// `snap_tolerance_m` of another feature's end or interior, or of a fixed line (the
/// rectangles' sides), is moved onto it; then features are split where they cross each
/// other or where an end of one lies on another. The pieces keep their feature's name
/// and values, in the features' order.
struct JoinedFeatures {
  std::vector<LineFeature> features;
  std::vector<int> source_feature;  ///< per joined feature: index of the input feature it is part of
  std::vector<FeatureSnap> snaps;  ///< feature ends moved, in the features' order
  int splits = 0;               ///< cuts made at crossings and touching ends
};
JoinedFeatures join_line_features(const std::vector<LineFeature>& features,
                                  const std::vector<std::pair<Vec2, Vec2>>& fixed_lines, double snap_tolerance_m);

Mesh build_structured_mesh(const StructuredMeshSpec& spec);
Mesh build_delaunay_mesh(const DelaunayMeshSpec& spec);

/// Fills joints and boundary edges from blocks and points (all joints get
/// `defaults`). Throws ModelError on a degenerate or inverted (clockwise) block or
/// an edge shared by more than two blocks.
void build_topology(Mesh& mesh, const JointProperties& defaults);

/// Ids of joints whose both end points lie on segment [a, b] (within tol metres).
std::vector<int> joints_on_segment(const Mesh& mesh, const Vec2& a, const Vec2& b, double tol);

/// Id of the point nearest to p.
int nearest_point(const Mesh& mesh, const Vec2& p);

}  // namespace hfdda::mesh
