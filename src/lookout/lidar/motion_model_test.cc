#include "lookout/lidar/motion_model.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lookout::lidar {
namespace {

MotionModelOptions NoNoise(MotionModelKind kind) {
  MotionModelOptions o;
  o.kind = kind;
  o.alpha1 = o.alpha2 = o.alpha3 = o.alpha4 = 0.0;
  o.arc_length_noise = 0.0;
  o.steering_noise_rad = 0.0;
  return o;
}

void ExpectPoseNear(const Pose2& a, const Pose2& b, double tol) {
  EXPECT_NEAR(a.x(), b.x(), tol);
  EXPECT_NEAR(a.y(), b.y(), tol);
  EXPECT_NEAR(WrapAngle(a.yaw - b.yaw), 0.0, tol);
}

TEST(MotionModel, ArcRoundTripAndCircleGeometry) {
  // A quarter circle of radius 5 m to the left ends at (5, 5) heading +90 degrees.
  const Pose2 quarter = IncrementOfArc({5.0 * kPi / 2.0, kPi / 2.0});
  ExpectPoseNear(quarter, Pose2(5.0, 5.0, kPi / 2.0), 1e-12);
  for (const Arc arc : {Arc{2.0, 0.3}, Arc{-1.5, 0.2}, Arc{3.0, 0.0}, Arc{0.7, -1.1}}) {
    const Arc back = ArcOfIncrement(IncrementOfArc(arc));
    EXPECT_NEAR(back.length_m, arc.length_m, 1e-9);
    EXPECT_NEAR(back.heading_change_rad, arc.heading_change_rad, 1e-12);
  }
}

TEST(MotionModel, DifferentialDriveWithoutNoiseAppliesTheIncrementExactly) {
  const MotionModelOptions o = NoNoise(MotionModelKind::kDifferentialDrive);
  Rng rng(1);
  const Pose2 start(3.0, -2.0, 0.8);
  // Forward, backward, sideways, turning on the spot: any increment is reachable.
  for (const Pose2& inc : {Pose2(1.0, 0.2, 0.3), Pose2(-0.8, 0.1, -0.2), Pose2(0.0, 0.5, 0.0),
                           Pose2(0.0, 0.0, 1.2), Pose2(0.3, -0.4, 2.5)}) {
    ExpectPoseNear(SampleDifferentialDrive(start, inc, o, rng), start * inc, 1e-12);
    ExpectPoseNear(ComposeIncrement(DecomposeIncrement(inc)), inc, 1e-12);
  }
}

TEST(MotionModel, BicycleWithoutNoiseDrivesDrivableArcsExactly) {
  MotionModelOptions o = NoNoise(MotionModelKind::kBicycle);
  Rng rng(1);
  const Pose2 start(-1.0, 4.0, -0.4);
  // Radius 10 m (steering atan(2.7 / 10) = 0.26 rad < 0.6), forwards and backwards; straight.
  for (const Arc arc : {Arc{2.0, 0.2}, Arc{-1.0, -0.1}, Arc{5.0, 0.0}}) {
    const Pose2 inc = IncrementOfArc(arc);
    ExpectPoseNear(SampleBicycle(start, inc, o, rng), start * inc, 1e-12);
  }
}

TEST(MotionModel, BicycleNeverTurnsTighterThanTheSteeringLimit) {
  MotionModelOptions o = NoNoise(MotionModelKind::kBicycle);
  o.steering_noise_rad = 0.3;
  o.arc_length_noise = 0.2;
  const std::uint64_t seed = 77;
  Rng rng(seed);
  const double max_curvature = std::tan(o.max_steering_rad) / o.wheelbase_m;
  // An increment that turns on the spot (impossible for a car) and a very tight one.
  for (const Pose2& inc : {Pose2(0.0, 0.0, 1.0), Pose2(0.5, 0.2, 1.5)}) {
    for (int i = 0; i < 1000; ++i) {
      const Arc arc = ArcOfIncrement(SampleBicycle(Pose2(), inc, o, rng));
      ASSERT_LE(std::abs(arc.heading_change_rad), max_curvature * std::abs(arc.length_m) + 1e-9)
          << "seed " << seed << " draw " << i;
    }
  }
}

TEST(MotionModel, DifferentialDriveNoiseHasTheStatedSpread) {
  MotionModelOptions o = NoNoise(MotionModelKind::kDifferentialDrive);
  o.alpha3 = 0.01;  // translation sigma = 0.1 * trans
  o.alpha2 = 0.0004;  // rotation sigma = 0.02 * trans
  const std::uint64_t seed = 2026;
  Rng rng(seed);
  const int n = 20000;
  double sum_x = 0.0;
  double sum_xx = 0.0;
  double sum_yaw2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const Pose2 p = SampleDifferentialDrive(Pose2(), Pose2(2.0, 0.0, 0.0), o, rng);
    sum_x += p.x();
    sum_xx += p.x() * p.x();
    sum_yaw2 += p.yaw * p.yaw;
  }
  const double mean = sum_x / n;
  const double sd = std::sqrt(sum_xx / n - mean * mean);
  EXPECT_NEAR(mean, 2.0, 0.01) << "seed " << seed;
  EXPECT_NEAR(sd, 0.2, 0.02) << "seed " << seed;
  // Heading: two independent rotations of sigma 0.04 each.
  EXPECT_NEAR(std::sqrt(sum_yaw2 / n), 0.04 * std::sqrt(2.0), 0.006) << "seed " << seed;
}

TEST(MotionModel, SameSeedSameSamples) {
  const MotionModelOptions o;
  Rng a(5);
  Rng b(5);
  for (int i = 0; i < 10; ++i) {
    const Pose2 pa = SampleMotion(Pose2(), Pose2(1.0, 0.1, 0.2), o, a);
    const Pose2 pb = SampleMotion(Pose2(), Pose2(1.0, 0.1, 0.2), o, b);
    EXPECT_EQ(pa.x(), pb.x());
    EXPECT_EQ(pa.yaw, pb.yaw);
  }
}

}  // namespace
}  // namespace lookout::lidar
