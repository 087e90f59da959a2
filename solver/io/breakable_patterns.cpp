// `breakable_patterns` (breakable_patterns.hpp): the key, its checks, and the expansion
// of each pattern into line features.
//
// The seed's propagation runs (3.4, 3.5) let only chosen joints of a structured mesh
// break: all inner-domain joints, only the cell diagonals, or the diagonals with weaker
// -45 degree ones. A pattern names those joints as families of lines of a square grid
// over a rectangle; loading turns each line into the FractureConfig the model applies
// to the joints lying on it, so the model needs no notion of patterns.

#include "io/breakable_patterns.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "io/case_fields.hpp"

namespace hfdda::io {

using namespace schema;

namespace {

/// More lines than this in one pattern is a mistake (a cell size in the wrong unit).
constexpr int kMaxLinesPerPattern = 100000;

enum class Family { horizontal, vertical, plus_45, minus_45 };

const Choices<Family>& families() {
  static const Choices<Family> words{{"horizontal", Family::horizontal},
                                     {"vertical", Family::vertical},
                                     {"plus_45", Family::plus_45},
                                     {"minus_45", Family::minus_45}};
  return words;
}

Family family_of(const std::string& word) {
  for (const auto& [name, family] : families())
    if (name == word) return family;
  return Family::horizontal;  // not reached: the words were checked when read
}

bool is_diagonal(Family family) { return family == Family::plus_45 || family == Family::minus_45; }

// ---------------------------------------------------------------------------
// Key table

/// Lines are what a pattern is for: an empty list is a mistake, not "nothing".
void check_pattern_item(const FileReader& r, const YAML::Node& item, const std::string& key,
                        const BreakablePatternConfig& pattern, const std::set<std::string>& seen) {
  check_strength_choice(r, item, key, seen);
  if (pattern.lines.empty())
    r.fail(item["lines"], key + ".lines",
           "must name at least one family of lines: " + join(choice_names(families()), ", "));
}

const Table<BreakablePatternConfig>& pattern_table() {
  using P = BreakablePatternConfig;
  static const Table<P> table{
      "`breakable_patterns[]` items",
      "Which joints of a structured mesh may break, without one fracture per grid line: the "
      "horizontal and vertical lines of a square grid of side `cell_size` with a corner at "
      "`origin`, and the diagonals of its cells (`plus_45`: y = x + c, `minus_45`: y = -x + c), "
      "each clipped to `region`; lines on the edges of `region` are not part of it. Each line "
      "becomes a line feature appended to `fractures` (named `<name>.<family>`), with the "
      "values below; the parts of a line lying on a `fractures[]` item are left out, so "
      "those joints keep that item's values. A later pattern overrides an earlier one on the "
      "joints they share. A line that does not follow the mesh edges is reported when the "
      "model is built, as the fracture it became (`fractures[i]`), at the pattern's line. "
      "`lines` names at least one family.",
      {text({"name", "", "", "label of its lines"}, &P::name),
       required(rect({"region", "m", "§3.4: the 40 m x 40 m inner domain",
                      "rectangle its lines are clipped to"},
                     &P::region, "inside domain.outer")),
       required(number({"cell_size", "m", "§3.4: joints at 2 m intervals",
                        "side of the grid's square cells: spacing of the horizontal and "
                        "vertical lines, and of the intercepts c of the diagonals"},
                       &P::cell_size_m, greater_than(0), kWithinDomain)),
       point({"origin", "m", "", "a corner of the grid's cells"}, &P::origin,
             "inside domain.outer"),
       required(choice_list({"lines", "", "§3.4: grid lines and diagonals; §3.5: -45 deg diagonals",
                             "families of lines that belong to the pattern"},
                            &P::lines, choice_names(families()))),
       boolean({"breakable", "", "§3.4: fracturing confined to the inner domain",
                "whether the intact bonds on its lines may break"},
               &P::breakable),
       optional_number({"tensile_strength", "Pa", "§3.5: T0 = 0.1 MPa on -45 deg diagonals",
                        "tensile strength T0 of the bonds on its lines"},
                       &P::tensile_strength_Pa, zero_to(kMaxStrength), "joints.tensile_strength"),
       fracture_toughness_key<P>("T0 of the bonds on its lines", &P::fracture_toughness_Pa_sqrt_m,
                                 "joints.fracture_toughness"),
       optional_number({"cohesion", "Pa", "", "cohesion C0 of the bonds on its lines"},
                       &P::cohesion_Pa, zero_to(kMaxStrength), "joints.cohesion"),
       optional_number({"friction_angle", "deg", "", "friction angle of the joints on its lines"},
                       &P::friction_angle_deg, interval(0, false, 90, true),
                       "joints.friction_angle")}};
  return table;
}

// ---------------------------------------------------------------------------
// Lines of a pattern

struct Segment {
  Vec2 from, to;
};

/// The value c that tells the lines of a family apart, for the line through `p`.
double line_value(Family family, const Vec2& p) {
  switch (family) {
    case Family::horizontal: return p.y();
    case Family::vertical: return p.x();
    case Family::plus_45: return p.y() - p.x();  // y = x + c
    case Family::minus_45: return p.y() + p.x();  // y = -x + c
  }
  return 0.0;
}

/// Open interval of c over which a line of the family crosses the interior of `r`.
std::pair<double, double> value_range(Family family, const Rect& r) {
  switch (family) {
    case Family::horizontal: return {r.ymin, r.ymax};
    case Family::vertical: return {r.xmin, r.xmax};
    case Family::plus_45: return {r.ymin - r.xmax, r.ymax - r.xmin};
    case Family::minus_45: return {r.xmin + r.ymin, r.xmax + r.ymax};
  }
  return {0.0, 0.0};
}

/// The line of value c clipped to `r`, left end first.
Segment clip(Family family, double c, const Rect& r) {
  switch (family) {
    case Family::horizontal: return {{r.xmin, c}, {r.xmax, c}};
    case Family::vertical: return {{c, r.ymin}, {c, r.ymax}};
    case Family::plus_45: {
      const double x0 = std::max(r.xmin, r.ymin - c), x1 = std::min(r.xmax, r.ymax - c);
      return {{x0, x0 + c}, {x1, x1 + c}};
    }
    case Family::minus_45: {
      const double x0 = std::max(r.xmin, c - r.ymax), x1 = std::min(r.xmax, c - r.ymin);
      return {{x0, c - x0}, {x1, c - x1}};
    }
  }
  return {};
}

/// Upper bound of the number of lines of one family, computed without listing them.
double line_count_bound(Family family, const BreakablePatternConfig& p) {
  const auto [lo, hi] = value_range(family, p.region);
  return std::floor((hi - lo) / p.cell_size_m) + 1.0;
}

/// c = c0 + k cell_size strictly inside the family's range; a line within a millionth
/// of a cell of an edge of the region counts as on the edge.
std::vector<double> line_values(Family family, const BreakablePatternConfig& p) {
  const double h = p.cell_size_m, tol = 1e-6 * h;
  const double c0 = line_value(family, p.origin);
  const auto [lo, hi] = value_range(family, p.region);
  if (!(std::abs((lo - c0) / h) < 1e15 && std::abs((hi - c0) / h) < 1e15)) return {};
  const auto k_first = static_cast<long long>(std::floor((lo - c0) / h));
  const auto k_last = static_cast<long long>(std::ceil((hi - c0) / h));
  std::vector<double> values;
  for (long long k = k_first; k <= k_last; ++k) {
    const double c = c0 + static_cast<double>(k) * h;
    if (c > lo + tol && c < hi - tol) values.push_back(c);
  }
  return values;
}

std::size_t line_count(const BreakablePatternConfig& p) {
  std::size_t count = 0;
  for (const auto& word : p.lines) count += line_values(family_of(word), p).size();
  return count;
}

// ---------------------------------------------------------------------------
// Leaving out the written fractures

/// The part of a line covered by a fracture on it: positions along the line (from its
/// `from` end) and the fracture's own end points there.
struct Overlap {
  double start = 0.0, end = 0.0;
  Vec2 start_point, end_point;
};

std::optional<Overlap> overlap(const Segment& line, const FractureConfig& fracture, double tol) {
  const double length = (line.to - line.from).norm();
  const Vec2 along = (line.to - line.from) / length;
  auto off_line = [&](const Vec2& p) {
    const Vec2 r = p - line.from;
    return std::abs(along.x() * r.y() - along.y() * r.x()) > tol;
  };
  if (off_line(fracture.from) || off_line(fracture.to)) return std::nullopt;
  const double a = (fracture.from - line.from).dot(along);
  const double b = (fracture.to - line.from).dot(along);
  const Overlap o = a <= b ? Overlap{a, b, fracture.from, fracture.to}
                           : Overlap{b, a, fracture.to, fracture.from};
  if (o.end <= tol || o.start >= length - tol) return std::nullopt;  // at most a point shared
  return o;
}

/// The pieces of `line` that no fracture covers, in order along it. Cut ends are the
/// fractures' own end points, so a piece ends exactly where a fracture starts.
std::vector<Segment> pieces_off_fractures(const Segment& line,
                                          const std::vector<FractureConfig>& fractures,
                                          double tol) {
  std::vector<Overlap> overlaps;
  for (const auto& fracture : fractures)
    if (const auto o = overlap(line, fracture, tol)) overlaps.push_back(*o);
  std::sort(overlaps.begin(), overlaps.end(),
            [](const Overlap& a, const Overlap& b) { return a.start < b.start; });
  const double length = (line.to - line.from).norm();
  std::vector<Segment> pieces;
  double covered_to = 0.0;
  Vec2 piece_start = line.from;
  for (const auto& o : overlaps) {
    if (o.start > covered_to + tol) pieces.push_back({piece_start, o.start_point});
    if (o.end > covered_to) {
      covered_to = o.end;
      piece_start = o.end_point;
    }
  }
  if (length > covered_to + tol) pieces.push_back({piece_start, line.to});
  return pieces;
}

FractureConfig line_feature(const BreakablePatternConfig& p, const std::string& family,
                            const Segment& piece) {
  FractureConfig feature;
  feature.name = p.name + "." + family;
  feature.from = piece.from;
  feature.to = piece.to;
  feature.breakable = p.breakable;
  feature.tensile_strength_Pa = p.tensile_strength_Pa;
  feature.fracture_toughness_Pa_sqrt_m = p.fracture_toughness_Pa_sqrt_m;
  feature.cohesion_Pa = p.cohesion_Pa;
  feature.friction_angle_deg = p.friction_angle_deg;
  feature.line = p.line;
  return feature;
}

}  // namespace

// ---------------------------------------------------------------------------
// Public

Field<CaseConfig> breakable_patterns_key() {
  return map_list({"breakable_patterns", "",
                   "§3.4, §3.5: only inner-domain joints, grid lines or diagonals break",
                   "which joints may break: grid lines and cell diagonals over a rectangle"},
                  &CaseConfig::breakable_patterns, &pattern_table, 0, "none",
                  check_pattern_item);
}

void check_pattern_mesh(const CaseConfig& c, const MergedChecker& m) {
  if (c.breakable_patterns.empty()) return;
  if (c.mesh.kind != MeshKind::structured)
    m.fail("breakable_patterns",
           "needs mesh.type: structured (the mesh is Delaunay, where line features are mesh "
           "constraints; joints.breakable_region selects joints there)");
  if (c.mesh.split == mesh::CellSplit::four) return;
  for (std::size_t i = 0; i < c.breakable_patterns.size(); ++i)
    for (const auto& word : c.breakable_patterns[i].lines)
      if (is_diagonal(family_of(word)))
        m.fail(item_key("breakable_patterns", i) + ".lines",
               "diagonal lines (" + word + ") need mesh.split: four, where every cell has "
               "both diagonals");
}

void check_pattern_regions(const CaseConfig& c, const MergedChecker& m) {
  for (std::size_t i = 0; i < c.breakable_patterns.size(); ++i) {
    const BreakablePatternConfig& p = c.breakable_patterns[i];
    const std::string key = item_key("breakable_patterns", i);
    if (!c.domain.outer.contains(p.origin))
      m.fail(key + ".origin", "lies outside the domain " + domain_text(c.domain.outer) +
                                  " (got " + format_point(p.origin) + ")");
    if (!c.domain.outer.contains(p.region))
      m.fail(key + ".region", "must lie in the domain " + domain_text(c.domain.outer) +
                                  " (got " + domain_text(p.region) + ")");
    double bound = 0.0;
    for (const auto& word : p.lines) bound += line_count_bound(family_of(word), p);
    if (bound > kMaxLinesPerPattern)
      m.fail(key + ".cell_size", "gives more than " + std::to_string(kMaxLinesPerPattern) +
                                     " lines in the region (cell_size " +
                                     format_number(p.cell_size_m) + " m)");
    if (line_count(p) == 0)
      m.fail(key + ".region", "holds no line of the pattern (cell_size " +
                                  format_number(p.cell_size_m) + " m, origin " +
                                  format_point(p.origin) + "; lines on its edges do not count)");
  }
}

void append_breakable_pattern_lines(CaseConfig& c) {
  const std::vector<FractureConfig> written = c.fractures;
  // As the model matches joints to line features (a millionth of the domain size).
  const double tol = 1e-6 * std::max(c.domain.outer.width(), c.domain.outer.height());
  for (const auto& pattern : c.breakable_patterns)
    for (const auto& word : pattern.lines) {
      const Family family = family_of(word);
      for (double value : line_values(family, pattern))
        for (const Segment& piece :
             pieces_off_fractures(clip(family, value, pattern.region), written, tol))
          c.fractures.push_back(line_feature(pattern, word, piece));
    }
}

}  // namespace hfdda::io
