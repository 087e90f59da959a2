#include "ensemble/likelihood_maps.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/number_text.hpp"
#include "io/output.hpp"

namespace hfdda::ensemble {

ProportionInterval wilson_interval(long successes, long trials, double z) {
  if (trials < 0 || successes < 0 || successes > trials) {
    throw std::invalid_argument("wilson_interval: need 0 <= successes <= trials (got " +
                                std::to_string(successes) + " of " + std::to_string(trials) + ")");
  }
  if (!(z > 0.0) || !std::isfinite(z)) throw std::invalid_argument("wilson_interval: z must be > 0");
  if (trials == 0) return {0.0, 0.0, 1.0};
  const double n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n;
  const double z2 = z * z;
  const double centre = p + z2 / (2.0 * n);
  const double half = z * std::sqrt(p * (1.0 - p) / n + z2 / (4.0 * n * n));
  const double scale = 1.0 + z2 / n;
  ProportionInterval r{p, (centre - half) / scale, (centre + half) / scale};
  // At k = 0 and k = n the bound is 0 or 1 analytically; rounding must not move it.
  r.low = successes == 0 ? 0.0 : std::clamp(r.low, 0.0, p);
  r.high = successes == trials ? 1.0 : std::clamp(r.high, p, 1.0);
  return r;
}

// --- Grid ---------------------------------------------------------------------

MapGrid MapGrid::covering(double xmin, double xmax, double ymin, double ymax, double cell_m) {
  if (!(cell_m > 0.0) || !std::isfinite(cell_m)) {
    throw std::invalid_argument("MapGrid::covering: cell size must be > 0 (got " + number_text(cell_m) + ")");
  }
  if (!(xmax > xmin) || !(ymax > ymin) || !std::isfinite(xmax - xmin) || !std::isfinite(ymax - ymin)) {
    throw std::invalid_argument("MapGrid::covering: need xmin < xmax and ymin < ymax");
  }
  // A sliver column of a billionth of a cell, left by rounding of width / cell, is not added.
  const auto count = [cell_m](double width) {
    const double n = std::max(1.0, std::ceil(width / cell_m - 1e-9));
    if (n > 1e7) throw std::invalid_argument("MapGrid::covering: more than 1e7 cells along one side");
    return static_cast<int>(n);
  };
  return MapGrid{xmin, ymin, cell_m, count(xmax - xmin), count(ymax - ymin)};
}

Vec2 MapGrid::cell_centre(int cell) const {
  if (cell < 0 || cell >= cells()) {
    throw std::out_of_range("MapGrid::cell_centre: cell " + std::to_string(cell) + " not in [0, " +
                            std::to_string(cells()) + ")");
  }
  return {xmin + (cell % nx + 0.5) * cell_m, ymin + (cell / nx + 0.5) * cell_m};
}

namespace {

// Index of the grid line at or below coordinate v, clamped to [-1, n] before the
// conversion so that far-away points cannot overflow an int.
int line_below(double v, double origin, double cell, int n) {
  return static_cast<int>(std::clamp(std::floor((v - origin) / cell), -1.0, static_cast<double>(n)));
}

// Separating-axis test of a segment against a closed axis-aligned square: they meet
// unless their boxes are apart or all four corners lie strictly on one side of the line.
bool segment_meets_square(const Vec2& a, const Vec2& b, double x0, double x1, double y0, double y1) {
  if (std::max(a.x(), b.x()) < x0 || std::min(a.x(), b.x()) > x1) return false;
  if (std::max(a.y(), b.y()) < y0 || std::min(a.y(), b.y()) > y1) return false;
  int above = 0, below = 0;
  for (const Vec2& c : {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)}) {
    const double s = cross2(a, b, c);
    above += s > 0.0;
    below += s < 0.0;
  }
  return above < 4 && below < 4;
}

}  // namespace

