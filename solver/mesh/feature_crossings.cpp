// Line features made to meet exactly before they become mesh constraints: fracture maps
// are digitised, and hand-written fractures cut into joints put their cut points a
// rounding error off each other. Ends near another feature are snapped onto it, and
// features are split where they cross or touch, so that every meeting point is a
// shared end of constraint pieces and becomes one mesh point.

#include <algorithm>
#include <cmath>
#include <map>

#include "mesh/mesh.hpp"

namespace hfdda::mesh {
namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Uniform grid over the features' boxes (grown by `margin`), for neighbour queries.
class SegmentGrid {
 public:
  SegmentGrid(const std::vector<std::pair<Vec2, Vec2>>& segments, double margin) : segments_(segments) {
    Vec2 lo(1e300, 1e300), hi(-1e300, -1e300);
    for (const auto& [a, b] : segments) lo = lo.cwiseMin(a).cwiseMin(b), hi = hi.cwiseMax(a).cwiseMax(b);
    lo_ = lo - Vec2(margin, margin);
    const Vec2 size = hi - lo + Vec2(2 * margin, 2 * margin);
    cells_ = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(segments.size()))), 1, 1024);
    cell_ = Vec2(std::max(size.x(), 1e-300) / cells_, std::max(size.y(), 1e-300) / cells_);
    bucket_.resize(static_cast<std::size_t>(cells_) * cells_);
    for (int k = 0; k < static_cast<int>(segments.size()); ++k) {
      const auto& [a, b] = segments[k];
      for_cells(a.cwiseMin(b) - Vec2(margin, margin), a.cwiseMax(b) + Vec2(margin, margin),
                [&](std::vector<int>& cell) { cell.push_back(k); });
    }
  }
  /// Segments whose grown box may contain a point of [lo, hi], each once.
  std::vector<int> near(const Vec2& lo, const Vec2& hi) {
    std::vector<int> out;
    for_cells(lo, hi, [&](std::vector<int>& cell) { out.insert(out.end(), cell.begin(), cell.end()); });
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

 private:
  template <class F>
  void for_cells(const Vec2& lo, const Vec2& hi, F f) {
    auto index = [&](double v, double origin, double w) {
      return std::clamp(static_cast<int>((v - origin) / w), 0, cells_ - 1);
    };
    for (int ix = index(lo.x(), lo_.x(), cell_.x()); ix <= index(hi.x(), lo_.x(), cell_.x()); ++ix)
      for (int iy = index(lo.y(), lo_.y(), cell_.y()); iy <= index(hi.y(), lo_.y(), cell_.y()); ++iy)
        f(bucket_[static_cast<std::size_t>(ix) * cells_ + iy]);
  }
  const std::vector<std::pair<Vec2, Vec2>>& segments_;
  Vec2 lo_, cell_;
  int cells_ = 1;
  std::vector<std::vector<int>> bucket_;
};

}  // namespace

