// Likelihood maps of an ensemble (solver/ensemble/likelihood_maps.hpp): Wilson intervals
// against hand values and by coverage, the cells a segment meets, the counts of
// synthetic realisations whatever order they come in, the convergence of the grid map,
// and the files, which must not depend on that order either.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ensemble/likelihood_maps.hpp"

namespace hfdda::ensemble {
namespace {

namespace fs = std::filesystem;

// --- Wilson interval -----------------------------------------------------------------

TEST(WilsonInterval, MatchesHandValues) {
  const ProportionInterval none = wilson_interval(0, 10);
  EXPECT_EQ(none.fraction, 0.0);
  EXPECT_EQ(none.low, 0.0);
  EXPECT_NEAR(none.high, 0.2775, 5e-5);
  const ProportionInterval half = wilson_interval(5, 10);
  EXPECT_EQ(half.fraction, 0.5);
  EXPECT_NEAR(half.low, 0.2366, 5e-5);
  EXPECT_NEAR(half.high, 0.7634, 5e-5);
  const ProportionInterval all = wilson_interval(10, 10);
  EXPECT_EQ(all.fraction, 1.0);
  EXPECT_EQ(all.high, 1.0);
  EXPECT_NEAR(all.low, 1.0 - 0.2775, 5e-5);
  // z = 1, k = 1 of 4: centre 3/8, half-width 1/4, scale 5/4, so [0.1, 0.5] exactly.
  const ProportionInterval z1 = wilson_interval(1, 4, 1.0);
  EXPECT_DOUBLE_EQ(z1.low, 0.1);
  EXPECT_DOUBLE_EQ(z1.high, 0.5);
}

TEST(WilsonInterval, NoTrialsIsUninformative) {
  const ProportionInterval w = wilson_interval(0, 0);
  EXPECT_EQ(w.fraction, 0.0);
  EXPECT_EQ(w.low, 0.0);
  EXPECT_EQ(w.high, 1.0);
}

TEST(WilsonInterval, ContainsTheFractionAndIsSymmetric) {
  for (long n = 1; n <= 60; ++n) {
    for (long k = 0; k <= n; ++k) {
      const ProportionInterval w = wilson_interval(k, n), mirror = wilson_interval(n - k, n);
      EXPECT_EQ(w.fraction, static_cast<double>(k) / static_cast<double>(n));
      EXPECT_LE(0.0, w.low);
      EXPECT_LE(w.low, w.fraction);
      EXPECT_LE(w.fraction, w.high);
      EXPECT_LE(w.high, 1.0);
      EXPECT_NEAR(w.low, 1.0 - mirror.high, 1e-12) << k << " of " << n;
      EXPECT_NEAR(w.high, 1.0 - mirror.low, 1e-12) << k << " of " << n;
    }
  }
}

TEST(WilsonInterval, CoversNinetyFivePercentOfBinomialDraws) {
  std::mt19937_64 rng(20140501);
  const double p = 0.3;
  const long n = 50, trials = 20000;
  std::binomial_distribution<long> binomial(n, p);
  long covered = 0;
  for (long i = 0; i < trials; ++i) {
    const ProportionInterval w = wilson_interval(binomial(rng), n);
    covered += w.low <= p && p <= w.high;
  }
  const double coverage = static_cast<double>(covered) / static_cast<double>(trials);
  EXPECT_GE(coverage, 0.93);
  EXPECT_LE(coverage, 0.97);
}

TEST(WilsonInterval, RefusesImpossibleCounts) {
  EXPECT_THROW(wilson_interval(11, 10), std::invalid_argument);
  EXPECT_THROW(wilson_interval(-1, 10), std::invalid_argument);
  EXPECT_THROW(wilson_interval(0, -1), std::invalid_argument);
  EXPECT_THROW(wilson_interval(1, 2, 0.0), std::invalid_argument);
}

// --- Grid and segments --------------------------------------------------------------

TEST(MapGrid, CoversTheRectangle) {
  const MapGrid g = MapGrid::covering(-50, 45, 0, 30, 10);
  EXPECT_EQ(g.nx, 10);  // the last column sticks out by 5 m
  EXPECT_EQ(g.ny, 3);
  EXPECT_EQ(g.cells(), 30);
  EXPECT_EQ(g.cell_centre(0), Vec2(-45, 5));
  EXPECT_EQ(g.cell_centre(13), Vec2(-15, 15));  // ix 3, iy 1
  // Widths that are whole numbers of cells but divide with rounding either way:
  // 2.1 / 0.7 = 3.0000000000000004 gets no sliver column, 0.7 / 0.1 = 6.999... no gap.
  const MapGrid fine = MapGrid::covering(0, 2.1, 0, 0.7, 0.7);
  EXPECT_EQ(fine.nx, 3);
  EXPECT_EQ(MapGrid::covering(0, 0.7, 0, 0.3, 0.1).nx, 7);
  EXPECT_THROW(MapGrid::covering(0, 10, 0, 10, 0), std::invalid_argument);
  EXPECT_THROW(MapGrid::covering(10, 0, 0, 10, 1), std::invalid_argument);
  EXPECT_THROW(g.cell_centre(30), std::out_of_range);
}

// 4 x 3 cells of 10 m from the origin: cell = iy * 4 + ix.
const MapGrid kGrid = MapGrid::covering(0, 40, 0, 30, 10);

std::vector<int> crossed(double ax, double ay, double bx, double by) {
  const std::vector<int> forward = cells_crossed(kGrid, {ax, ay}, {bx, by});
  EXPECT_EQ(forward, cells_crossed(kGrid, {bx, by}, {ax, ay})) << "direction matters";
  return forward;
}
using Cells = std::vector<int>;

TEST(CellsCrossed, HorizontalVerticalAndDiagonal) {
  EXPECT_EQ(crossed(1, 5, 35, 5), (Cells{0, 1, 2, 3}));
  EXPECT_EQ(crossed(1, 5, 25, 5), (Cells{0, 1, 2}));
  EXPECT_EQ(crossed(15, 1, 15, 25), (Cells{1, 5, 9}));
  EXPECT_EQ(crossed(1, 2, 19, 8), (Cells{0, 1}));
  EXPECT_EQ(crossed(1, 1, 39, 29), (Cells{0, 1, 5, 6, 10, 11}));
  // Through the corner (10, 10): the two squares that only touch it are met as well.
  EXPECT_EQ(crossed(5, 5, 15, 15), (Cells{0, 1, 4, 5}));
}

TEST(CellsCrossed, AlongAGridLineMeetsBothSides) {
  EXPECT_EQ(crossed(10, 2, 10, 8), (Cells{0, 1}));
  EXPECT_EQ(crossed(2, 10, 18, 10), (Cells{0, 1, 4, 5}));
  EXPECT_EQ(crossed(0, 2, 0, 8), (Cells{0}));          // the outer edge: no cell beyond
  EXPECT_EQ(crossed(12, 30, 28, 30), (Cells{9, 10}));  // the top edge
  EXPECT_EQ(crossed(10, 0, 10, 30), (Cells{0, 1, 4, 5, 8, 9}));
}

TEST(CellsCrossed, ClipsToTheGrid) {
  EXPECT_EQ(crossed(-20, -20, -5, -5), Cells{});
  EXPECT_EQ(crossed(-15, 5, 5, 5), (Cells{0}));
  EXPECT_EQ(crossed(-100, 5, 100, 5), (Cells{0, 1, 2, 3}));
  EXPECT_EQ(crossed(35, 25, 80, 25), (Cells{11}));
  EXPECT_EQ(crossed(45, -5, 50, 40), Cells{});
  EXPECT_EQ(crossed(-5, 25, 5, 35), (Cells{8}));  // cuts the top-left corner
  EXPECT_EQ(crossed(-5, 35, 5, 45), Cells{});     // passes it by
  EXPECT_EQ(crossed(-1e300, 5, 1e300, 5), (Cells{0, 1, 2, 3}));
  EXPECT_THROW(cells_crossed(kGrid, {0, 0}, {std::nan(""), 1}), std::invalid_argument);
}

TEST(CellsCrossed, APointMeetsTheSquaresHoldingIt) {
  EXPECT_EQ(crossed(15, 15, 15, 15), (Cells{5}));
  EXPECT_EQ(crossed(10, 10, 10, 10), (Cells{0, 1, 4, 5}));
  EXPECT_EQ(crossed(40, 30, 40, 30), (Cells{11}));
  EXPECT_EQ(crossed(50, 15, 50, 15), Cells{});
}

// Reference by Liang-Barsky clipping against every cell: a different algorithm, exact
// here because every coordinate is a multiple of 0.5.
bool clip_meets(Vec2 a, Vec2 b, double x0, double x1, double y0, double y1) {
  double t0 = 0.0, t1 = 1.0;
  const double d[2] = {b.x() - a.x(), b.y() - a.y()}, s[2] = {a.x(), a.y()};
  const double lo[2] = {x0, y0}, hi[2] = {x1, y1};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (s[k] < lo[k] || s[k] > hi[k]) return false;
      continue;
    }
    const double ta = (lo[k] - s[k]) / d[k], tb = (hi[k] - s[k]) / d[k];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return t0 <= t1;
}

TEST(CellsCrossed, AgreesWithClippingOnRandomSegments) {
  const MapGrid grid = MapGrid::covering(-20, 20, -10, 15, 2.5);
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> half_metres(-50, 50);  // [-25, 25] m in steps of 0.5
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec2 a(0.5 * half_metres(rng), 0.5 * half_metres(rng));
    const Vec2 b = trial % 5 == 0 ? Vec2(a.x(), 0.5 * half_metres(rng))
                                  : Vec2(0.5 * half_metres(rng), 0.5 * half_metres(rng));
    Cells expected;
    for (int c = 0; c < grid.cells(); ++c) {
      const double x0 = grid.xmin + (c % grid.nx) * grid.cell_m, y0 = grid.ymin + (c / grid.nx) * grid.cell_m;
      if (clip_meets(a, b, x0, x0 + grid.cell_m, y0, y0 + grid.cell_m)) expected.push_back(c);
    }
    ASSERT_EQ(cells_crossed(grid, a, b), expected) << a.transpose() << " - " << b.transpose();
  }
}

