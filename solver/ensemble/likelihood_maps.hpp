#pragma once
// Likelihood maps of a Monte Carlo ensemble (W. E. Morgan, PhD dissertation, Georgia
// Institute of Technology, 2014, sections 5.5 and 5.6, Figures 5.20-5.44): at each map
// time, the fraction of realisations in which a joint is open, or holds fluid, and the
// fraction in which a grid cell contains such a joint, each with its 95 % Wilson score
// interval. The maps depend only on the set of realisations added, never on the order
// they are added in, so that any split of an ensemble over ranks or shards gives the same
// maps byte for byte.

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "core/geometry.hpp"

namespace hfdda::ensemble {

/// Wilson score interval of a binomial proportion (E. B. Wilson, 1927): for k successes
/// in n trials, p = k / n and the interval
///   (p + z^2/(2n) -+ z sqrt(p (1 - p) / n + z^2 / (4 n^2))) / (1 + z^2 / n).
/// n = 0 gives the uninformative [0, 1].
struct ProportionInterval {
  double fraction = 0.0;  ///< k / n (0 when n = 0)
  double low = 0.0;
  double high = 1.0;
};
/// z = 1.959963984540054 is the two-sided 95 % normal quantile.
ProportionInterval wilson_interval(long successes, long trials, double z = 1.959963984540054);

/// A regular grid of square cells over a rectangle (the domain's outer box): cell (ix, iy)
/// covers [xmin + ix c, xmin + (ix+1) c) x [ymin + iy c, ymin + (iy+1) c); its index is
/// iy * nx + ix. The last row and column may stick out of the rectangle.
struct MapGrid {
  double xmin = 0.0, ymin = 0.0;
  double cell_m = 10.0;
  int nx = 0, ny = 0;
  /// The grid with cells of `cell_m` covering [xmin, xmax] x [ymin, ymax].
  static MapGrid covering(double xmin, double xmax, double ymin, double ymax, double cell_m);
  int cells() const { return nx * ny; }
  Vec2 cell_centre(int cell) const;
};

/// The cells whose closed square the segment a-b meets, sorted and without repeats. A
/// segment along a grid line meets the cells on both sides of it; parts outside the grid
/// meet nothing. The test is exact up to the rounding of the cell corners.
std::vector<int> cells_crossed(const MapGrid& grid, Vec2 a, Vec2 b);

/// What one realisation looked like at one map time: sorted ids of open joints and of
/// joints holding fluid, and sorted indices of the grid cells that contain one.
struct MapSnapshot {
  std::vector<int> open_joints, wet_joints;
  std::vector<int> open_cells, wet_cells;
};

/// A realisation's contribution: its index in the ensemble and one snapshot per map time
/// it reached (a realisation that stopped early has fewer; it counts at those times only).
struct RealisationMaps {
  long index = 0;
  std::vector<MapSnapshot> snapshots;  ///< snapshots[t] at map_times[t], t < size()
};

/// Counts over the realisations added so far, per map time, per joint and per cell.
class LikelihoodAccumulator {
 public:
  /// joints = 0: grid maps only (realisations on different meshes).
  LikelihoodAccumulator(std::vector<double> map_times_s, int joints, MapGrid grid);

  /// Adds one realisation. Throws std::invalid_argument for an id out of range, ids not
  /// sorted or repeated, more snapshots than map times, or an index already added; a
  /// rejected realisation changes no count.
  void add(const RealisationMaps& realisation);

  const std::vector<double>& map_times_s() const { return times_; }
  const MapGrid& grid() const { return grid_; }
  int joints() const { return joints_; }
  /// Realisations that reached map time t (the denominator of every fraction at t).
  /// The getters throw std::out_of_range for a time, joint or cell out of range.
  long realisations_at(int t) const;
  long open_joint_count(int t, int joint) const;
  long wet_joint_count(int t, int joint) const;
  long open_cell_count(int t, int cell) const;
  long wet_cell_count(int t, int cell) const;

 private:
  std::vector<double> times_;
  int joints_;
  MapGrid grid_;
  std::vector<long> reached_;
  std::set<long> indices_;  ///< of the realisations added, to refuse one added twice
  std::vector<std::vector<long>> open_joint_, wet_joint_, open_cell_, wet_cell_;  ///< [t][id]
};

/// Convergence of the grid map at time index t (issue: "the largest change of the grid
/// map between the first N/2 and all N realisations, against N"): realisations sorted by
/// index; for each N from 2 to their number, the max over cells of |fraction over the
/// first floor(N/2) - fraction over the first N|, for the open and for the wet map,
/// counting only the realisations that reached t (empty when fewer than 2 did).
/// Throws std::invalid_argument for a cell id out of range or an index given twice.
struct ConvergencePoint {
  long n = 0;
  double max_change_open = 0.0;
  double max_change_wet = 0.0;
};
std::vector<ConvergencePoint> grid_convergence(std::vector<RealisationMaps> realisations, const MapGrid& grid, int t);

/// The geometry of the mesh joints, for the per-joint outputs.
struct JointSegment {
  Vec2 a, b;
  bool natural = false;
};

/// Writes, atomically (io::write_file_atomically), into `dir`:
///  - likelihood_joints.csv: time_s, joint, x1, y1, x2, y2, natural, realisations,
///    p_open, p_open_low, p_open_high, p_wet, p_wet_low, p_wet_high (one row per map time
///    and joint that is open or wet in at least one realisation at that time);
///  - likelihood_grid.csv: time_s, cell, ix, iy, x_centre, y_centre, realisations, the
///    same six columns (every cell, every time);
///  - likelihood_joints_<k>.vtu and likelihood_grid_<k>.vtu per map time k (k from 0, 3
///    digits) with the same fractions as cell data, and likelihood_joints.pvd,
///    likelihood_grid.pvd listing them with their times (ParaView);
///  - likelihood_convergence.csv: time_s, n, max_change_open, max_change_wet.
/// Numbers are written with the shortest text that reads back exactly (core/number_text),
/// so equal counts give equal files. `segments` may be empty (grid maps only: the joint
/// files then have no rows or cells); otherwise it has one segment per joint.
/// convergence_per_time[t] belongs to map time t and may stop before the last time.
void write_likelihood_maps(const std::string& dir, const LikelihoodAccumulator& maps,
                           const std::vector<JointSegment>& segments,
                           const std::vector<std::vector<ConvergencePoint>>& convergence_per_time);

}  // namespace hfdda::ensemble
