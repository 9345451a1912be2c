#include "lookout/fusion/stereo_prediction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <variant>

#include "lookout/fusion/fusion_test_support.h"

namespace lookout::fusion {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

using testing::kCameraMount;
using testing::kLidarMount;

stereo::StereoPoint CrossingCar() {
  StereoObject o;
  o.id = 1;
  o.center_m = Vector2d(19.2, 0.0);  // 20 m ahead of the vehicle's centre
  o.yaw_rad = kPi / 2.0;             // crossing to the left
  o.length_m = 4.0;
  o.width_m = 2.0;
  o.speed_lateral_mps = 10.0;
  o.center_covariance = Vector2d(0.2, 0.01).asDiagonal();
  o.yaw_variance = 0.0;
  o.speed_variance = 0.25;
  return std::get<stereo::StereoPoint>(
      stereo::ProjectStereoObject(o, kCameraMount, kLidarMount, {}));
}

TEST(StereoPredictionTest, ObjectMotionAndCovarianceGrowth) {
  const stereo::StereoPoint p = CrossingCar();
  ASSERT_LT((p.point.point_m - Vector2d(19.0, 0.0)).norm(), 1e-12);  // its right side
  const double dt = 0.05;
  const stereo::StereoPoint q = PredictStereoPoint(p, dt, Pose2(), kLidarMount, 3.0);
  EXPECT_LT((q.point.point_m - Vector2d(19.0, 0.5)).norm(), 1e-12);
  EXPECT_LT((q.footprint.center_m - Vector2d(20.0, 0.5)).norm(), 1e-12);
  const double q_pos = std::pow(0.5 * 3.0 * dt * dt, 2);
  EXPECT_NEAR(q.point.covariance(0, 0), 0.2 + dt * dt * 0.25 + q_pos, 1e-12);
  EXPECT_NEAR(q.point.covariance(1, 1), 0.01 + dt * dt * 0.25 + q_pos, 1e-12);
  EXPECT_NEAR(q.velocity_covariance(0, 0), 0.25 + std::pow(3.0 * dt, 2), 1e-12);
  // The range and bearing follow the moved point.
  EXPECT_NEAR(q.polar.range_m, std::hypot(16.8, 0.5), 1e-12);
  EXPECT_NEAR(q.polar.bearing_rad, std::atan2(0.5, 16.8), 1e-12);
}

// The ego drove 0.5 m forward and turned 0.1 rad between the stereo and the lidar stamps: a
// still object appears 0.5 m nearer and turned the other way.
TEST(StereoPredictionTest, EgoMotionIsUndone) {
  stereo::StereoPoint p = CrossingCar();
  p.velocity_mps = Vector2d::Zero();
  const Pose2 ego_then(0.0, 0.0, 0.0);
  const Pose2 ego_now(0.5, 0.0, 0.1);
  const Pose2 now_from_then = ego_now.Inverse() * ego_then;
  const stereo::StereoPoint q = PredictStereoPoint(p, 0.05, now_from_then, kLidarMount, 0.0);
  EXPECT_LT((q.point.point_m - ego_now.Inverse() * Vector2d(19.0, 0.0)).norm(), 1e-12);
  EXPECT_NEAR(q.footprint.yaw_rad, kPi / 2.0 - 0.1, 1e-12);
  const Matrix2d r = now_from_then.Rotation();
  // No acceleration noise: the covariance grows by dt^2 C_v only, and turns with the ego.
  const Matrix2d grown = p.point.covariance + 0.05 * 0.05 * p.velocity_covariance;
  EXPECT_LT((q.point.covariance - r * grown * r.transpose()).norm(), 1e-12);
}

TEST(StereoPredictionTest, InterpolatePose) {
  const Pose2 a(0.0, 0.0, 3.0);
  const Pose2 b(1.0, 2.0, -3.0);  // across the +-pi seam: 0.283 rad of turn
  const Pose2 mid = InterpolatePose(0, a, 80'000'000, b, 40'000'000);
  EXPECT_NEAR(mid.x(), 0.5, 1e-12);
  EXPECT_NEAR(mid.y(), 1.0, 1e-12);
  EXPECT_NEAR(WrapAngle(mid.yaw - (3.0 + 0.5 * (2.0 * kPi - 6.0))), 0.0, 1e-12);
  const Pose2 after = InterpolatePose(0, a, 80'000'000, b, 120'000'000);  // extrapolated
  EXPECT_NEAR(after.x(), 1.5, 1e-12);
}

}  // namespace
}  // namespace lookout::fusion
