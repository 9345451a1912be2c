#include "lookout/core/dead_reckoning.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <vector>

#include "lookout/core/input_error.h"
#include "lookout/core/random.h"

namespace lookout {
namespace {

// The textbook closed form, in long double: the reference the series must agree with.
Pose2 ArcReference(const Pose2& start, double v, double w, double dt) {
  using LD = long double;
  const auto ld = [](double value) { return static_cast<LD>(value); };
  const LD th = ld(start.yaw), x = ld(start.x()), y = ld(start.y());
  if (w == 0.0) {
    return Pose2(static_cast<double>(x + ld(v) * ld(dt) * std::cos(th)),
                 static_cast<double>(y + ld(v) * ld(dt) * std::sin(th)), start.yaw);
  }
  const LD r = ld(v) / ld(w);
  const LD th1 = th + ld(w) * ld(dt);
  return Pose2(static_cast<double>(x + r * (std::sin(th1) - std::sin(th))),
               static_cast<double>(y - r * (std::cos(th1) - std::cos(th))),
               WrapAngle(static_cast<double>(th1)));
}

EgoOdometry Reading(TimeNs t, double v, double w) { return EgoOdometry{t, v, w}; }

DeadReckoningOptions NoiselessOptions() {
  DeadReckoningOptions o;
  o.noise = OdometryNoise{0.0, 0.0, 0.0, 0.0};
  return o;
}

TEST(IntegrateArcTest, StraightLine) {
  const Pose2 start(1.0, 2.0, 0.3);
  const Pose2 end = IntegrateArc(start, 10.0, 0.0, 1.5);
  EXPECT_NEAR(end.x(), 1.0 + 15.0 * std::cos(0.3), 1e-12);
  EXPECT_NEAR(end.y(), 2.0 + 15.0 * std::sin(0.3), 1e-12);
  EXPECT_NEAR(end.yaw, 0.3, 1e-15);
}

TEST(IntegrateArcTest, QuarterTurnLandsOnTheCircle) {
  // Radius v / w = 4 m, turning left from the origin heading +x: centre (0, 4).
  const Pose2 end = IntegrateArc(Pose2(), 2.0, 0.5, kPi);  // a = pi/2
  EXPECT_NEAR(end.x(), 4.0, 1e-12);
  EXPECT_NEAR(end.y(), 4.0, 1e-12);
  EXPECT_NEAR(end.yaw, kPi / 2.0, 1e-12);
}

TEST(IntegrateArcTest, FullCircleReturnsToTheStart) {
  for (const double w : {0.5, -1.3, 2.0 * kPi / 10.0}) {
    const Pose2 start(3.0, -7.0, 0.3);
    const Pose2 end = IntegrateArc(start, 2.0, w, 2.0 * kPi / std::abs(w));
    EXPECT_NEAR(end.x(), start.x(), 1e-9) << "w " << w;
    EXPECT_NEAR(end.y(), start.y(), 1e-9) << "w " << w;
    EXPECT_NEAR(WrapAngle(end.yaw - start.yaw), 0.0, 1e-9) << "w " << w;
  }
}

TEST(IntegrateArcTest, SmallYawRateLimitIsContinuousAndExact) {
  // Across the series threshold (|w dt| = 1e-2 here at w = 1e-2 / dt) and down to 0, the
  // result matches the long-double closed form and tends to the straight line.
  const Pose2 start(5.0, 1.0, -2.0);
  const double v = 13.0;
  const double dt = 0.7;
  const Pose2 line = IntegrateArc(start, v, 0.0, dt);
  for (double w = 1.0; w > 1e-17; w *= 0.37) {
    for (const double sign : {1.0, -1.0}) {
      const double ws = sign * w;
      const Pose2 fast = IntegrateArc(start, v, ws, dt);
      if (std::abs(ws * dt) > 1e-6) {  // the long-double reference itself cancels below
        const Pose2 ref = ArcReference(start, v, ws, dt);
        ASSERT_NEAR(fast.x(), ref.x(), 1e-11) << "w " << ws;
        ASSERT_NEAR(fast.y(), ref.y(), 1e-11) << "w " << ws;
      }
      // Lipschitz in w near 0: the lateral offset of an arc is v dt^2 w / 2 to first order.
      const double bound = v * dt * dt * std::abs(ws) + 1e-14;
      ASSERT_NEAR(fast.x(), line.x(), bound) << "w " << ws;
      ASSERT_NEAR(fast.y(), line.y(), bound) << "w " << ws;
    }
  }
  // Either side of the series threshold: no step.
  const double w_threshold = 1e-2 / dt;
  const Pose2 below = IntegrateArc(start, v, w_threshold * (1.0 - 1e-12), dt);
  const Pose2 above = IntegrateArc(start, v, w_threshold * (1.0 + 1e-12), dt);
  EXPECT_NEAR(below.x(), above.x(), 1e-13);
  EXPECT_NEAR(below.y(), above.y(), 1e-13);
}

TEST(IntegrateArcTest, SplittingAnIntervalChangesNothing) {
  // Exact arcs compose: n short arcs at one twist are one long arc.
  const Pose2 start(0.5, 0.25, 1.0);
  const Pose2 whole = IntegrateArc(start, 8.0, 0.4, 3.0);
  Pose2 pieces = start;
  for (int i = 0; i < 150; ++i) pieces = IntegrateArc(pieces, 8.0, 0.4, 0.02);
  EXPECT_NEAR(pieces.x(), whole.x(), 1e-11);
  EXPECT_NEAR(pieces.y(), whole.y(), 1e-11);
  EXPECT_NEAR(WrapAngle(pieces.yaw - whole.yaw), 0.0, 1e-12);
}

TEST(IntegrateArcTest, JacobiansMatchFiniteDifferences) {
  const Pose2 start(2.0, -1.0, 0.8);
  for (const double w : {0.0, 1e-9, 1e-3, 0.3, -2.0}) {
    const double v = 6.0;
    const double dt = 0.4;
    const ArcJacobians j = IntegrateArcJacobians(start, v, w, dt);
    const double h = 1e-6;
    auto diff = [](const Pose2& a, const Pose2& b) {
      return Eigen::Vector3d(a.x() - b.x(), a.y() - b.y(), WrapAngle(a.yaw - b.yaw));
    };
    const Eigen::Vector3d d_yaw = diff(IntegrateArc(Pose2(2.0, -1.0, 0.8 + h), v, w, dt),
                                       IntegrateArc(Pose2(2.0, -1.0, 0.8 - h), v, w, dt)) /
                                  (2.0 * h);
    const Eigen::Vector3d d_v =
        diff(IntegrateArc(start, v + h, w, dt), IntegrateArc(start, v - h, w, dt)) / (2.0 * h);
    const Eigen::Vector3d d_w =
        diff(IntegrateArc(start, v, w + h, dt), IntegrateArc(start, v, w - h, dt)) / (2.0 * h);
    EXPECT_TRUE(j.wrt_start.col(2).isApprox(d_yaw, 1e-7)) << "w " << w;
    EXPECT_TRUE(j.wrt_twist.col(0).isApprox(d_v, 1e-7)) << "w " << w;
    EXPECT_TRUE(j.wrt_twist.col(1).isApprox(d_w, 1e-7)) << "w " << w;
  }
}

TEST(DeadReckoningTest, StraightLineAndExtrapolation) {
  DeadReckoningOptions o = NoiselessOptions();
  o.initial_pose = Pose2(1.0, 2.0, 0.5);
  DeadReckoning dr(o);
  EXPECT_FALSE(dr.PoseAt(0).has_value());
  for (TimeNs k = 0; k <= 50; ++k) ASSERT_TRUE(dr.Add(Reading(k * 20'000'000, 10.0, 0.0)));
  // Readings up to 1 s; ask at 1.25 s: extrapolated 12.5 m along the heading.
  const EgoState s = dr.At(1'250'000'000);
  EXPECT_EQ(s.stamp, 1'250'000'000);
  EXPECT_NEAR(s.pose.x(), 1.0 + 12.5 * std::cos(0.5), 1e-9);
  EXPECT_NEAR(s.pose.y(), 2.0 + 12.5 * std::sin(0.5), 1e-9);
  EXPECT_NEAR(s.pose.yaw, 0.5, 1e-15);
  EXPECT_EQ(s.speed_mps, 10.0);
  // Between readings, from the reading held at the time.
  const EgoState mid = dr.At(510'000'000);
  EXPECT_NEAR(mid.pose.x(), 1.0 + 5.1 * std::cos(0.5), 1e-9);
}

TEST(DeadReckoningTest, CircleOfRadiusVOverWClosesAfterOnePeriod) {
  // w chosen so that the period 2 pi / w is exactly 10 s, a whole number of 20 ms readings.
  const double w = 2.0 * kPi / 10.0;
  const double v = 3.0;
  DeadReckoningOptions o = NoiselessOptions();
  o.initial_pose = Pose2(-4.0, 6.0, 1.1);
  DeadReckoning dr(o);
  for (TimeNs k = 0; k < 500; ++k) ASSERT_TRUE(dr.Add(Reading(k * 20'000'000, v, w)));
  const EgoState back = dr.At(10 * kNanosPerSecond);  // the last 20 ms extrapolated
  EXPECT_NEAR(back.pose.x(), -4.0, 1e-9);
  EXPECT_NEAR(back.pose.y(), 6.0, 1e-9);
  EXPECT_NEAR(WrapAngle(back.pose.yaw - 1.1), 0.0, 1e-9);
  // Half way round: diametrically opposite, 2 v / w away.
  const EgoState half = dr.At(5 * kNanosPerSecond);
  const Eigen::Vector2d centre =
      Eigen::Vector2d(-4.0, 6.0) + (v / w) * Eigen::Vector2d(-std::sin(1.1), std::cos(1.1));
  EXPECT_NEAR((half.pose.translation - centre).norm(), v / w, 1e-9);
  EXPECT_NEAR((half.pose.translation - Eigen::Vector2d(-4.0, 6.0)).norm(), 2.0 * v / w, 1e-9);
}

TEST(DeadReckoningTest, BackwardsTimeIsCountedAndIgnored) {
  DeadReckoning dr(NoiselessOptions());
  ASSERT_TRUE(dr.Add(Reading(100'000'000, 5.0, 0.0)));
  ASSERT_TRUE(dr.Add(Reading(200'000'000, 5.0, 0.0)));
  const EgoState before = dr.At(300'000'000);
  EXPECT_FALSE(dr.Add(Reading(150'000'000, -40.0, 3.0)));
  EXPECT_FALSE(dr.Add(Reading(0, -40.0, 3.0)));
  EXPECT_EQ(dr.rejected_backwards_count(), 2);
  EXPECT_EQ(dr.NewestStamp(), 200'000'000);
  const EgoState after = dr.At(300'000'000);
  EXPECT_EQ(after.pose.translation, before.pose.translation);
  EXPECT_EQ(after.speed_mps, 5.0);

  // Non-finite readings: refused, counted separately.
  EXPECT_FALSE(dr.Add(Reading(250'000'000, std::numeric_limits<double>::quiet_NaN(), 0.0)));
  EXPECT_FALSE(dr.Add(Reading(250'000'000, 1.0, std::numeric_limits<double>::infinity())));
  EXPECT_EQ(dr.rejected_non_finite_count(), 2);
  EXPECT_EQ(dr.rejected_backwards_count(), 2);

  // The same stamp again replaces the twist without moving.
  EXPECT_TRUE(dr.Add(Reading(200'000'000, 0.0, 0.0)));
  EXPECT_NEAR(dr.At(300'000'000).pose.x(), dr.At(200'000'000).pose.x(), 1e-15);
}

TEST(DeadReckoningTest, PoseAtRefusesFarExtrapolation) {
  DeadReckoningOptions o = NoiselessOptions();
  o.max_extrapolation_s = 0.25;
  o.history_s = 0.5;
  DeadReckoning dr(o);
  for (TimeNs k = 0; k <= 100; ++k) dr.Add(Reading(k * 20'000'000, 1.0, 0.0));  // 0 .. 2 s
  EXPECT_EQ(dr.OldestStamp(), 1'500'000'000);  // history pruned to the newest 0.5 s
  EXPECT_TRUE(dr.PoseAt(2'250'000'000).has_value());
  EXPECT_FALSE(dr.PoseAt(2'250'000'001).has_value());
  EXPECT_TRUE(dr.PoseAt(1'250'000'000).has_value());
  EXPECT_FALSE(dr.PoseAt(1'249'999'999).has_value());
  // Backwards from the oldest kept reading: 1 m/s straight, so x = t.
  EXPECT_NEAR(dr.PoseAt(1'300'000'000)->pose.x(), 1.3, 1e-9);

  const EgoPoseSource& source = dr;  // usable through the interface
  EXPECT_NEAR(source.PoseAt(2'000'000'000)->pose.x(), 2.0, 1e-9);
}

TEST(DeadReckoningTest, CovarianceGrowsFromTheNoiseModel) {
  DeadReckoningOptions o;
  o.noise = OdometryNoise{0.1, 0.0, 0.0, 0.0};
  DeadReckoning dr(o);
  dr.Add(Reading(0, 10.0, 0.0));
  // One interval held from one reading: var(x) = (0.1 m/s * 2 s)^2 along the heading (+x).
  const Eigen::Matrix3d p = dr.At(2 * kNanosPerSecond).covariance;
  EXPECT_NEAR(p(0, 0), 0.04, 1e-12);
  EXPECT_NEAR(p(1, 1), 0.0, 1e-15);
  EXPECT_NEAR(p(2, 2), 0.0, 1e-15);

  // Zero noise and zero initial covariance: zero for ever.
  DeadReckoning exact(NoiselessOptions());
  exact.Add(Reading(0, 10.0, 0.3));
  exact.Add(Reading(kNanosPerSecond, 12.0, -0.3));
  EXPECT_TRUE(exact.At(3 * kNanosPerSecond).covariance.isZero(0.0));

  // Default noise: symmetric, positive definite once moving and turning, growing with time.
  DeadReckoning noisy{DeadReckoningOptions{}};
  for (TimeNs k = 0; k <= 50; ++k) noisy.Add(Reading(k * 20'000'000, 8.0, 0.2));
  double previous_trace = 0.0;
  for (TimeNs t = 1'100'000'000; t <= 2'000'000'000; t += 100'000'000) {
    const Eigen::Matrix3d c = noisy.At(t).covariance;
    EXPECT_TRUE(c.isApprox(c.transpose(), 0.0));
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c).eigenvalues().minCoeff(), 0.0);
    EXPECT_GT(c.trace(), previous_trace);
    previous_trace = c.trace();
  }
}

// The first-order covariance agrees with Monte Carlo sampling of the documented model: each
// reading's speed and yaw rate drawn with the configured sigmas and held over its interval.
TEST(DeadReckoningTest, CovarianceMatchesMonteCarloOfTheModel) {
  const std::uint64_t seed = 20260611;
  OdometryNoise noise{0.2, 0.02, 0.0, 0.0};
  DeadReckoningOptions o;
  o.noise = noise;
  DeadReckoning dr(o);
  const int readings = 50;  // 1 s at 50 Hz, then the state at 1 s
  for (TimeNs k = 0; k < readings; ++k) dr.Add(Reading(k * 20'000'000, 10.0, 0.3));
  const EgoState predicted = dr.At(kNanosPerSecond);

  Rng rng(seed);
  const int samples = 20000;
  std::vector<Eigen::Vector3d> ends;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int s = 0; s < samples; ++s) {
    Pose2 p;
    for (TimeNs k = 0; k < readings; ++k) {
      const double speed_mps = 10.0 + noise.speed_noise_mps * rng.Normal();
      const double yaw_rate_radps = 0.3 + noise.yaw_rate_noise_radps * rng.Normal();
      p = IntegrateArc(p, speed_mps, yaw_rate_radps, 0.02);
    }
    ends.emplace_back(p.x(), p.y(), p.yaw);
    mean += ends.back();
  }
  mean /= samples;
  Eigen::Matrix3d sampled = Eigen::Matrix3d::Zero();
  for (const auto& e : ends) sampled += (e - mean) * (e - mean).transpose();
  sampled /= samples - 1;
  for (int i = 0; i < 3; ++i) {
    // 20000 samples: the variance's relative standard error is about 1%.
    EXPECT_NEAR(sampled(i, i), predicted.covariance(i, i), 0.05 * predicted.covariance(i, i))
        << "seed " << seed << " index " << i;
  }
}

TEST(DeadReckoningOptionsTest, ValidateNamesTheField) {
  DeadReckoningOptions o;
  o.noise.speed_noise_mps = -1.0;
  try {
    o.Validate("config.yaml");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "dead_reckoning.noise.speed_noise_mps");
    EXPECT_EQ(e.file(), "config.yaml");
  }
  o = DeadReckoningOptions{};
  o.history_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(DeadReckoning{o}, InputError);
  EXPECT_NO_THROW(DeadReckoningOptions{}.Validate());
}

}  // namespace
}  // namespace lookout