JoinedFeatures join_line_features(const std::vector<LineFeature>& features,
                                  const std::vector<std::pair<Vec2, Vec2>>& fixed_lines, double snap_tolerance_m) {
  JoinedFeatures out;
  const int nf = static_cast<int>(features.size());
  // Segments: the features first, then the fixed lines (rectangle sides), which only
  // receive snapped ends and are never split here (CGAL splits a constraint at a point
  // inserted exactly on it; a snapped point is put exactly on an axis-parallel side).
  std::vector<std::pair<Vec2, Vec2>> seg;
  for (const LineFeature& f : features) seg.emplace_back(f.from, f.to);
  for (const auto& l : fixed_lines) seg.push_back(l);
  const double tol = snap_tolerance_m;

  // 1. Snap: an end within tol of another end takes that end; else within tol of the
  // interior of another segment, it moves onto it (the nearest).
  {
    SegmentGrid grid(seg, tol);
    for (int i = 0; i < nf; ++i)
      for (int end = 0; end < 2; ++end) {
        Vec2& p = end == 0 ? seg[i].first : seg[i].second;
        const Vec2 original = p;
        double best = tol;
        Vec2 target = p;
        bool to_end = false;
        for (int k : grid.near(p, p)) {
          if (k == i) continue;
          const auto& [a, b] = seg[k];
          for (const Vec2& q : {a, b}) {
            const double d = (q - p).norm();
            if (d <= tol && (d < best || !to_end)) best = d, target = q, to_end = true;
          }
          if (to_end) continue;
          const Vec2 ab = b - a;
          if (ab.squaredNorm() == 0.0) continue;
          const double t = (p - a).dot(ab) / ab.squaredNorm();
          if (t <= 0.0 || t >= 1.0) continue;
          Vec2 foot = a + t * ab;
          // Exactly on an axis-parallel line, the other coordinate kept.
          if (a.x() == b.x()) foot = Vec2(a.x(), p.y());
          if (a.y() == b.y()) foot = Vec2(p.x(), a.y());
          const double d = (foot - p).norm();
          if (d < best) best = d, target = foot;
        }
        if (target != original) {
          p = target;
          out.snaps.push_back({features[i].name, end, original, target, (target - original).norm()});
        }
      }
  }

  // 2. Split each feature where another crosses it or ends on it (within tol). Cut points
  // within tol of each other are one point, shared by every feature cut there (three
  // features crossing at nearly one place must not get three points a rounding error apart).
  std::map<std::pair<long long, long long>, std::vector<Vec2>> cut_points;
  auto shared_point = [&](const Vec2& x) {
    const long long ix = static_cast<long long>(std::floor(x.x() / tol)), iy = static_cast<long long>(std::floor(x.y() / tol));
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy) {
        const auto it = cut_points.find({ix + dx, iy + dy});
        if (it == cut_points.end()) continue;
        for (const Vec2& q : it->second)
          if ((q - x).norm() <= tol) return q;
      }
    cut_points[{ix, iy}].push_back(x);
    return x;
  };
  std::vector<std::vector<std::pair<double, Vec2>>> cuts(nf);
  {
    std::vector<std::pair<Vec2, Vec2>> feature_segments(seg.begin(), seg.begin() + nf);
    SegmentGrid grid(feature_segments, tol);
    for (int i = 0; i < nf; ++i) {
      const auto& [a, b] = seg[i];
      const Vec2 ab = b - a;
      const double length2 = ab.squaredNorm();
      if (length2 == 0.0) continue;
      for (int k : grid.near(a.cwiseMin(b), a.cwiseMax(b))) {
        if (k == i) continue;
        const auto& [c, d] = seg[k];
        // Ends of k on the interior of i.
        for (const Vec2& q : {c, d}) {
          const double t = (q - a).dot(ab) / length2;
          if (t <= 0.0 || t >= 1.0 || q == a || q == b) continue;
          if (std::abs(cross(ab, q - a)) / std::sqrt(length2) <= tol) cuts[i].emplace_back(t, shared_point(q));
        }
        // A proper crossing of the interiors: both are cut at the same constructed point.
        const Vec2 cd = d - c;
        const double denom = cross(ab, cd);
        if (denom == 0.0) continue;
        const double t = cross(c - a, cd) / denom, u = cross(c - a, ab) / denom;
        const double margin_t = tol / std::sqrt(length2), margin_u = tol / cd.norm();
        if (t > margin_t && t < 1.0 - margin_t && u > margin_u && u < 1.0 - margin_u && k > i) {
          Vec2 x = a + t * ab;
          // On an axis-parallel feature the crossing keeps that feature's coordinate
          // exactly (cut points of both then lie exactly on each other's lines).
          for (const auto* line : {&seg[i], &seg[k]}) {
            if (line->first.x() == line->second.x()) x.x() = line->first.x();
            if (line->first.y() == line->second.y()) x.y() = line->first.y();
          }
          x = shared_point(x);
          cuts[i].emplace_back(t, x);
          cuts[k].emplace_back(u, x);
        }
      }
    }
  }
  for (int i = 0; i < nf; ++i) {
    auto& c = cuts[i];
    std::sort(c.begin(), c.end(), [](const auto& l, const auto& r) { return l.first < r.first; });
    Vec2 from = seg[i].first;
    for (const auto& [t, x] : c) {
      if ((x - from).norm() <= tol || (x - seg[i].second).norm() <= tol) continue;
      LineFeature piece = features[i];
      piece.from = from, piece.to = x;
      out.features.push_back(piece);
      out.source_feature.push_back(i);
      from = x;
      ++out.splits;
    }
    LineFeature last = features[i];
    last.from = from, last.to = seg[i].second;
    out.features.push_back(last);
    out.source_feature.push_back(i);
  }
  return out;
}

}  // namespace hfdda::mesh
