// Anderson acceleration of fixed-point iterations (core/anderson_acceleration.hpp),
// against plain iteration on maps whose fixed points are known in closed form.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "core/anderson_acceleration.hpp"

namespace hfdda {
namespace {

/// Iterates of x <- next(x, G(x)) until |G(x) - x| <= tol |x*|; the count, or -1.
template <class Map>
int iterations_to_converge(AndersonAcceleration& acceleration, const Map& g, Eigen::VectorXd x, double scale,
                           int limit, Eigen::VectorXd* solution = nullptr) {
  for (int k = 1; k <= limit; ++k) {
    const Eigen::VectorXd gx = g(x);
    if ((gx - x).norm() <= 1e-12 * scale) {
      if (solution) *solution = x;
      return k;
    }
    x = acceleration.next(x, gx);
  }
  return -1;
}

// A wedge of two sliding contacts: each one's friction lowers the other's normal force,
// N = p - B N with B = mu / tan(alpha) on the off-diagonal. At alpha = 15 deg and
// phi = 30 deg the gain is 2.15: plain iteration diverges with alternating sign; the
// fixed point (I + B)^-1 p exists and is positive.
TEST(AndersonAcceleration, ConvergesOnAWedgeWherePlainIterationDiverges) {
  const double gain = std::tan(std::numbers::pi / 6.0) / std::tan(std::numbers::pi / 12.0);
  Eigen::Matrix2d b;
  b << 0.3, gain, gain, 0.1;  // slightly asymmetric, as two unequal faces are
  const Eigen::Vector2d p(1.0e6, 0.8e6);
  auto g = [&](const Eigen::VectorXd& n) -> Eigen::VectorXd { return p - b * n; };
  const Eigen::Vector2d exact = (Eigen::Matrix2d::Identity() + b).partialPivLu().solve(p);
  ASSERT_GT(exact.minCoeff(), 0.0);

  AndersonAcceleration plain(0);  // depth 0: x <- G(x)
  EXPECT_EQ(iterations_to_converge(plain, g, Eigen::Vector2d(1.0e6, 1.0e6), exact.norm(), 200), -1);

  AndersonAcceleration accelerated(5);
  Eigen::VectorXd solution;
  const int count = iterations_to_converge(accelerated, g, Eigen::Vector2d(1.0e6, 1.0e6), exact.norm(), 200, &solution);
  ASSERT_GT(count, 0);
  EXPECT_LE(count, 5);  // a linear map of dimension 2: two differences span it
  EXPECT_NEAR((solution - exact).norm() / exact.norm(), 0.0, 1e-10);
}

// A contraction converges either way, and the acceleration must not slow it down.
TEST(AndersonAcceleration, DoesNotSlowAContraction) {
  const int n = 20;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    a(i, i) = 0.5;
    if (i + 1 < n) a(i, i + 1) = a(i + 1, i) = 0.2;
  }
  const Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  auto g = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return a * x + c; };
  const Eigen::VectorXd exact = (Eigen::MatrixXd::Identity(n, n) - a).partialPivLu().solve(c);
  AndersonAcceleration plain(0), accelerated(5);
  const int plain_count = iterations_to_converge(plain, g, Eigen::VectorXd::Zero(n), exact.norm(), 500);
  const int accelerated_count = iterations_to_converge(accelerated, g, Eigen::VectorXd::Zero(n), exact.norm(), 500);
  ASSERT_GT(plain_count, 0);
  ASSERT_GT(accelerated_count, 0);
  EXPECT_LT(accelerated_count, plain_count);
}

// A new problem of another size starts afresh instead of mixing unrelated vectors.
TEST(AndersonAcceleration, AChangeOfSizeStartsAfresh) {
  AndersonAcceleration acceleration(3);
  acceleration.next(Eigen::Vector2d(1, 2), Eigen::Vector2d(2, 3));
  acceleration.next(Eigen::Vector2d(2, 3), Eigen::Vector2d(2.5, 3.5));
  EXPECT_EQ(acceleration.columns(), 1);
  const Eigen::Vector3d g(7, 8, 9);
  const Eigen::VectorXd next = acceleration.next(Eigen::Vector3d(1, 1, 1), g);
  EXPECT_EQ(acceleration.columns(), 0);
  EXPECT_EQ(next, Eigen::VectorXd(g));
}

}  // namespace
}  // namespace hfdda
