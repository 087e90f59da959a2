#pragma once
// Rubin's measurements and the peer simulator's results as time series, and the error
// measure of the Rubin case (seed 3.3): the mean relative error of a model series at the
// measured points. Used by metrics.cpp and by the unit tests of the metric
// (verification/tests/test_rubin_metric.cpp), which recompute the peer's errors.

#include <array>
#include <string>
#include <vector>

namespace hfdda::verification::rubin {

/// A time series in SI units.
struct Series {
  std::vector<double> t, v;
};

/// The five compared quantities, in the order of the reference file.
struct Quantity {
  const char* key;          ///< metric suffix
  const char* experiment;   ///< column of rubin1983_experiment.csv
  double experiment_to_si;  ///< factor to SI
  double t_min_s;           ///< points compared: t > t_min
};
extern const std::array<Quantity, 5> kQuantities;

/// Seconds added to the peer simulator's clock to align it with the experiment's
/// (reference_data/README.md).
constexpr double kPeerClockShift_s = 3.7;
/// Height of the fractured PMMA layer [m]: the peer's half-model area / height is its half-length.
constexpr double kLayerHeight_m = 0.055;

/// A CSV file with a header line, as columns of text cells.
struct Table {
  std::vector<std::string> names;
  std::vector<std::vector<std::string>> rows;
  std::size_t column(const std::string& name, const std::string& file) const;
};

Table read_table(const std::string& path);

/// Column `name` of `table` against its time column, scaled; empty cells are left out.
Series series_of(const Table& table, const std::string& name, double scale, double clock_shift_s,
                 const std::string& file);

/// Linear interpolation of `s` at t; NaN outside its range.
double interpolate(const Series& s, double t);

/// Mean relative error of `model` at the measured points with t_min < t <= t_max. A
/// measured time outside the model's samples gives NaN.
double mean_relative_error(const Series& model, const Series& measured, double t_min_s,
                           double t_max_s = 1e300);

/// The five measured series of the experiment file, in kQuantities order.
std::vector<Series> measured_series(const std::string& experiment_file);
/// The peer's five series (clock shifted, half-model area over the layer height as half-length).
std::vector<Series> peer_series(const std::string& peer_file);

}  // namespace hfdda::verification::rubin
