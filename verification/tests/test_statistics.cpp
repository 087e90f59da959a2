// Unit tests of the verification cases' shared statistics (verification/harness/statistics.hpp).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "statistics.hpp"

namespace hfdda::verification {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

TEST(VerificationStatistics, NanMinMaxTreatNanAsNoValueYet) {
  EXPECT_EQ(nan_min(kNan, 3.0), 3.0);
  EXPECT_EQ(nan_max(kNan, 3.0), 3.0);
  EXPECT_EQ(nan_min(2.0, 3.0), 2.0);
  EXPECT_EQ(nan_max(2.0, 3.0), 3.0);
  EXPECT_EQ(nan_min(-0.5, 1.0), -0.5);
}

TEST(VerificationStatistics, RangeSpreadAndItsNaNCases) {
  Range r;
  EXPECT_TRUE(std::isnan(r.spread()));  // empty
  for (double v : {2.0, 2.0, 2.5}) r.add(v);
  EXPECT_DOUBLE_EQ(r.min, 2.0);
  EXPECT_DOUBLE_EQ(r.max, 2.5);
  EXPECT_DOUBLE_EQ(r.spread(), 0.25);
  r.add(kNan);  // a value that is not a number must not be skipped
  EXPECT_TRUE(std::isnan(r.spread()));
}

TEST(VerificationStatistics, MaxAbsFiniteIsNaNForEmptyOrNonFinite) {
  const std::vector<double> ok{1.0, -3.0, 2.0}, bad{1.0, std::numeric_limits<double>::infinity()}, none;
  auto id = [](double v) { return v; };
  EXPECT_EQ(max_abs_finite(ok, id), 3.0);
  EXPECT_TRUE(std::isnan(max_abs_finite(bad, id)));
  EXPECT_TRUE(std::isnan(max_abs_finite(none, id)));
}

}  // namespace
}  // namespace hfdda::verification
