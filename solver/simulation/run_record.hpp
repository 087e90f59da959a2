#pragma once
// The one schema of a run's per-step output: a registry of columns (name, unit,
// description, how to compute the value from the step's context) that feeds
// history.csv, the in-memory RunRecord returned by simulation::run, and the column
// table of README.md (checked by a unit test). summary.json's solver statistics come
// from a second small registry over the run's accumulated StepStatistics.

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "core/step_statistics.hpp"
#include "simulation/model.hpp"

namespace hfdda::simulation {

/// What a column may read about a step: the model after the step was committed, its
/// number and end time, its statistics, the run's elapsed wall time, and quantities
/// derived from the model once per step (shared by several columns).
struct StepContext {
  const Model& model;
  int step = 0;
  double time_s = 0.0;
  const StepStatistics& stats;
  double elapsed_s = 0.0;

  // Derived once per step by make_step_context().
  int open_joint_ends = 0;
  double max_aperture_m = 0.0;
  /// Largest overlap of a joint's faces in the committed state (the negative of its
  /// smallest gap, 0 if none) [m]: unlike the step statistics' max_penetration_m it
  /// ignores the iterates of the contact iterations.
  double max_overlap_m = 0.0;
  int wetted_joints = 0;               ///< 0 without a flow network
  int inlet_point = -1;                ///< mesh point of the first injection, -1 if none
  double open_xmin_m = 0.0, open_xmax_m = 0.0, open_ymin_m = 0.0, open_ymax_m = 0.0;
  /// x-extent of the ends of fluid-filled joints that are open or no longer bonded there:
  /// the fracture reaches the tip of a joint broken whole even where its faces touch at
  /// the tip, which the open ends alone miss by one joint from step to step [m].
  double fracture_xmin_m = 0.0, fracture_xmax_m = 0.0;
  /// Lengths of joints per kind (0 rock, 1 natural: mesh::JointProperties::natural) [m]:
  /// with an open end, holding fluid (invaded), with a sliding end.
  double opened_m[2] = {0.0, 0.0}, invaded_m[2] = {0.0, 0.0}, slipped_m[2] = {0.0, 0.0};
  /// Largest distance from the first injection point (else the origin) of an end of an
  /// open joint, and of an invaded joint [m].
  double open_extent_m = 0.0, invaded_extent_m = 0.0;
};

/// The context of a committed step (derived quantities computed here, once).
StepContext make_step_context(const Model& model, int step, double time_s, const StepStatistics& stats,
                              double elapsed_s);

/// One column of history.csv and of the RunRecord.
struct OutputColumn {
  std::string name;         ///< CSV header, snake_case with the unit as suffix where it has one
  std::string unit;         ///< SI unit, "-" for counts and ratios
  std::string description;  ///< one line, Markdown
  std::function<double(const StepContext&)> value;
};

/// The fixed columns, in history.csv order (without the per-probe columns).
const std::vector<OutputColumn>& fixed_history_columns();

/// The two columns of one probe (`probe_<name>_pressure_Pa`, `probe_<name>_aperture_m`);
/// `index` is the probe's position in the case's probe list.
std::vector<OutputColumn> probe_columns(const std::string& name, std::size_t index);

/// The columns of a case with a load ramp: its load level and the broken fraction of its
/// stop joints.
std::vector<OutputColumn> load_ramp_columns();

/// Every column of a case, in history.csv order: the fixed ones, then two per probe.
std::vector<OutputColumn> history_columns(const Model& model);

/// The column table documented in README.md (fixed columns and the probe pattern), as
/// Markdown; a unit test checks that README.md contains it verbatim.
std::string history_columns_markdown();

/// The per-step values of a run in memory: the same columns and numbers as history.csv.
/// Looking up a column the record does not have throws std::out_of_range naming the
/// column and listing the known ones.
class RunRecord {
 public:
  RunRecord() = default;
  explicit RunRecord(std::vector<std::string> columns);

  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t rows() const { return rows_.size(); }
  bool empty() const { return rows_.empty(); }
  bool has(const std::string& name) const { return index_.count(name) != 0; }
  /// Position of a column; throws std::out_of_range for an unknown name.
  std::size_t column(const std::string& name) const;
  /// Value of a column in a row; throws std::out_of_range for an unknown column or row.
  double value(std::size_t row, const std::string& name) const;
  /// Every row's value of a column; throws std::out_of_range for an unknown column.
  std::vector<double> series(const std::string& name) const;
  const std::vector<double>& row(std::size_t row) const { return rows_.at(row); }
  /// Adds a row; throws std::invalid_argument if its size differs from the column count.
  void append(std::vector<double> row);

 private:
  std::vector<std::string> columns_;
  std::map<std::string, std::size_t> index_;
  std::vector<std::vector<double>> rows_;
};

/// One field of summary.json's "solver" object, from the run's accumulated statistics
/// (numbers only; "contact_method" is written beside them).
struct SummaryField {
  std::string name, description;
  std::function<double(const StepStatistics& totals)> value;
  bool integer = false;  ///< written as a JSON integer
};

/// The numeric fields of summary.json's "solver" object.
const std::vector<SummaryField>& summary_solver_fields();

}  // namespace hfdda::simulation