// --- Accumulator --------------------------------------------------------------------

// Four realisations on 5 joints and a 2 x 2 grid, at map times 60 s and 120 s; the
// last one stopped before 120 s.
std::vector<RealisationMaps> synthetic_realisations() {
  std::vector<RealisationMaps> r(4);
  r[0] = {10, {{{1, 3}, {3}, {0}, {0}}, {{1, 3, 4}, {3, 4}, {0, 1}, {0, 1}}}};
  r[1] = {11, {{{3}, {}, {2}, {}}, {{3}, {3}, {2}, {2}}}};
  r[2] = {12, {{{}, {}, {}, {}}, {{0}, {0}, {3}, {3}}}};
  r[3] = {13, {{{0, 3}, {0, 3}, {1, 2}, {1}}}};
  return r;
}
const MapGrid kSmallGrid = MapGrid::covering(0, 20, 0, 20, 10);

LikelihoodAccumulator accumulate(const std::vector<RealisationMaps>& realisations) {
  LikelihoodAccumulator maps({60.0, 120.0}, 5, kSmallGrid);
  for (const RealisationMaps& r : realisations) maps.add(r);
  return maps;
}

TEST(LikelihoodAccumulator, CountsOpenAndWetJointsAndCells) {
  const LikelihoodAccumulator maps = accumulate(synthetic_realisations());
  EXPECT_EQ(maps.realisations_at(0), 4);
  EXPECT_EQ(maps.realisations_at(1), 3);  // realisation 13 counts at 60 s only
  EXPECT_EQ(maps.open_joint_count(0, 3), 3);
  EXPECT_EQ(wilson_interval(maps.open_joint_count(0, 3), maps.realisations_at(0)).fraction, 0.75);
  EXPECT_EQ(maps.wet_joint_count(0, 3), 2);
  EXPECT_EQ(maps.open_joint_count(0, 0), 1);
  EXPECT_EQ(maps.open_joint_count(1, 0), 1);
  EXPECT_EQ(maps.open_joint_count(1, 4), 1);
  EXPECT_EQ(maps.wet_joint_count(1, 1), 0);
  EXPECT_EQ(maps.open_cell_count(0, 2), 2);
  EXPECT_EQ(maps.wet_cell_count(0, 2), 0);
  EXPECT_EQ(maps.wet_cell_count(0, 1), 1);
  EXPECT_EQ(maps.wet_cell_count(1, 2), 1);
  EXPECT_EQ(maps.open_cell_count(1, 1), 1);
  EXPECT_THROW(maps.open_joint_count(2, 0), std::out_of_range);
  EXPECT_THROW(maps.wet_cell_count(0, 4), std::out_of_range);
  EXPECT_THROW(maps.realisations_at(2), std::out_of_range);
}

