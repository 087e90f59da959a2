#pragma once
// Output contract of a run directory (later issues and users rely on it):
//   summary.json              status (completed, failed, interrupted), steps, wall time, statistics;
//                             with keys given as distributions, random_seed and sampled_parameters
//                             (each key's law and its value, or the count, min, mean and max of its draws)
//   history.csv               one row per step
//   joints/joints_NNNNNN.csv  per-joint state at output times; joints/joints_final.csv
//   vtu/blocks_NNNNNN.vtu, vtu/joints_NNNNNN.vtu with blocks.pvd and joints.pvd series
//   checkpoint.bin            state to restart from (simulation/checkpoint.hpp)
//   iterations.csv            with --trace-iterations: a row per open-close iteration and per
//                             attempt at a step (simulation/iteration_trace.hpp)
// Every file is written to a temporary name and renamed, so none is ever half-written;
// history.csv is created that way and then appended one whole line per write.

#include <Eigen/Core>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry.hpp"

namespace hfdda::io {

/// Block field at one output time (current geometry).
struct BlockFrame {
  std::vector<Vec2> corners;             ///< all blocks' corners, block after block [m]
  std::vector<int> corner_offsets;       ///< size n_blocks + 1, CSR offsets into corners
  std::vector<Vec2> corner_displacement; ///< total displacement since t = 0 [m]
  std::vector<Eigen::Vector3d> stress;   ///< (sxx, syy, sxy) per block, tension positive [Pa]
  std::vector<int> material;             ///< material index per block
};

/// One joint at one output time. End "p" and "q" follow the mesh joint's points.
struct JointRow {
  int id = 0;
  Vec2 p{0, 0}, q{0, 0};                 ///< current end points (mean of the two faces) [m]
  double length_m = 0.0;
  double aperture_p_m = 0.0, aperture_q_m = 0.0;  ///< normal separation at each end, >= 0
  double normal_stress_p_Pa = 0.0, normal_stress_q_Pa = 0.0;  ///< contact stress, tension +
  double shear_stress_p_Pa = 0.0, shear_stress_q_Pa = 0.0;
  std::string state_p, state_q;          ///< "open", "sliding", "locked"
  bool broken = false, natural = false, fluid = false;
  double pressure_p_Pa = 0.0, pressure_q_Pa = 0.0;  ///< fluid pressure at the end points (0 if dry)
};

/// Writes `text` to `path` atomically (temporary file + rename). Throws std::runtime_error.
void write_file_atomically(const std::string& path, const std::string& text);

/// Per-joint CSV, one row per joint; header:
/// id,px,py,qx,qy,length,aperture_p,aperture_q,normal_stress_p,normal_stress_q,
/// shear_stress_p,shear_stress_q,state_p,state_q,broken,natural,fluid,pressure_p,pressure_q
void write_joints_csv(const std::string& path, const std::vector<JointRow>& joints);

/// VTK XML unstructured grid of the blocks (polygons) with point data
/// "displacement" and cell data "stress" (3 components), "material".
void write_blocks_vtu(const std::string& path, const BlockFrame& frame);

/// VTK XML unstructured grid of the joints as lines with cell data "aperture"
/// (mean of both ends), "normal_stress", "shear_stress", "state" (0 open, 1 sliding,
/// 2 locked, taking the more open end), "broken", "natural", "fluid".
void write_joints_vtu(const std::string& path, const std::vector<JointRow>& joints);

/// An integer value per line of write_lines_vtu, shown in ParaView under `name`.
struct LineCellData {
  std::string name;
  std::vector<int> values;
};

/// VTK XML unstructured grid of straight lines (p, q) with integer cell data (each
/// array one value per line). Throws std::invalid_argument on an array of another size.
void write_lines_vtu(const std::string& path, const std::vector<std::pair<Vec2, Vec2>>& lines,
                     const std::vector<LineCellData>& cell_data);

/// A ParaView .pvd collection: datasets with their times, rewritten atomically on add().
class PvdSeries {
 public:
  using Entries = std::vector<std::pair<double, std::string>>;
  explicit PvdSeries(std::string path) : path_(std::move(path)) {}
  void add(double time_s, const std::string& relative_file);
  const Entries& entries() const { return entries_; }
  /// Replaces the datasets (a restarted run) and rewrites the file.
  void restore(Entries entries);

 private:
  void write() const;
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

/// history.csv: fixed columns, one row appended per step. The header and `rows` (the
/// rows kept from before a restart) are written to a temporary file that is renamed;
/// each later row is then appended with a single write and flushed, so a run that is
/// killed leaves whole lines only.
class HistoryCsv {
 public:
  HistoryCsv(const std::string& path, std::vector<std::string> columns,
             const std::vector<std::vector<double>>& rows = {});
  void append(const std::vector<double>& values);  ///< size must equal columns

 private:
  std::vector<std::string> columns_;
  std::ofstream out_;
};

}  // namespace hfdda::io
