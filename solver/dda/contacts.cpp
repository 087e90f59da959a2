#include "dda/contacts.hpp"

namespace hfdda::dda {

const char* to_string(ContactState state) {
  switch (state) {
    case ContactState::open: return "open";
    case ContactState::sliding: return "sliding";
    case ContactState::locked: return "locked";
  }
  return "unknown";
}

double vertex_edge_gap(const Vec2& p1, const Vec2& p2, const Vec2& p3) {
  return cross2(p1, p3, p2) / (p3 - p2).norm();
}

void linearise_vertex_edge(const Vec2& p1, const Vec2& p2, const Vec2& p3, const Vec2& vertex_centroid,
                           const Vec2& edge_centroid, VertexEdgeSpring& s) {
  const double length = (p3 - p2).norm();
  const Vec2 t = (p3 - p2) / length;
  const Vec2 n(t.y(), -t.x());  // outward normal of a counter-clockwise block's edge
  s.edge_length_m = length;
  s.gap0 = (p1 - p2).dot(n);
  // Gradients of (p1 - p2) x (p3 - p2) / length with respect to p2 and p3.
  const Vec2 d_p2(p1.y() - p3.y(), p3.x() - p1.x()), d_p3(p2.y() - p1.y(), p1.x() - p2.x());
  const Mat26 t1 = displacement_matrix(p1, vertex_centroid);
  const Mat26 t2 = displacement_matrix(p2, edge_centroid);
  const Mat26 t3 = displacement_matrix(p3, edge_centroid);
  // The edge's stretch (d length = t . (dp3 - dp2)) also changes gap = area / length;
  // Shi holds the length fixed, which is exact only at zero gap. Keep the full derivative.
  const Mat26 edge_stretch = t3 - t2;
  s.gap_vertex = n.transpose() * t1;
  s.gap_edge = (d_p2.transpose() * t2 + d_p3.transpose() * t3) / length -
               (s.gap0 / length) * t.transpose() * edge_stretch;
  // Shear: displacement of the corner along the edge relative to its reference point,
  // including the edge's rotation (d t = n n^T (dp3 - dp2) / length).
  const Vec2 p0 = p2 + s.reference_ratio * (p3 - p2);
  s.shear0 = (p1 - p0).dot(t);
  s.shear_vertex = t.transpose() * t1;
  s.shear_edge = -t.transpose() * displacement_matrix(p0, edge_centroid) +
                 ((p1 - p0).dot(n) / length) * n.transpose() * edge_stretch;
}

}  // namespace hfdda::dda