TEST(LikelihoodAccumulator, OrderOfAddingChangesNoCount) {
  std::vector<RealisationMaps> r = synthetic_realisations();
  const LikelihoodAccumulator reference = accumulate(r);
  std::sort(r.begin(), r.end(), [](const auto& x, const auto& y) { return x.index < y.index; });
  do {
    const LikelihoodAccumulator maps = accumulate(r);
    for (int t = 0; t < 2; ++t) {
      ASSERT_EQ(maps.realisations_at(t), reference.realisations_at(t));
      for (int j = 0; j < 5; ++j) {
        ASSERT_EQ(maps.open_joint_count(t, j), reference.open_joint_count(t, j));
        ASSERT_EQ(maps.wet_joint_count(t, j), reference.wet_joint_count(t, j));
      }
      for (int c = 0; c < 4; ++c) {
        ASSERT_EQ(maps.open_cell_count(t, c), reference.open_cell_count(t, c));
        ASSERT_EQ(maps.wet_cell_count(t, c), reference.wet_cell_count(t, c));
      }
    }
  } while (std::next_permutation(r.begin(), r.end(),
                                 [](const auto& x, const auto& y) { return x.index < y.index; }));
}

void expect_rejected(LikelihoodAccumulator& maps, const RealisationMaps& r, const std::string& words) {
  try {
    maps.add(r);
    ADD_FAILURE() << "accepted: " << words;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(LikelihoodAccumulator, RefusesInvalidRealisations) {
  LikelihoodAccumulator maps({60.0, 120.0}, 5, kSmallGrid);
  maps.add({1, {{{0}, {0}, {0}, {0}}}});
  expect_rejected(maps, {2, {{{5}, {}, {}, {}}}}, "open joint id 5 is not in [0, 5)");
  expect_rejected(maps, {2, {{{}, {-1}, {}, {}}}}, "wet joint id -1");
  expect_rejected(maps, {2, {{}, {{}, {}, {4}, {}}}}, "map time 1: open cell id 4 is not in [0, 4)");
  expect_rejected(maps, {2, {{{}, {}, {}, {3, 1}}}}, "wet cell ids are not sorted");
  expect_rejected(maps, {2, {{{2, 2}, {}, {}, {}}}}, "not sorted without repeats");
  expect_rejected(maps, {2, {{}, {}, {}}}, "3 snapshots for 2 map times");
  expect_rejected(maps, {1, {{}}}, "realisation 1 was already added");
  // Nothing of the rejected realisations was counted.
  EXPECT_EQ(maps.realisations_at(0), 1);
  EXPECT_EQ(maps.realisations_at(1), 0);
  EXPECT_EQ(maps.open_joint_count(0, 2), 0);
  // joints = 0: grid maps only, so any joint id is out of range.
  LikelihoodAccumulator grid_only({60.0}, 0, kSmallGrid);
  grid_only.add({1, {{{}, {}, {1}, {1}}}});
  expect_rejected(grid_only, {2, {{{0}, {}, {}, {}}}}, "open joint id 0 is not in [0, 0)");
  EXPECT_THROW(LikelihoodAccumulator({120.0, 60.0}, 1, kSmallGrid), std::invalid_argument);
}

// --- Convergence --------------------------------------------------------------------

TEST(GridConvergence, MatchesAHandComputation) {
  // Two cells; at time 0, by index: open {0} {} {0,1} {1}, wet {0} {0,1} {0} {}. Index 5
  // never reached time 0 and is left out.
  std::vector<RealisationMaps> r = {{3, {{{1}, {}, {1}, {}}}},
                                    {5, {}},
                                    {1, {{{}, {}, {}, {0, 1}}}},
                                    {0, {{{}, {}, {0}, {0}}}},
                                    {2, {{{}, {}, {0, 1}, {0}}}}};
  const MapGrid grid = MapGrid::covering(0, 20, 0, 10, 10);
  const std::vector<ConvergencePoint> points = grid_convergence(r, grid, 0);
  ASSERT_EQ(points.size(), 3u);
  // N = 2: first 1 open (1, 0), wet (1, 0); first 2 open (1/2, 0), wet (1, 1/2).
  EXPECT_EQ(points[0].n, 2);
  EXPECT_DOUBLE_EQ(points[0].max_change_open, 0.5);
  EXPECT_DOUBLE_EQ(points[0].max_change_wet, 0.5);
  // N = 3: first 1 as above; first 3 open (2/3, 1/3), wet (1, 1/3).
  EXPECT_EQ(points[1].n, 3);
  EXPECT_DOUBLE_EQ(points[1].max_change_open, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(points[1].max_change_wet, 1.0 / 3.0);
  // N = 4: first 2 open (1/2, 0), wet (1, 1/2); all 4 open (1/2, 1/2), wet (3/4, 1/4).
  EXPECT_EQ(points[2].n, 4);
  EXPECT_DOUBLE_EQ(points[2].max_change_open, 0.5);
  EXPECT_DOUBLE_EQ(points[2].max_change_wet, 0.25);

  std::reverse(r.begin(), r.end());
  const std::vector<ConvergencePoint> again = grid_convergence(r, grid, 0);
  for (std::size_t i = 0; i < points.size(); ++i)
    EXPECT_EQ(again[i].max_change_wet, points[i].max_change_wet);
  EXPECT_TRUE(grid_convergence(r, grid, 1).empty());  // nobody reached time 1
  r.push_back({3, {{}}});
  EXPECT_THROW(grid_convergence(r, grid, 0), std::invalid_argument);
}

// --- Files --------------------------------------------------------------------------

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("hfdda_likelihood_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Rows of a CSV file as column name -> text.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& path) {
  std::istringstream in(read_text(path));
  std::vector<std::vector<std::string>> lines;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    lines.emplace_back();
    for (std::string f; std::getline(fields, f, ',');) lines.back().push_back(f);
  }
  std::vector<std::map<std::string, std::string>> rows;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].size(), lines[0].size()) << path << " line " << i + 1;
    rows.emplace_back();
    for (std::size_t k = 0; k < std::min(lines[i].size(), lines[0].size()); ++k)
      rows.back()[lines[0][k]] = lines[i][k];
  }
  return rows;
}

