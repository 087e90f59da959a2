// Unstructured triangular block mesh: CGAL constrained Delaunay triangulation refined
// by Delaunay refinement (Ruppert / Shewchuk, CGAL Mesh_2) with a size bound per
// region (inner rectangle / rest of the domain) and a minimum-angle bound.
//
// Line features (fractures, interfaces) are constraints pre-split into pieces of the
// requested joint length, so that a fracture is made of joints of that length; the
// refinement may split a piece further when a new point encroaches on it.

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "core/errors.hpp"
#include "mesh/mesh.hpp"
#include "mesh/format.hpp"

namespace hfdda::mesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;  // info: point id
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Exact_predicates_tag: crossing line features are allowed; their intersection points
// are constructed (inexactly) and become mesh points (join_line_features has already
// split features at their crossings, so this is a safety net).
using CdtBase = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;
// The "plus" hierarchy remembers which input constraint every refined edge came from,
// so the joints of a feature are known from meshing rather than searched for again.
using Cdt = CGAL::Constrained_triangulation_plus_2<CdtBase>;

// Above this the standard Delaunay refinement has no termination guarantee even for
// inputs without small angles (Shewchuk's Triangle works up to about 33 degrees).
constexpr double kMaxMinAngleDeg = 33.0;
/// Unless the case gives a snap tolerance, feature ends this close to another feature
/// (relative to the domain's diagonal) are snapped onto it: 5e-7 of a 141 m diagonal is
/// 0.07 mm, far below any joint length and far above the rounding of written coordinates.
constexpr double kDefaultSnapTolerance = 5e-7;

using detail::num;

void require(bool ok, const std::string& rule) {
  if (!ok) throw ModelError("Delaunay mesh: " + rule);
}

void validate(const DelaunayMeshSpec& spec) {
  require(spec.outer.width() > 0.0 && spec.outer.height() > 0.0,
          "outer rectangle must have positive width and height");
  if (spec.has_inner) {
    require(spec.inner.width() > 0.0 && spec.inner.height() > 0.0,
            "inner rectangle must have positive width and height");
    require(spec.outer.contains(spec.inner), "inner rectangle must lie inside the outer rectangle");
    require(std::isfinite(spec.max_area_inner_m2) && spec.max_area_inner_m2 > 0.0,
            "max_area_inner_m2 = " + num(spec.max_area_inner_m2) + " must be > 0");
  }
  require(std::isfinite(spec.max_area_outer_m2) && spec.max_area_outer_m2 > 0.0,
          "max_area_outer_m2 = " + num(spec.max_area_outer_m2) + " must be > 0");
  require(spec.min_angle_deg >= 0.0 && spec.min_angle_deg <= kMaxMinAngleDeg,
          "min_angle_deg = " + num(spec.min_angle_deg) + " must be in [0, " +
              num(kMaxMinAngleDeg) + "]");
  require(std::isfinite(spec.snap_tolerance_m) && spec.snap_tolerance_m >= 0.0,
          "snap_tolerance_m = " + num(spec.snap_tolerance_m) + " must be >= 0");
  const double tol = 1e-9 * std::hypot(spec.outer.width(), spec.outer.height());
  for (const LineFeature& f : spec.constraints) {
    const std::string name = "line feature '" + f.name + "'";
    require(spec.outer.contains(f.from, tol) && spec.outer.contains(f.to, tol),
            name + " must lie inside the outer rectangle");
    require((f.to - f.from).norm() > tol, name + " has zero length");
    require(std::isfinite(f.segment_length_m) && f.segment_length_m >= 0.0,
            name + ": segment_length_m = " + num(f.segment_length_m) + " must be >= 0");
  }
}

/// Which triangles Delaunay refinement must split. A triangle is imperatively bad
/// when its area exceeds the bound of the region holding its centroid (triangles never
/// straddle the inner rectangle, whose boundary is constrained), and bad when its
/// smallest angle is below the bound. The angle test is skipped for triangles whose
/// shortest edge is below `min_edge_m`: near small input angles (fractures crossing
/// at a shallow angle) such triangles cannot be improved and would make the
/// refinement cascade; this is the usual practical guard (as in Triangle).
class RegionCriteria {
 public:
  struct Quality {
    double sine2 = 1.0;       ///< squared sine of the smallest angle
    double size_ratio = 0.0;  ///< area / region's area bound

