#include "lookout/stereo/range_bearing.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>

#include "lookout/core/random.h"

namespace lookout::stereo {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

TEST(RangeBearingTest, RoundTripsThroughAMountedSensor) {
  const Pose2 lidar(2.2, 0.3, 0.2);
  CartesianPoint point;
  point.point_m = Vector2d(20.0, 7.0);
  point.covariance << 0.5, 0.1, 0.1, 0.04;
  const RangeBearing polar = ToRangeBearing(point, lidar);
  EXPECT_NEAR(polar.range_m, (point.point_m - lidar.translation).norm(), 1e-12);
  EXPECT_NEAR(polar.bearing_rad, std::atan2(6.7, 17.8) - 0.2, 1e-12);
  const CartesianPoint back = ToCartesian(polar, lidar);
  EXPECT_LT((back.point_m - point.point_m).norm(), 1e-12);
  EXPECT_LT((back.covariance - point.covariance).norm(), 1e-12);
}

// A pure range error of a point straight ahead is an x error; a bearing error is a y error of
// range times the angle.
TEST(RangeBearingTest, AnalyticCaseStraightAhead) {
  RangeBearing polar;
  polar.range_m = 10.0;
  polar.bearing_rad = 0.0;
  polar.covariance << 0.04, 0.0, 0.0, 1e-4;
  const CartesianPoint p = ToCartesian(polar, Pose2());
  EXPECT_NEAR(p.covariance(0, 0), 0.04, 1e-15);
  EXPECT_NEAR(p.covariance(1, 1), 100.0 * 1e-4, 1e-15);
  EXPECT_NEAR(p.covariance(0, 1), 0.0, 1e-15);
}

// The propagated covariance against the sample covariance of 200,000 Monte Carlo draws of
// (range, bearing) pushed through the exact conversion. Tolerance: the sample covariance of N
// Gaussian draws has a relative standard error of about sqrt(2 / N) = 0.32 % on each variance
// (a bit more off the diagonal); 2 % is over six standard errors, and the linearisation error
// for these sigmas (r sigma_theta^2 = 2.5 mm of bias) is far below it.
TEST(RangeBearingTest, CovarianceMatchesMonteCarlo) {
  const std::uint64_t seed = 20261122;
  Rng rng(seed);
  const Pose2 lidar(2.2, 0.0, 0.0);
  RangeBearing polar;
  polar.range_m = 25.0;
  polar.bearing_rad = 0.6;
  const double sigma_r = 0.8;
  const double sigma_b = 0.01;
  const double rho = 0.3;
  polar.covariance << sigma_r * sigma_r, rho * sigma_r * sigma_b, rho * sigma_r * sigma_b,
      sigma_b * sigma_b;
  const Matrix2d chol = polar.covariance.llt().matrixL();
  const int n = 200000;
  Vector2d sum = Vector2d::Zero();
  Matrix2d sum_outer = Matrix2d::Zero();
  for (int i = 0; i < n; ++i) {
    const Vector2d z = chol * Vector2d{rng.Normal(), rng.Normal()};
    const double r = polar.range_m + z.x();
    const double b = polar.bearing_rad + z.y();
    const Vector2d p = lidar * Vector2d(r * std::cos(b), r * std::sin(b));
    sum += p;
    sum_outer += p * p.transpose();
  }
  const double count = static_cast<double>(n);
  const Vector2d mean = sum / count;
  const Matrix2d sample = (sum_outer - count * mean * mean.transpose()) / (count - 1.0);
  const CartesianPoint linear = ToCartesian(polar, lidar);
  const double scale = std::sqrt(linear.covariance(0, 0) * linear.covariance(1, 1));
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      EXPECT_NEAR(sample(i, j), linear.covariance(i, j), 0.02 * scale)
          << "entry (" << i << ", " << j << "), seed " << seed;
    }
  }
  // The mean moves by about r sigma_b^2 / 2 = 1.25 mm only; its standard error is ~2 mm.
  EXPECT_LT((mean - linear.point_m).norm(), 0.02) << "seed " << seed;
}

}  // namespace
}  // namespace lookout::stereo