const std::vector<JointSegment> kSegments = {{{1, 1}, {9, 1}, false},
                                             {{9, 1}, {11, 9}, true},
                                             {{11, 9}, {19, 19}, false},
                                             {{2, 12}, {8, 18}, true},
                                             {{0, 0}, {20, 20}, true}};

void write_maps(const fs::path& dir, const std::vector<RealisationMaps>& realisations) {
  const LikelihoodAccumulator maps = accumulate(realisations);
  write_likelihood_maps(
      dir.string(), maps, kSegments,
      {grid_convergence(realisations, kSmallGrid, 0), grid_convergence(realisations, kSmallGrid, 1)});
}

// The synthetic realisations and 60 random ones (indices from 100), each joint and cell
// open with probability 0.4 and then wet with probability 0.5.
std::vector<RealisationMaps> many_realisations() {
  std::vector<RealisationMaps> r = synthetic_realisations();
  std::mt19937_64 rng(42);
  std::bernoulli_distribution open(0.4), wet(0.5), early(0.3);
  for (long i = 0; i < 60; ++i) {
    RealisationMaps m{100 + i, std::vector<MapSnapshot>(early(rng) ? 1 : 2)};
    for (MapSnapshot& s : m.snapshots) {
      for (int id = 0; id < 5; ++id) {
        if (open(rng)) s.open_joints.push_back(id);
        if (id < 4 && open(rng)) s.open_cells.push_back(id);
        if (wet(rng)) s.wet_joints.push_back(id);
        if (id < 4 && wet(rng)) s.wet_cells.push_back(id);
      }
    }
    r.push_back(m);
  }
  return r;
}