    // q1 < q2: q1 is refined first. Oversized triangles first, largest first, then the
    // worst-shaped ones (as CGAL::Delaunay_mesh_size_criteria_2).
    bool operator<(const Quality& q) const {
      if (size_ratio > 1.0 || q.size_ratio > 1.0) return size_ratio > q.size_ratio;
      return sine2 < q.sine2;
    }
  };

  explicit RegionCriteria(const DelaunayMeshSpec& spec)
      : has_inner_(spec.has_inner), inner_(spec.inner),
        max_area_inner_m2_(spec.max_area_inner_m2), max_area_outer_m2_(spec.max_area_outer_m2),
        min_sine2_(std::pow(std::sin(spec.min_angle_deg * std::numbers::pi / 180.0), 2)),
        domain_diagonal_m_(std::hypot(spec.outer.width(), spec.outer.height())) {}

  class Is_bad {
   public:
    explicit Is_bad(const RegionCriteria& c) : c_(&c) {}

    CGAL::Mesh_2::Face_badness operator()(const Quality& q) const {
      if (q.size_ratio > 1.0) return CGAL::Mesh_2::IMPERATIVELY_BAD;
      return q.sine2 < c_->min_sine2_ ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }

    CGAL::Mesh_2::Face_badness operator()(const Cdt::Face_handle& f, Quality& q) const {
      const Vec2 a = to_vec(f->vertex(0)->point());
      const Vec2 b = to_vec(f->vertex(1)->point());
      const Vec2 c = to_vec(f->vertex(2)->point());
      const double twice_area = cross2(a, b, c);
      const double max_area = c_->area_bound((a + b + c) / 3.0);
      q.size_ratio = 0.5 * twice_area / max_area;
      std::array<double, 3> edge2{(b - c).squaredNorm(), (c - a).squaredNorm(),
                                  (a - b).squaredNorm()};
      std::sort(edge2.begin(), edge2.end());
      const double min_edge = c_->min_edge_m(max_area);
      // The smallest angle lies between the two longest edges: 2A = |e1||e2| sin(angle).
      q.sine2 = edge2[0] < min_edge * min_edge ? 1.0
                                               : twice_area * twice_area / (edge2[1] * edge2[2]);
      return (*this)(q);
    }

   private:
    static Vec2 to_vec(const Kernel::Point_2& p) { return {p.x(), p.y()}; }
    const RegionCriteria* c_;  ///< not owned: the mesher's copy, which outlives every Is_bad
  };

  Is_bad is_bad_object() const { return Is_bad(*this); }

  double area_bound(const Vec2& centroid) const {
    return has_inner_ && inner_.contains(centroid) ? max_area_inner_m2_ : max_area_outer_m2_;
  }
  double min_edge_m(double area_bound) const {
    return 1e-3 * std::min(std::sqrt(area_bound), domain_diagonal_m_);
  }

 private:
  bool has_inner_;
  Rect inner_;
  double max_area_inner_m2_, max_area_outer_m2_;
  double min_sine2_;  ///< sin^2 of min_angle_deg, CGAL's shape bound B
  double domain_diagonal_m_;
};

Cdt::Point point_of(const Vec2& p) { return {p.x(), p.y()}; }

void insert_rectangle(Cdt& cdt, const Rect& r) {
  const std::vector<Cdt::Point> corners{
      {r.xmin, r.ymin}, {r.xmax, r.ymin}, {r.xmax, r.ymax}, {r.xmin, r.ymax}};
  cdt.insert_constraint(corners.begin(), corners.end(), /*close=*/true);
}

