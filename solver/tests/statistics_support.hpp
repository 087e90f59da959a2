#pragma once
// Statistics shared by the tests of random draws (distributions, network generator).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

namespace hfdda::test {

/// Kolmogorov-Smirnov statistic of a sample against a CDF.
inline double ks_statistic(std::vector<double> sample, const std::function<double(double)>& cdf) {
  std::sort(sample.begin(), sample.end());
  const double n = static_cast<double>(sample.size());
  double d = 0.0;
  for (std::size_t i = 0; i < sample.size(); ++i) {
    const double f = cdf(sample[i]);
    d = std::max({d, (static_cast<double>(i) + 1.0) / n - f, f - static_cast<double>(i) / n});
  }
  return d;
}

/// Critical KS distance at significance 1e-3 (asymptotic: K = 1.949).
inline double ks_critical(std::size_t n) { return 1.949 / std::sqrt(static_cast<double>(n)); }

}  // namespace hfdda::test