TEST(LikelihoodMapFiles, DoNotDependOnTheOrderOfRealisations) {
  TempDir tmp;
  std::vector<RealisationMaps> r = many_realisations();
  write_maps(tmp.path / "a", r);
  std::shuffle(r.begin(), r.end(), std::mt19937_64(3));
  write_maps(tmp.path / "b", r);
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(tmp.path / "a"))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{
                       "likelihood_convergence.csv", "likelihood_grid.csv", "likelihood_grid.pvd",
                       "likelihood_grid_000.vtu", "likelihood_grid_001.vtu", "likelihood_joints.csv",
                       "likelihood_joints.pvd", "likelihood_joints_000.vtu", "likelihood_joints_001.vtu"}));
  for (const std::string& name : names) {
    EXPECT_EQ(read_text(tmp.path / "a" / name), read_text(tmp.path / "b" / name)) << name;
  }
  const std::string grid_vtu = read_text(tmp.path / "a" / "likelihood_grid_000.vtu");
  EXPECT_NE(grid_vtu.find("NumberOfPoints=\"9\" NumberOfCells=\"4\""), std::string::npos);
  EXPECT_NE(grid_vtu.find("0 1 4 3\n"), std::string::npos);  // counter-clockwise quad
  EXPECT_NE(read_text(tmp.path / "a" / "likelihood_joints.pvd").find("timestep=\"120\""), std::string::npos);
}