std::vector<int> cells_crossed(const MapGrid& grid, Vec2 a, Vec2 b) {
  if (!a.allFinite() || !b.allFinite()) throw std::invalid_argument("cells_crossed: non-finite end point");
  std::vector<int> cells;
  if (grid.nx <= 0 || grid.ny <= 0) return cells;
  const double c = grid.cell_m;
  // Candidates column by column from the segment's y-range within the column, widened by
  // one cell each way against rounding; the exact square test then decides.
  const int i0 = std::max(0, line_below(std::min(a.x(), b.x()), grid.xmin, c, grid.nx) - 1);
  const int i1 = std::min(grid.nx - 1, line_below(std::max(a.x(), b.x()), grid.xmin, c, grid.nx) + 1);
  const double dx = b.x() - a.x();
  for (int ix = i0; ix <= i1; ++ix) {
    const double x0 = grid.xmin + ix * c, x1 = grid.xmin + (ix + 1) * c;
    double t0 = 0.0, t1 = 1.0;
    if (dx != 0.0) {
      const double ta = (x0 - a.x()) / dx, tb = (x1 - a.x()) / dx;
      t0 = std::max(0.0, std::min(ta, tb));
      t1 = std::min(1.0, std::max(ta, tb));
      if (t0 > t1) {  // the segment misses this column; keep its nearer end as candidate
        t0 = t1 = std::clamp(0.5 * (ta + tb), 0.0, 1.0);
      }
    }
    const double ya = a.y() + t0 * (b.y() - a.y()), yb = a.y() + t1 * (b.y() - a.y());
    const int j0 = std::max(0, line_below(std::min(ya, yb), grid.ymin, c, grid.ny) - 1);
    const int j1 = std::min(grid.ny - 1, line_below(std::max(ya, yb), grid.ymin, c, grid.ny) + 1);
    for (int iy = j0; iy <= j1; ++iy) {
      if (segment_meets_square(a, b, x0, x1, grid.ymin + iy * c, grid.ymin + (iy + 1) * c)) {
        cells.push_back(iy * grid.nx + ix);
      }
    }
  }
  std::sort(cells.begin(), cells.end());
  return cells;  // each (ix, iy) is visited once, so there are no repeats
}

// --- Accumulator ----------------------------------------------------------------

namespace {

// Ids must be sorted, without repeats and in [0, size): a repeat would count a joint
// twice in one realisation and give fractions above 1.
void check_ids(const std::vector<int>& ids, int size, const char* what, long realisation, std::size_t t) {
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const auto where = [&] {
      return "realisation " + std::to_string(realisation) + ", map time " + std::to_string(t) + ": " + what;
    };
    if (ids[i] < 0 || ids[i] >= size) {
      throw std::invalid_argument(where() + " id " + std::to_string(ids[i]) + " is not in [0, " +
                                  std::to_string(size) + ")");
    }
    if (i > 0 && ids[i] <= ids[i - 1]) {
      throw std::invalid_argument(where() + " ids are not sorted without repeats (" +
                                  std::to_string(ids[i - 1]) + " then " + std::to_string(ids[i]) + ")");
    }
  }
}

long count_at(const std::vector<std::vector<long>>& counts, int t, int id, const char* what) {
  if (t < 0 || static_cast<std::size_t>(t) >= counts.size() || id < 0 ||
      static_cast<std::size_t>(id) >= counts[static_cast<std::size_t>(t)].size()) {
    throw std::out_of_range(std::string("LikelihoodAccumulator: no ") + what + " " + std::to_string(id) +
                            " at map time " + std::to_string(t));
  }
  return counts[static_cast<std::size_t>(t)][static_cast<std::size_t>(id)];
}

void increment(std::vector<long>& counts, const std::vector<int>& ids) {
  for (const int id : ids) ++counts[static_cast<std::size_t>(id)];
}

}  // namespace

LikelihoodAccumulator::LikelihoodAccumulator(std::vector<double> map_times_s, int joints, MapGrid grid)
    : times_(std::move(map_times_s)), joints_(joints), grid_(grid) {
  for (std::size_t t = 0; t < times_.size(); ++t) {
    if (!std::isfinite(times_[t]) || (t > 0 && !(times_[t] > times_[t - 1]))) {
      throw std::invalid_argument("LikelihoodAccumulator: map times must be finite and increasing");
    }
  }
  if (joints_ < 0) throw std::invalid_argument("LikelihoodAccumulator: negative number of joints");
  if (grid_.nx < 0 || grid_.ny < 0 || !(grid_.cell_m > 0.0) ||
      static_cast<long long>(grid_.nx) * grid_.ny > 1'000'000'000LL) {
    throw std::invalid_argument("LikelihoodAccumulator: invalid grid");
  }
  const std::size_t n = times_.size();
  reached_.assign(n, 0);
  open_joint_.assign(n, std::vector<long>(static_cast<std::size_t>(joints_), 0));
  wet_joint_ = open_joint_;
  open_cell_.assign(n, std::vector<long>(static_cast<std::size_t>(grid_.cells()), 0));
  wet_cell_ = open_cell_;
}

