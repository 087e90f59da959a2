#pragma once
// Small statistics the verification cases' metrics share: running minima and maxima that
// start from "nothing seen" (NaN), and the largest magnitude of a series that is NaN when
// any value is not finite (a run that diverged must not pass a "max error <=" check).
// Used for the path joints of the LEFM and KGD-toughness cases (seed 4.3, 4.5: joint
// lengths, bond strengths, K_IC of eq. 4.13) and the mass ledgers of the KGD and
// propagation cases (seed 3.2, 3.4-3.5).

#include <algorithm>
#include <cmath>
#include <limits>

namespace hfdda::verification {

/// min(a, b) with NaN as "no value yet": NaN in `a` gives `b`.
inline double nan_min(double a, double b) { return std::isnan(a) ? b : std::min(a, b); }
/// max(a, b) with NaN as "no value yet": NaN in `a` gives `b`.
inline double nan_max(double a, double b) { return std::isnan(a) ? b : std::max(a, b); }

/// Smallest and largest of the values added; both NaN until the first one. A value that
/// is not a number makes the spread NaN (a check on it then fails) instead of being
/// skipped.
struct Range {
  double min = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
  bool saw_nan = false;
  void add(double v) {
    saw_nan = saw_nan || std::isnan(v);
    min = nan_min(min, v);
    max = nan_max(max, v);
  }
  /// max / min - 1: how far the values spread (0 when all are equal; NaN when empty or
  /// when a NaN was added).
  double spread() const { return saw_nan ? std::numeric_limits<double>::quiet_NaN() : max / min - 1.0; }
};

/// Largest |value(item)| over `items`; NaN if there are none or any value is not finite.
template <class Items, class Value>
double max_abs_finite(const Items& items, Value value) {
  if (items.empty()) return std::numeric_limits<double>::quiet_NaN();
  double largest = 0.0;
  for (const auto& item : items) {
    const double v = value(item);
    if (!std::isfinite(v)) return std::numeric_limits<double>::quiet_NaN();
    largest = std::max(largest, std::abs(v));
  }
  return largest;
}

}  // namespace hfdda::verification