// The numbers of the DataArray called `name` in a VTU text.
std::vector<double> vtu_array(const std::string& vtu, const std::string& name) {
  const std::size_t start = vtu.find(">\n", vtu.find("Name=\"" + name + "\"")) + 2;
  std::istringstream in(vtu.substr(start, vtu.find("</DataArray>", start) - start));
  std::vector<double> values;
  for (double v; in >> v;) values.push_back(v);
  return values;
}

TEST(LikelihoodMapFiles, HoldTheFractionsAndTheirIntervals) {
  TempDir tmp;
  const std::vector<RealisationMaps> r = synthetic_realisations();
  write_maps(tmp.path, r);
  const LikelihoodAccumulator maps = accumulate(r);
  const auto check = [](const std::map<std::string, std::string>& row, long open, long wet, long n) {
    const ProportionInterval o = wilson_interval(open, n), w = wilson_interval(wet, n);
    EXPECT_EQ(std::stol(row.at("realisations")), n);
    const std::vector<double> expected = {o.fraction, o.low, o.high, w.fraction, w.low, w.high};
    const char* names[] = {"p_open", "p_open_low", "p_open_high", "p_wet", "p_wet_low", "p_wet_high"};
    for (int i = 0; i < 6; ++i) EXPECT_EQ(std::stod(row.at(names[i])), expected[i]) << names[i];
  };
  const auto grid_rows = read_csv(tmp.path / "likelihood_grid.csv");
  ASSERT_EQ(grid_rows.size(), 8u);  // every cell at both times
  for (const auto& row : grid_rows) {
    const int t = row.at("time_s") == "60" ? 0 : 1, c = std::stoi(row.at("cell"));
    check(row, maps.open_cell_count(t, c), maps.wet_cell_count(t, c), maps.realisations_at(t));
    EXPECT_EQ(Vec2(std::stod(row.at("x_centre")), std::stod(row.at("y_centre"))), kSmallGrid.cell_centre(c));
  }
  const auto joint_rows = read_csv(tmp.path / "likelihood_joints.csv");
  ASSERT_EQ(joint_rows.size(), 7u);  // joints 0, 1, 3 at 60 s; 0, 1, 3, 4 at 120 s
  for (const auto& row : joint_rows) {
    const int t = row.at("time_s") == "60" ? 0 : 1, j = std::stoi(row.at("joint"));
    check(row, maps.open_joint_count(t, j), maps.wet_joint_count(t, j), maps.realisations_at(t));
    EXPECT_EQ(row.at("natural"), kSegments.at(j).natural ? "1" : "0");
    EXPECT_EQ(std::stod(row.at("x2")), kSegments.at(j).b.x());
  }
  EXPECT_EQ(joint_rows[2].at("joint"), "3");
  EXPECT_EQ(joint_rows[2].at("p_open"), "0.75");
  const auto convergence = read_csv(tmp.path / "likelihood_convergence.csv");
  ASSERT_EQ(convergence.size(), 3u + 2u);  // N = 2..4 at 60 s, N = 2..3 at 120 s
  EXPECT_EQ(convergence[3].at("time_s"), "120");
  EXPECT_EQ(convergence[3].at("n"), "2");

  // The VTU files: every cell and every joint, open or not.
  for (int t = 0; t < 2; ++t) {
    const std::string suffix = t == 0 ? "_000.vtu" : "_001.vtu";
    const double n = static_cast<double>(maps.realisations_at(t));
    const std::string grid = read_text(tmp.path / ("likelihood_grid" + suffix));
    const std::string joints = read_text(tmp.path / ("likelihood_joints" + suffix));
    const std::vector<double> open = vtu_array(grid, "p_open"), wet = vtu_array(grid, "p_wet");
    const std::vector<double> joint_open = vtu_array(joints, "p_open"),
                              high = vtu_array(joints, "p_wet_high");
    ASSERT_EQ(open.size(), 4u);
    ASSERT_EQ(wet.size(), 4u);
    ASSERT_EQ(joint_open.size(), 5u);
    for (int c = 0; c < 4; ++c) {
      EXPECT_EQ(open.at(c), static_cast<double>(maps.open_cell_count(t, c)) / n);
      EXPECT_EQ(wet.at(c), static_cast<double>(maps.wet_cell_count(t, c)) / n);
    }
    for (int j = 0; j < 5; ++j) {
      EXPECT_EQ(joint_open.at(j), static_cast<double>(maps.open_joint_count(t, j)) / n);
      EXPECT_EQ(high.at(j), wilson_interval(maps.wet_joint_count(t, j), maps.realisations_at(t)).high);
    }
    EXPECT_EQ(vtu_array(joints, "types"), std::vector<double>(5, 3.0));  // VTK_LINE
    EXPECT_EQ(vtu_array(grid, "types"), std::vector<double>(4, 9.0));    // VTK_QUAD
  }
}

TEST(LikelihoodMapFiles, RefuseSegmentsThatDoNotMatchTheJoints) {
  TempDir tmp;
  const LikelihoodAccumulator maps = accumulate(synthetic_realisations());
  EXPECT_THROW(write_likelihood_maps(tmp.path.string(), maps, {kSegments[0]}, {}), std::invalid_argument);
  write_likelihood_maps(tmp.path.string(), maps, {}, {});  // grid maps only
  EXPECT_EQ(read_csv(tmp.path / "likelihood_joints.csv").size(), 0u);
  EXPECT_EQ(read_csv(tmp.path / "likelihood_grid.csv").size(), 8u);
}

}  // namespace
}  // namespace hfdda::ensemble