/// Number of constraint pieces of a feature: equal pieces no longer than its
/// segment length (the 1e-9 keeps an exact multiple from gaining a sliver piece).
int piece_count(const LineFeature& f) {
  if (f.segment_length_m <= 0.0) return 1;
  return std::max(1, static_cast<int>(std::ceil((f.to - f.from).norm() / f.segment_length_m - 1e-9)));
}

/// Inserts a feature as one polyline constraint of its pieces; returns its id.
Cdt::Constraint_id insert_feature(Cdt& cdt, const LineFeature& f, const Rect& outer) {
  // End points within round-off outside the domain are pulled onto its boundary: a
  // point outside would enlarge the convex hull by a sliver that is not domain.
  const Vec2 lo(outer.xmin, outer.ymin), hi(outer.xmax, outer.ymax);
  const auto inside = [&](const Vec2& p) -> Vec2 { return p.cwiseMax(lo).cwiseMin(hi); };
  const int n = piece_count(f);
  std::vector<Cdt::Point> points{point_of(inside(f.from))};
  for (int k = 1; k <= n; ++k) {
    const Vec2 p = k == n ? f.to : Vec2(f.from + (f.to - f.from) * (static_cast<double>(k) / n));
    points.push_back(point_of(inside(p)));
  }
  return cdt.insert_constraint(points.begin(), points.end());
}

/// The straight constraint pieces as they will be inserted: the rectangles' sides and
/// each feature's pieces (end points pulled into the domain as insert_feature does).
struct Piece {
  Vec2 a, b;
  int feature;  ///< -1: outer rectangle, -2: inner, else the index of the line feature
};

std::vector<Piece> constraint_pieces(const DelaunayMeshSpec& spec) {
  std::vector<Piece> pieces;
  auto rectangle = [&](const Rect& r, int id) {
    const Vec2 c[] = {{r.xmin, r.ymin}, {r.xmax, r.ymin}, {r.xmax, r.ymax}, {r.xmin, r.ymax}};
    for (int i = 0; i < 4; ++i) pieces.push_back({c[i], c[(i + 1) % 4], id});
  };
  rectangle(spec.outer, -1);
  if (spec.has_inner) rectangle(spec.inner, -2);
  const Vec2 lo(spec.outer.xmin, spec.outer.ymin), hi(spec.outer.xmax, spec.outer.ymax);
  for (std::size_t i = 0; i < spec.constraints.size(); ++i) {
    const LineFeature& f = spec.constraints[i];
    const int n = piece_count(f);
    Vec2 previous = f.from.cwiseMax(lo).cwiseMin(hi);
    for (int k = 1; k <= n; ++k) {
      const Vec2 p = k == n ? f.to : Vec2(f.from + (f.to - f.from) * (static_cast<double>(k) / n));
      const Vec2 next = p.cwiseMax(lo).cwiseMin(hi);
      pieces.push_back({previous, next, static_cast<int>(i)});
      previous = next;
    }
  }
  return pieces;
}

std::string feature_name(const DelaunayMeshSpec& spec, int feature) {
  if (feature == -1) return "the outer rectangle";
  if (feature == -2) return "the inner rectangle";
  return "line feature '" + spec.constraints[feature].name + "'";
}