void LikelihoodAccumulator::add(const RealisationMaps& r) {
  // Everything is checked before anything is counted: a rejected realisation leaves the
  // counts as they were.
  if (r.snapshots.size() > times_.size()) {
    throw std::invalid_argument("realisation " + std::to_string(r.index) + " has " +
                                std::to_string(r.snapshots.size()) + " snapshots for " +
                                std::to_string(times_.size()) + " map times");
  }
  if (indices_.count(r.index) != 0) {
    throw std::invalid_argument("realisation " + std::to_string(r.index) + " was already added");
  }
  for (std::size_t t = 0; t < r.snapshots.size(); ++t) {
    const MapSnapshot& s = r.snapshots[t];
    check_ids(s.open_joints, joints_, "open joint", r.index, t);
    check_ids(s.wet_joints, joints_, "wet joint", r.index, t);
    check_ids(s.open_cells, grid_.cells(), "open cell", r.index, t);
    check_ids(s.wet_cells, grid_.cells(), "wet cell", r.index, t);
  }
  indices_.insert(r.index);
  for (std::size_t t = 0; t < r.snapshots.size(); ++t) {
    const MapSnapshot& s = r.snapshots[t];
    ++reached_[t];
    increment(open_joint_[t], s.open_joints);
    increment(wet_joint_[t], s.wet_joints);
    increment(open_cell_[t], s.open_cells);
    increment(wet_cell_[t], s.wet_cells);
  }
}

long LikelihoodAccumulator::realisations_at(int t) const {
  if (t < 0 || static_cast<std::size_t>(t) >= reached_.size()) {
    throw std::out_of_range("LikelihoodAccumulator: no map time " + std::to_string(t));
  }
  return reached_[static_cast<std::size_t>(t)];
}
long LikelihoodAccumulator::open_joint_count(int t, int j) const {
  return count_at(open_joint_, t, j, "joint");
}
long LikelihoodAccumulator::wet_joint_count(int t, int j) const {
  return count_at(wet_joint_, t, j, "joint");
}
long LikelihoodAccumulator::open_cell_count(int t, int c) const { return count_at(open_cell_, t, c, "cell"); }
long LikelihoodAccumulator::wet_cell_count(int t, int c) const { return count_at(wet_cell_, t, c, "cell"); }

// --- Convergence --------------------------------------------------------------------

std::vector<ConvergencePoint> grid_convergence(std::vector<RealisationMaps> realisations, const MapGrid& grid,
                                               int t) {
  if (t < 0) throw std::invalid_argument("grid_convergence: negative map time index");
  const auto ts = static_cast<std::size_t>(t);
  std::vector<const RealisationMaps*> reached;
  for (const RealisationMaps& r : realisations) {
    if (r.snapshots.size() > ts) reached.push_back(&r);
  }
  std::sort(reached.begin(), reached.end(), [](auto* x, auto* y) { return x->index < y->index; });
  for (std::size_t i = 0; i < reached.size(); ++i) {
    if (i > 0 && reached[i]->index == reached[i - 1]->index) {
      throw std::invalid_argument("grid_convergence: realisation " + std::to_string(reached[i]->index) +
                                  " appears twice");
    }
    const MapSnapshot& s = reached[i]->snapshots[ts];
    check_ids(s.open_cells, grid.cells(), "open cell", reached[i]->index, ts);
    check_ids(s.wet_cells, grid.cells(), "wet cell", reached[i]->index, ts);
  }
  // Prefix counts over the first N and the first floor(N/2) realisations, each grown by
  // one realisation at a time.
  const auto cells = static_cast<std::size_t>(grid.cells());
  std::vector<long> open_all(cells, 0), wet_all(cells, 0), open_half(cells, 0), wet_half(cells, 0);
  const auto change = [](long half, double n_half, long all, double n_all) {
    return std::abs(static_cast<double>(half) / n_half - static_cast<double>(all) / n_all);
  };
  std::vector<ConvergencePoint> points;
  for (std::size_t n = 1; n <= reached.size(); ++n) {
    increment(open_all, reached[n - 1]->snapshots[ts].open_cells);
    increment(wet_all, reached[n - 1]->snapshots[ts].wet_cells);
    if (n % 2 == 0) {
      increment(open_half, reached[n / 2 - 1]->snapshots[ts].open_cells);
      increment(wet_half, reached[n / 2 - 1]->snapshots[ts].wet_cells);
    }
    if (n < 2) continue;
    const double all = static_cast<double>(n), half = static_cast<double>(n / 2);
    ConvergencePoint p{static_cast<long>(n), 0.0, 0.0};
    for (std::size_t c = 0; c < cells; ++c) {
      p.max_change_open = std::max(p.max_change_open, change(open_half[c], half, open_all[c], all));
      p.max_change_wet = std::max(p.max_change_wet, change(wet_half[c], half, wet_all[c], all));
    }
    points.push_back(p);
  }
  return points;
}

