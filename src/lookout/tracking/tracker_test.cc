#include "lookout/tracking/tracker.h"

#include <gtest/gtest.h>

#include <limits>

namespace lookout::tracking {
namespace {

Detection At(double x, double y) {
  Detection d;
  d.position_m = Eigen::Vector2d(x, y);
  d.covariance = Eigen::Vector2d(0.04, 0.09).asDiagonal();
  return d;
}

TEST(BirthState, TakesTheDetectionsVelocityWhereItIsSurerThanThePrior) {
  Detection d = At(3.0, -2.0);
  const Gaussian without = BirthState(d, 5.0);
  EXPECT_EQ(without.mean, Eigen::Vector4d(3.0, -2.0, 0.0, 0.0));
  EXPECT_EQ(without.cov.topLeftCorner(2, 2), d.covariance);
  EXPECT_EQ(without.cov.bottomRightCorner(2, 2), 25.0 * Eigen::Matrix2d::Identity());
  EXPECT_EQ(without.cov.topRightCorner(2, 2), Eigen::Matrix2d::Zero());

  // A camera car crossing at 10 m/s, its velocity known to 0.3 m/s.
  d.velocity_mps = Eigen::Vector2d(0.0, 10.0);
  d.velocity_covariance = 0.09 * Eigen::Matrix2d::Identity();
  const Gaussian with = BirthState(d, 5.0);
  EXPECT_EQ(with.mean, Eigen::Vector4d(3.0, -2.0, 0.0, 10.0));
  EXPECT_EQ(with.cov.bottomRightCorner(2, 2), d.velocity_covariance);
  EXPECT_EQ(with.cov.topLeftCorner(2, 2), d.covariance);

  // Looser than the prior (a walker's 1.5 m/s prior against 2 m/s): the prior.
  d.velocity_covariance = 4.0 * Eigen::Matrix2d::Identity();
  EXPECT_EQ(BirthState(d, 1.5).mean.tail(2), Eigen::Vector2d::Zero());
  // Unusable: not positive definite, not finite.
  d.velocity_covariance << 0.09, 0.2, 0.2, 0.09;
  EXPECT_EQ(BirthState(d, 5.0).mean.tail(2), Eigen::Vector2d::Zero());
  d.velocity_covariance = 0.09 * Eigen::Matrix2d::Identity();
  d.velocity_mps = Eigen::Vector2d(std::numeric_limits<double>::quiet_NaN(), 1.0);
  EXPECT_EQ(BirthState(d, 5.0).mean.tail(2), Eigen::Vector2d::Zero());
  EXPECT_EQ(BirthState(d, 5.0).cov.bottomRightCorner(2, 2), 25.0 * Eigen::Matrix2d::Identity());
}

}  // namespace
}  // namespace lookout::tracking