/// A constraint point a rounding error away from another constraint, without lying on
/// it exactly, makes CGAL's refinement fail (an assertion in Mesh_2's edge refinement;
/// a segmentation fault when CGAL's checks are compiled out), so such input is refused.
/// Points exactly on another constraint (exact predicate) and shared end points are fine.
void reject_near_misses(const DelaunayMeshSpec& spec) {
  const std::vector<Piece> pieces = constraint_pieces(spec);
  const double tol = 1e-9 * std::hypot(spec.outer.width(), spec.outer.height());
  // Pieces bucketed on a uniform grid by their boxes grown by tol.
  const int cells = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(pieces.size()))), 1, 1024);
  const double cw = spec.outer.width() / cells, ch = spec.outer.height() / cells;
  auto cell_x = [&](double x) { return std::clamp(static_cast<int>((x - spec.outer.xmin) / cw), 0, cells - 1); };
  auto cell_y = [&](double y) { return std::clamp(static_cast<int>((y - spec.outer.ymin) / ch), 0, cells - 1); };
  std::vector<std::vector<int>> bucket(static_cast<std::size_t>(cells) * cells);
  for (int k = 0; k < static_cast<int>(pieces.size()); ++k) {
    const Piece& s = pieces[k];
    for (int ix = cell_x(std::min(s.a.x(), s.b.x()) - tol); ix <= cell_x(std::max(s.a.x(), s.b.x()) + tol); ++ix)
      for (int iy = cell_y(std::min(s.a.y(), s.b.y()) - tol); iy <= cell_y(std::max(s.a.y(), s.b.y()) + tol); ++iy)
        bucket[static_cast<std::size_t>(ix) * cells + iy].push_back(k);
  }
  for (const Piece& owner : pieces)
    for (const Vec2& p : {owner.a, owner.b})
      for (int k : bucket[static_cast<std::size_t>(cell_x(p.x())) * cells + cell_y(p.y())]) {
        const Piece& s = pieces[k];
        if (s.feature == owner.feature || p == s.a || p == s.b) continue;
        const Vec2 d = s.b - s.a;
        if (d.squaredNorm() == 0.0) continue;  // a piece clamped to a point on the boundary
        const double t = std::clamp((p - s.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
        const double distance = (p - (s.a + t * d)).norm();
        if (distance >= tol) continue;
        const bool on_line = CGAL::orientation(point_of(s.a), point_of(s.b), point_of(p)) == CGAL::COLLINEAR;
        if (on_line && t > 0.0 && t < 1.0) continue;
        throw ModelError("Delaunay mesh: " + feature_name(spec, owner.feature) + " has a point (" + num(p.x()) +
                         ", " + num(p.y()) + ") " + num(distance) + " m from " + feature_name(spec, s.feature) +
                         " without lying on it; make them meet exactly or keep them at least " + num(tol) +
                         " m apart (1e-9 of the domain's diagonal)");
      }
}

/// Expected number of mesh points, to stop a refinement that does not terminate.
double expected_points(const DelaunayMeshSpec& spec) {
  const double inner_area = spec.has_inner ? spec.inner.width() * spec.inner.height() : 0.0;
  const double outer_area = spec.outer.width() * spec.outer.height() - inner_area;
  double count = outer_area / spec.max_area_outer_m2;
  if (spec.has_inner) count += inner_area / spec.max_area_inner_m2;
  for (const LineFeature& f : spec.constraints) count += piece_count(f);
  return count;
}

void refine(Cdt& cdt, const DelaunayMeshSpec& spec) {
  const double expected = expected_points(spec);
  require(expected < 2e7,
          "about " + num(expected) + " points requested: too many (check the area bounds)");
  // Shape-quality refinement produces a few times the size-bound estimate; far beyond
  // that, refinement is cascading (min angle too large for the input's small angles).
  const double budget = 20.0 * expected + 10000.0;
  CGAL::Delaunay_mesher_2<Cdt, RegionCriteria> mesher(cdt, RegionCriteria(spec));
  mesher.init();
  while (mesher.step_by_step_refine_mesh()) {
    if (static_cast<double>(cdt.number_of_vertices()) > budget)
      throw ModelError("Delaunay mesh: refinement exceeded " + num(budget) +
                       " points without terminating; lower min_angle_deg = " + num(spec.min_angle_deg) +
                       " (line features crossing at small angles need a smaller bound)");
  }
}

/// Blocks from the triangles inside the domain, points numbered in order of first use;
/// the feature edges from the constraint hierarchy.
Mesh extract_mesh(Cdt& cdt, const std::map<Cdt::Constraint_id, int>& feature_of_constraint) {
  Mesh mesh;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) v->info() = -1;
  mesh.blocks.reserve(cdt.number_of_faces());
  mesh.points.reserve(cdt.number_of_vertices());
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    Block& block = mesh.blocks.emplace_back();
    for (int i = 0; i < 3; ++i) {  // CGAL faces are counter-clockwise
      const Cdt::Vertex_handle v = f->vertex(i);
      if (v->info() < 0) {
        v->info() = static_cast<int>(mesh.points.size());
        mesh.points.emplace_back(v->point().x(), v->point().y());
      }
      block.points.push_back(v->info());
    }
  }
  mesh.has_feature_edges = true;
  for (auto e = cdt.finite_edges_begin(); e != cdt.finite_edges_end(); ++e) {
    if (!cdt.is_constrained(*e)) continue;
    const Cdt::Vertex_handle va = e->first->vertex(Cdt::cw(e->second));
    const Cdt::Vertex_handle vb = e->first->vertex(Cdt::ccw(e->second));
    if (va->info() < 0 || vb->info() < 0) continue;
    for (auto context : cdt.contexts(va, vb)) {  // Context::id() is not const in CGAL 5.5
      const auto it = feature_of_constraint.find(context.id());
      if (it != feature_of_constraint.end()) mesh.feature_edges.push_back({va->info(), vb->info(), it->second});
    }
  }
  std::sort(mesh.feature_edges.begin(), mesh.feature_edges.end(), [](const FeatureEdge& x, const FeatureEdge& y) {
    return std::tie(x.feature, x.point_p, x.point_q) < std::tie(y.feature, y.point_p, y.point_q);
  });
  mesh.feature_edges.erase(std::unique(mesh.feature_edges.begin(), mesh.feature_edges.end(),
                                       [](const FeatureEdge& x, const FeatureEdge& y) {
                                         return x.feature == y.feature && x.point_p == y.point_p &&
                                                x.point_q == y.point_q;
                                       }),
                           mesh.feature_edges.end());
  return mesh;
}

}  // namespace