// --- Files --------------------------------------------------------------------------

namespace {

using Fractions = std::array<double, 6>;  // p_open, its low and high, p_wet, low, high
const char* const kFractionNames[6] = {"p_open", "p_open_low", "p_open_high",
                                       "p_wet",  "p_wet_low",  "p_wet_high"};

Fractions fractions(long open, long wet, long n) {
  const ProportionInterval o = wilson_interval(open, n), w = wilson_interval(wet, n);
  return {o.fraction, o.low, o.high, w.fraction, w.low, w.high};
}

std::string csv_row(const std::vector<std::string>& fields, const Fractions& f) {
  std::string out;
  for (const std::string& field : fields) out += field + ",";
  for (std::size_t i = 0; i < f.size(); ++i) out += number_text(f[i]) + (i + 1 < f.size() ? "," : "\n");
  return out;
}

// Lines or quads with `corners` points each, and their integer cell data.
struct VtuMesh {
  std::vector<Vec2> points;
  std::vector<long> connectivity;
  std::size_t corners = 0;
  int vtk_type = 0;  // 3 VTK_LINE, 9 VTK_QUAD
  std::vector<std::pair<std::string, std::vector<long>>> labels;
};

std::string data_array(const char* type, const std::string& name, int components, const std::string& values) {
  return "        <DataArray type=\"" + std::string(type) + "\" Name=\"" + name + "\" NumberOfComponents=\"" +
         std::to_string(components) + "\" format=\"ascii\">\n" + values + "        </DataArray>\n";
}

template <class T, class Text>
std::string lines(const std::vector<T>& values, Text text) {
  std::string out;
  for (const T& v : values) out += text(v) + "\n";
  return out;
}

// ASCII XML UnstructuredGrid (ParaView), the fractions of each cell as cell data.
std::string vtu_text(const VtuMesh& m, const std::vector<Fractions>& cell_fractions) {
  const std::size_t cells = cell_fractions.size();
  const auto integer = [](long v) { return std::to_string(v); };
  std::string connectivity, offsets, types;
  for (std::size_t i = 0; i < m.connectivity.size(); ++i) {
    connectivity += std::to_string(m.connectivity[i]) + ((i + 1) % m.corners != 0 ? " " : "\n");
  }
  for (std::size_t c = 0; c < cells; ++c) {
    offsets += std::to_string((c + 1) * static_cast<std::size_t>(m.corners)) + "\n";
    types += std::to_string(m.vtk_type) + "\n";
  }
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" +
      std::to_string(m.points.size()) + "\" NumberOfCells=\"" + std::to_string(cells) +
      "\">\n      <Points>\n" +
      data_array("Float64", "Points", 3,
                 lines(m.points,
                       [](const Vec2& p) { return number_text(p.x()) + " " + number_text(p.y()) + " 0"; })) +
      "      </Points>\n      <Cells>\n" + data_array("Int64", "connectivity", 1, connectivity) +
      data_array("Int64", "offsets", 1, offsets) + data_array("UInt8", "types", 1, types) +
      "      </Cells>\n      <CellData>\n";
  for (const auto& [name, values] : m.labels) out += data_array("Int32", name, 1, lines(values, integer));
  for (std::size_t i = 0; i < 6; ++i) {
    out += data_array("Float64", kFractionNames[i], 1,
                      lines(cell_fractions, [i](const Fractions& f) { return number_text(f[i]); }));
  }
  return out + "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
}

std::string vtu_name(const std::string& stem, std::size_t k) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%03zu.vtu", stem.c_str(), k);
  return name;
}

std::string pvd_text(const std::vector<double>& times, const std::string& stem) {
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
  for (std::size_t k = 0; k < times.size(); ++k) {
    out += "    <DataSet timestep=\"" + number_text(times[k]) + "\" group=\"\" part=\"0\" file=\"" +
           vtu_name(stem, k) + "\"/>\n";
  }
  return out + "  </Collection>\n</VTKFile>\n";
}

}  // namespace

