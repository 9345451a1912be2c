#include "lookout/eval/trajectory_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "lookout/core/input_error.h"

namespace lookout::eval {
namespace {

// A reference drive: an S-curve, one pose every 0.1 s, headings along the path.
Trajectory2 SCurve(int poses) {
  Trajectory2 trajectory;
  for (int i = 0; i < poses; ++i) {
    const double t = 0.1 * i;
    const double x = 2.0 * t;
    const double y = 3.0 * std::sin(0.4 * t);
    const double yaw = std::atan2(1.2 * std::cos(0.4 * t), 2.0);
    trajectory.push_back({t, Pose2(x, y, yaw)});
  }
  return trajectory;
}

TEST(TrajectoryErrorTest, AlignRigidRecoversAKnownTransform) {
  const unsigned seed = 20261122;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
  const Pose2 truth(12.5, -7.25, 2.4);
  std::vector<Eigen::Vector2d> source;
  std::vector<Eigen::Vector2d> target;
  for (int i = 0; i < 40; ++i) {
    source.emplace_back(coordinate(rng), coordinate(rng));
    target.push_back(truth * source.back());
  }
  const Pose2 found = AlignRigid(source, target);
  EXPECT_NEAR(found.x(), truth.x(), 1e-9) << "seed " << seed;
  EXPECT_NEAR(found.y(), truth.y(), 1e-9) << "seed " << seed;
  EXPECT_NEAR(WrapAngle(found.yaw - truth.yaw), 0.0, 1e-12) << "seed " << seed;
}

TEST(TrajectoryErrorTest, RotatedAndTranslatedCopyHasZeroErrorAfterAlignment) {
  const Trajectory2 reference = SCurve(200);
  const Pose2 moved(-40.0, 15.0, -2.0);  // the estimate's frame, far from the reference's
  Trajectory2 estimate = reference;
  for (StampedPose2& p : estimate) p.pose = moved * p.pose;
  const AbsoluteTrajectoryError error = ComputeAbsoluteTrajectoryError(estimate, reference);
  EXPECT_EQ(error.matched, reference.size());
  EXPECT_EQ(error.unmatched, 0u);
  EXPECT_NEAR(error.ate_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(error.heading_rmse_rad, 0.0, 1e-12);
  const Pose2 back = error.alignment * moved;  // the alignment undoes the move
  EXPECT_NEAR(back.translation.norm(), 0.0, 1e-9);
  EXPECT_NEAR(back.yaw, 0.0, 1e-12);
}

TEST(TrajectoryErrorTest, RadialOffsetOnACircleIsTheAte) {
  // Concentric circles: by symmetry the best alignment is the identity, so every pose keeps
  // its 0.3 m radial error and the ATE is exactly 0.3 m.
  Trajectory2 reference;
  Trajectory2 estimate;
  for (int i = 0; i < 360; ++i) {
    const double a = DegToRad(i);
    const Eigen::Vector2d u(std::cos(a), std::sin(a));
    reference.push_back({1.0 * i, Pose2(10.0 * u, a + kPi / 2)});
    estimate.push_back({1.0 * i, Pose2(10.3 * u, a + kPi / 2)});
  }
  const AbsoluteTrajectoryError error = ComputeAbsoluteTrajectoryError(estimate, reference);
  EXPECT_NEAR(error.ate_rmse_m, 0.3, 1e-9);
  EXPECT_NEAR(error.heading_rmse_rad, 0.0, 1e-12);
  EXPECT_NEAR(error.alignment.translation.norm(), 0.0, 1e-9);
}

TEST(TrajectoryErrorTest, HeadingOffsetIsTheHeadingRmse) {
  const Trajectory2 reference = SCurve(100);
  Trajectory2 estimate = reference;
  for (StampedPose2& p : estimate) p.pose.yaw = WrapAngle(p.pose.yaw + 0.1);
  const AbsoluteTrajectoryError error = ComputeAbsoluteTrajectoryError(estimate, reference);
  EXPECT_NEAR(error.ate_rmse_m, 0.0, 1e-9);  // positions agree, so no rotation is fitted
  EXPECT_NEAR(error.heading_rmse_rad, 0.1, 1e-9);
}

TEST(TrajectoryErrorTest, EstimateIsInterpolatedAtTheReferenceTimes) {
  // The estimate moves at constant velocity and turn rate, sampled at 1 Hz; the reference
  // samples the same motion at 0.25 s offsets, so interpolation is exact.
  const auto motion = [](double t) { return Pose2(1.5 * t, -0.5 * t, WrapAngle(3.0 + 0.05 * t)); };
  Trajectory2 estimate;
  for (int i = 0; i <= 10; ++i) estimate.push_back({1.0 * i, motion(i)});
  Trajectory2 reference;
  for (int i = -2; i <= 45; ++i) reference.push_back({0.25 * i, motion(0.25 * i)});
  const AbsoluteTrajectoryError error = ComputeAbsoluteTrajectoryError(estimate, reference);
  EXPECT_EQ(error.matched, 41u);   // 0 .. 10 s
  EXPECT_EQ(error.unmatched, 7u);  // -0.5, -0.25 and 10.25 .. 11.25 s
  EXPECT_NEAR(error.ate_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(error.heading_rmse_rad, 0.0, 1e-9);
}

TEST(TrajectoryErrorTest, InterpolationTakesTheShorterArcAndTheLastOfABurst) {
  const Trajectory2 trajectory = {{0.0, Pose2(0, 0, 3.1)},
                                  {1.0, Pose2(2, 0, -3.1)},
                                  {1.0, Pose2(4, 0, -3.1)},
                                  {3.0, Pose2(4, 2, -3.1)}};
  const std::optional<Pose2> middle = InterpolatePose(trajectory, 0.5);
  ASSERT_TRUE(middle.has_value());
  EXPECT_NEAR(std::abs(middle->yaw), kPi, 1e-12);  // through pi, not through 0
  EXPECT_NEAR(middle->x(), 1.0, 1e-12);
  const std::optional<Pose2> burst = InterpolatePose(trajectory, 1.0);
  ASSERT_TRUE(burst.has_value());
  EXPECT_EQ(burst->x(), 4.0);
  EXPECT_NEAR(InterpolatePose(trajectory, 2.0)->y(), 1.0, 1e-12);
  EXPECT_FALSE(InterpolatePose(trajectory, -0.1).has_value());
  EXPECT_FALSE(InterpolatePose(trajectory, 3.1).has_value());
  EXPECT_FALSE(InterpolatePose(trajectory, 2.0, 1.5).has_value());  // a 2 s gap
  EXPECT_TRUE(InterpolatePose(trajectory, 0.5, 1.5).has_value());
}

TEST(TrajectoryErrorTest, TimeGoingBackwardsIsRefused) {
  const Trajectory2 estimate = {{0.0, Pose2()}, {2.0, Pose2()}, {1.0, Pose2()}};
  try {
    ComputeAbsoluteTrajectoryError(estimate, SCurve(5));
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "[2].t");
  }
}

TEST(TrajectoryErrorTest, NothingMatchedGivesNaN) {
  const Trajectory2 estimate = {{100.0, Pose2()}, {101.0, Pose2()}};
  const AbsoluteTrajectoryError error = ComputeAbsoluteTrajectoryError(estimate, SCurve(5));
  EXPECT_EQ(error.matched, 0u);
  EXPECT_EQ(error.unmatched, 5u);
  EXPECT_TRUE(std::isnan(error.ate_rmse_m));
}

}  // namespace
}  // namespace lookout::eval