Mesh build_delaunay_mesh(const DelaunayMeshSpec& input) {
  validate(input);
  // Features meet exactly: near-misses within the snap tolerance are snapped, crossings
  // split (feature_crossings.cpp); what is left farther apart than the rounding
  // tolerance of reject_near_misses is fine.
  std::vector<std::pair<Vec2, Vec2>> sides;
  auto add_sides = [&](const Rect& r) {
    const Vec2 c[] = {{r.xmin, r.ymin}, {r.xmax, r.ymin}, {r.xmax, r.ymax}, {r.xmin, r.ymax}};
    for (int i = 0; i < 4; ++i) sides.emplace_back(c[i], c[(i + 1) % 4]);
  };
  add_sides(input.outer);
  if (input.has_inner) add_sides(input.inner);
  DelaunayMeshSpec spec = input;
  const double diagonal = std::hypot(spec.outer.width(), spec.outer.height());
  const double snap_m = spec.snap_tolerance_m > 0.0 ? spec.snap_tolerance_m : kDefaultSnapTolerance * diagonal;
  JoinedFeatures joined = join_line_features(input.constraints, sides, snap_m);
  spec.constraints = std::move(joined.features);
  for (const LineFeature& piece : spec.constraints)
    require((piece.to - piece.from).norm() > 1e-9 * diagonal,
            "line feature '" + piece.name + "' shrinks to a point when its ends are snapped (snap tolerance " +
                num(snap_m) + " m); give a smaller snap tolerance or remove the feature");
  reject_near_misses(spec);
  Cdt cdt;
  insert_rectangle(cdt, spec.outer);
  if (spec.has_inner) insert_rectangle(cdt, spec.inner);
  std::map<Cdt::Constraint_id, int> feature_of_constraint;  // joined piece -> input feature
  for (std::size_t k = 0; k < spec.constraints.size(); ++k)
    feature_of_constraint[insert_feature(cdt, spec.constraints[k], spec.outer)] = joined.source_feature[k];
  refine(cdt, spec);
  Mesh mesh = extract_mesh(cdt, feature_of_constraint);
  mesh.feature_snaps = std::move(joined.snaps);
  mesh.feature_snap_tolerance_m = snap_m;
  return mesh;
}

}  // namespace hfdda::mesh