void write_likelihood_maps(const std::string& dir, const LikelihoodAccumulator& maps,
                           const std::vector<JointSegment>& segments,
                           const std::vector<std::vector<ConvergencePoint>>& convergence_per_time) {
  const std::vector<double>& times = maps.map_times_s();
  if (!segments.empty() && segments.size() != static_cast<std::size_t>(maps.joints())) {
    throw std::invalid_argument("write_likelihood_maps: " + std::to_string(segments.size()) +
                                " joint segments for " + std::to_string(maps.joints()) + " joints");
  }
  if (convergence_per_time.size() > times.size()) {
    throw std::invalid_argument("write_likelihood_maps: convergence given for more times than map times");
  }
  const MapGrid& g = maps.grid();
  const std::string head = "p_open,p_open_low,p_open_high,p_wet,p_wet_low,p_wet_high\n";
  std::string joints_csv = "time_s,joint,x1,y1,x2,y2,natural,realisations," + head;
  std::string grid_csv = "time_s,cell,ix,iy,x_centre,y_centre,realisations," + head;

  // The meshes are the same at every map time; joints do not share points.
  VtuMesh joint_mesh{{}, {}, 2, 3, {{"joint", {}}, {"natural", {}}}};
  for (std::size_t j = 0; j < segments.size(); ++j) {
    joint_mesh.points.insert(joint_mesh.points.end(), {segments[j].a, segments[j].b});
    joint_mesh.connectivity.insert(joint_mesh.connectivity.end(),
                                   {2 * static_cast<long>(j), 2 * static_cast<long>(j) + 1});
    joint_mesh.labels[0].second.push_back(static_cast<long>(j));
    joint_mesh.labels[1].second.push_back(segments[j].natural ? 1 : 0);
  }
  VtuMesh grid_mesh{{}, {}, 4, 9, {{"ix", {}}, {"iy", {}}}};
  const long row = g.nx + 1;
  for (long j = 0; j <= g.ny; ++j) {
    for (long i = 0; i <= g.nx; ++i)
      grid_mesh.points.emplace_back(g.xmin + i * g.cell_m, g.ymin + j * g.cell_m);
  }
  for (long c = 0; c < g.cells(); ++c) {
    const long p = (c / g.nx) * row + c % g.nx;  // lower left, then counter-clockwise
    grid_mesh.connectivity.insert(grid_mesh.connectivity.end(), {p, p + 1, p + 1 + row, p + row});
    grid_mesh.labels[0].second.push_back(c % g.nx);
    grid_mesh.labels[1].second.push_back(c / g.nx);
  }

  for (std::size_t k = 0; k < times.size(); ++k) {
    const int t = static_cast<int>(k);
    const long n = maps.realisations_at(t);
    const std::string time = number_text(times[k]), count = std::to_string(n);
    std::vector<Fractions> joint_fractions, grid_fractions;
    for (std::size_t j = 0; j < segments.size(); ++j) {
      const long open = maps.open_joint_count(t, static_cast<int>(j));
      const long wet = maps.wet_joint_count(t, static_cast<int>(j));
      joint_fractions.push_back(fractions(open, wet, n));
      if (open == 0 && wet == 0) continue;
      const JointSegment& s = segments[j];
      joints_csv += csv_row({time, std::to_string(j), number_text(s.a.x()), number_text(s.a.y()),
                             number_text(s.b.x()), number_text(s.b.y()), s.natural ? "1" : "0", count},
                            joint_fractions.back());
    }
    for (int c = 0; c < g.cells(); ++c) {
      grid_fractions.push_back(fractions(maps.open_cell_count(t, c), maps.wet_cell_count(t, c), n));
      const Vec2 centre = g.cell_centre(c);
      grid_csv += csv_row({time, std::to_string(c), std::to_string(c % g.nx), std::to_string(c / g.nx),
                           number_text(centre.x()), number_text(centre.y()), count},
                          grid_fractions.back());
    }
    io::write_file_atomically(dir + "/" + vtu_name("likelihood_joints", k),
                              vtu_text(joint_mesh, joint_fractions));
    io::write_file_atomically(dir + "/" + vtu_name("likelihood_grid", k),
                              vtu_text(grid_mesh, grid_fractions));
  }
  std::string convergence_csv = "time_s,n,max_change_open,max_change_wet\n";
  for (std::size_t k = 0; k < convergence_per_time.size(); ++k) {
    for (const ConvergencePoint& p : convergence_per_time[k]) {
      convergence_csv += number_text(times[k]) + "," + std::to_string(p.n) + "," +
                         number_text(p.max_change_open) + "," + number_text(p.max_change_wet) + "\n";
    }
  }
  io::write_file_atomically(dir + "/likelihood_joints.csv", joints_csv);
  io::write_file_atomically(dir + "/likelihood_grid.csv", grid_csv);
  io::write_file_atomically(dir + "/likelihood_joints.pvd", pvd_text(times, "likelihood_joints"));
  io::write_file_atomically(dir + "/likelihood_grid.pvd", pvd_text(times, "likelihood_grid"));
  io::write_file_atomically(dir + "/likelihood_convergence.csv", convergence_csv);
}

}  // namespace hfdda::ensemble
