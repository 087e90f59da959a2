// Structured (tensor-product) block mesh: square cells of the requested size inside the
// inner rectangle, geometrically graded cells from there to the outer boundary.
//
// Fractures of a structured mesh can only run along grid lines (or cell diagonals), so
// the grid lines are placed to pass exactly through the inner rectangle's corners and,
// for an inner rectangle symmetric about the origin, through x = 0 and y = 0.

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "mesh/mesh.hpp"
#include "mesh/format.hpp"

namespace hfdda::mesh {
namespace {

// A typo in cell_size_m (mm instead of m) should fail at once, not exhaust the memory.
constexpr std::int64_t kMaxLinesPerAxis = 1'000'000;
constexpr std::int64_t kMaxBlocks = 20'000'000;

using detail::num;

void require(bool ok, const std::string& rule) {
  if (!ok) throw ModelError("structured mesh: " + rule);
}

void validate(const StructuredMeshSpec& spec) {
  require(std::isfinite(spec.cell_size_m) && spec.cell_size_m > 0.0,
          "cell_size_m = " + num(spec.cell_size_m) + " must be > 0");
  require(std::isfinite(spec.outer_growth) && spec.outer_growth >= 1.0,
          "outer_growth = " + num(spec.outer_growth) + " must be >= 1");
  require(spec.outer.width() > 0.0 && spec.outer.height() > 0.0,
          "outer rectangle must have positive width and height");
  if (!spec.has_inner) return;
  require(spec.inner.width() > 0.0 && spec.inner.height() > 0.0,
          "inner rectangle must have positive width and height");
  require(spec.outer.contains(spec.inner), "inner rectangle must lie inside the outer rectangle");
}

/// Number of cells of size h tiling [a, b]; the range must be an integer multiple of h
/// so the grid lines land exactly on both ends.
int uniform_cell_count(double a, double b, double h, const std::string& range_name) {
  const double length = b - a;
  const double n = std::round(length / h);
  require(n >= 1.0 && std::abs(n * h - length) <= 1e-9 * length,
          range_name + " = " + num(length) + " m is not an integer multiple of cell_size_m = " +
              num(h) + " m (ratio " + num(length / h) + ")");
  require(n < static_cast<double>(kMaxLinesPerAxis),
          range_name + " / cell_size_m = " + num(n) + " cells: too many");
  return static_cast<int>(n);
}

/// n + 1 equally spaced lines from a to b. Interpolating from both ends (rather than
/// accumulating a + i h) makes lines of a range symmetric about 0 exact negatives of
/// each other and puts its middle line exactly on 0.
void append_uniform_lines(double a, double b, int n, std::vector<double>& lines) {
  for (int i = 0; i <= n; ++i) lines.push_back((a * (n - i) + b * i) / n);
}

/// Offsets (> 0) of the graded grid lines beyond an inner edge, up to `gap` metres.
/// Cell k (k = 1, 2, ...) measures h * growth^k; the last cell ends exactly at `gap`,
/// and a final sliver smaller than half its neighbour is merged into that neighbour.
/// The first outer cell never merges into the inner (uniform) cells.
std::vector<double> graded_offsets(double gap, double h, double growth) {
  std::vector<double> offsets;
  double position = 0.0, step = h;
  while (true) {
    const double previous_step = step;
    step *= growth;
    if (position + step < gap) {
      position += step;
      offsets.push_back(position);
      require(static_cast<std::int64_t>(offsets.size()) < kMaxLinesPerAxis,
              "too many graded cells (outer_growth too close to 1 for this domain)");
      continue;
    }
    const double sliver = gap - position;
    if (!offsets.empty() && sliver < 0.5 * previous_step)
      offsets.back() = gap;
    else
      offsets.push_back(gap);
    return offsets;
  }
}

/// Grid-line coordinates along one axis, increasing, first and last on the outer
/// boundary. `inner_a`, `inner_b` are used only when `has_inner`.
std::vector<double> axis_lines(double outer_a, double outer_b, bool has_inner, double inner_a,
                               double inner_b, double h, double growth, const std::string& axis) {
  std::vector<double> lines;
  if (!has_inner) {
    append_uniform_lines(outer_a, outer_b, uniform_cell_count(outer_a, outer_b, h, "outer " + axis),
                         lines);
    return lines;
  }
  const int n_inner = uniform_cell_count(inner_a, inner_b, h, "inner " + axis);
  const double gap_low = inner_a - outer_a, gap_high = outer_b - inner_b;
  // A gap of a rounding error would leave a zero-width row of cells.
  for (double gap : {gap_low, gap_high})
    require(gap == 0.0 || gap > 1e-6 * h,
            "the outer boundary is " + num(gap) + " m from the inner rectangle along " + axis +
                ": make them coincide or leave at least a fraction of a cell");
  if (gap_low > 0.0) {
    const std::vector<double> offsets = graded_offsets(gap_low, h, growth);
    // The outermost offset equals the gap; use outer_a itself so the line is exact.
    lines.push_back(outer_a);
    for (int k = static_cast<int>(offsets.size()) - 2; k >= 0; --k)
      lines.push_back(inner_a - offsets[k]);
  }
  append_uniform_lines(inner_a, inner_b, n_inner, lines);
  if (gap_high > 0.0) {
    const std::vector<double> offsets = graded_offsets(gap_high, h, growth);
    for (std::size_t k = 0; k + 1 < offsets.size(); ++k) lines.push_back(inner_b + offsets[k]);
    lines.push_back(outer_b);
  }
  return lines;
}

/// Index of the line closest to `centre`: the vertex where the triangles' diagonals of
/// the union-jack pattern meet, so a mesh symmetric about that point stays symmetric.
int nearest_line(const std::vector<double>& lines, double centre) {
  int best = 0;
  for (int i = 1; i < static_cast<int>(lines.size()); ++i)
    if (std::abs(lines[i] - centre) < std::abs(lines[best] - centre)) best = i;
  return best;
}

/// Blocks of one cell with corners (counter-clockwise) c00, c10, c11, c01.
void add_cell_blocks(CellSplit split, int c00, int c10, int c11, int c01, bool rising_diagonal,
                     int centre, std::vector<Block>& blocks) {
  auto add = [&blocks](std::initializer_list<int> corners) { blocks.emplace_back().points = corners; };
  switch (split) {
    case CellSplit::none:
      add({c00, c10, c11, c01});
      break;
    case CellSplit::two:
      if (rising_diagonal) {
        add({c00, c10, c11});
        add({c00, c11, c01});
      } else {
        add({c00, c10, c01});
        add({c10, c11, c01});
      }
      break;
    case CellSplit::four:
      add({c00, c10, centre});
      add({c10, c11, centre});
      add({c11, c01, centre});
      add({c01, c00, centre});
      break;
  }
}

int blocks_per_cell(CellSplit split) {
  return split == CellSplit::none ? 1 : split == CellSplit::two ? 2 : 4;
}

}  // namespace

Mesh build_structured_mesh(const StructuredMeshSpec& spec) {
  validate(spec);
  const Rect& o = spec.outer;
  const Rect& in = spec.inner;
  const double h = spec.cell_size_m, g = spec.outer_growth;
  const std::vector<double> xs =
      axis_lines(o.xmin, o.xmax, spec.has_inner, in.xmin, in.xmax, h, g, "width (x)");
  const std::vector<double> ys =
      axis_lines(o.ymin, o.ymax, spec.has_inner, in.ymin, in.ymax, h, g, "height (y)");
  const int nx = static_cast<int>(xs.size()) - 1, ny = static_cast<int>(ys.size()) - 1;
  require(static_cast<std::int64_t>(nx) * ny * blocks_per_cell(spec.split) <= kMaxBlocks,
          std::to_string(nx) + " x " + std::to_string(ny) + " cells: too many blocks");

  Mesh mesh;
  const int n_grid_points = (nx + 1) * (ny + 1);
  const bool centres = spec.split == CellSplit::four;
  mesh.points.reserve(n_grid_points + (centres ? nx * ny : 0));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) mesh.points.emplace_back(xs[i], ys[j]);
  if (centres)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        mesh.points.emplace_back(0.5 * (xs[i] + xs[i + 1]), 0.5 * (ys[j] + ys[j + 1]));

  const Rect& middle = spec.has_inner ? in : o;
  const int ic = nearest_line(xs, 0.5 * (middle.xmin + middle.xmax));
  const int jc = nearest_line(ys, 0.5 * (middle.ymin + middle.ymax));
  auto grid_point = [nx](int i, int j) { return j * (nx + 1) + i; };

  mesh.blocks.reserve(static_cast<std::size_t>(nx) * ny * blocks_per_cell(spec.split));
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      // Checkerboard of diagonal directions: cell (ic, jc) rises from the centre vertex.
      const bool rising = ((i + ic + j + jc) & 1) == 0;
      add_cell_blocks(spec.split, grid_point(i, j), grid_point(i + 1, j), grid_point(i + 1, j + 1),
                      grid_point(i, j + 1), rising, n_grid_points + j * nx + i, mesh.blocks);
    }
  }
  return mesh;
}

}  // namespace hfdda::mesh
