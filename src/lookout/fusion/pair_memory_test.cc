#include "lookout/fusion/pair_memory.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lookout::fusion {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

FusedObject Walker(const Vector2d& point, const Vector2d& velocity) {
  FusedObject f;
  f.point_m = point;
  f.point_covariance = Vector2d(0.01, 0.04).asDiagonal();
  f.velocity_mps = velocity;
  f.velocity_covariance = 0.09 * Matrix2d::Identity();
  f.sensor_count = 2;
  f.stereo_id = 4;
  return f;
}

// The memory lives in the odometry frame: 80 ms later, with the ego moved and turned, the prior
// is the fused point moved by its velocity, seen from the new vehicle pose, its covariance the
// closed form (rotated into the new axes).
TEST(PairMemory, MovesWithTheFusedVelocityIntoTheNewVehicleFrame) {
  const Pose2 ego_before(5.0, 1.0, 0.3);
  const Pose2 ego_after(5.8, 1.2, 0.35);
  const FusedObject f = Walker(Vector2d(12.0, 2.0), Vector2d(0.0, 1.5));  // vehicle axes
  const PairMemory memory = RememberPair(f, 1'000'000'000, ego_before);
  const double dt = 0.08;
  const double sigma_a = 3.0;
  const auto prior = PredictPairPrior(memory, 1'080'000'000, ego_after, sigma_a, 0.3);
  ASSERT_TRUE(prior.has_value());
  const Matrix2d r_before = ego_before.Rotation();
  const Vector2d odometry = ego_before * f.point_m + dt * (r_before * f.velocity_mps);
  EXPECT_LT((prior->point_m - ego_after.Inverse() * odometry).norm(), 1e-12);
  const double a = 0.5 * sigma_a * dt * dt;
  const Matrix2d odometry_covariance = r_before * f.point_covariance * r_before.transpose() +
                                       dt * dt * 0.09 * Matrix2d::Identity() +
                                       a * a * Matrix2d::Identity();
  const Matrix2d r_after = ego_after.Rotation().transpose();
  EXPECT_LT((prior->covariance - r_after * odometry_covariance * r_after.transpose()).norm(),
            1e-12);
  // Seen from the pose it was remembered in, at once: the fused point itself.
  const auto same = PredictPairPrior(memory, 1'000'000'001, ego_before, sigma_a, 0.3);
  ASSERT_TRUE(same.has_value());
  EXPECT_LT((same->point_m - f.point_m).norm(), 1e-6);
}

TEST(PairMemory, TooOldOrNotOlderIsNoPrior) {
  const PairMemory memory =
      RememberPair(Walker(Vector2d(12.0, 2.0), Vector2d::Zero()), 1'000'000'000, Pose2());
  EXPECT_FALSE(PredictPairPrior(memory, 1'000'000'000, Pose2(), 3.0, 0.3).has_value());
  EXPECT_FALSE(PredictPairPrior(memory, 900'000'000, Pose2(), 3.0, 0.3).has_value());
  EXPECT_FALSE(PredictPairPrior(memory, 1'400'000'000, Pose2(), 3.0, 0.3).has_value());
  EXPECT_TRUE(PredictPairPrior(memory, 1'300'000'000, Pose2(), 3.0, 0.3).has_value());
}

}  // namespace
}  // namespace lookout::fusion
