#include "lookout/sim/trajectory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

constexpr double kCarLength = 4.5;  // wheelbase 2.7 m with the default fraction

double DistanceToSegment(const Vector2d& a, const Vector2d& b, const Vector2d& p) {
  const Vector2d ab = b - a;
  const double u = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + u * ab - p).norm();
}

double DistanceToPolyline(const std::vector<Vector2d>& path, const Vector2d& p) {
  double best = 1e300;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    best = std::min(best, DistanceToSegment(path[i], path[i + 1], p));
  }
  return best;
}

TEST(TrajectoryTest, StraightPathIsDrivenExactly) {
  const std::vector<Vector2d> path = {{-10.0, 2.0}, {90.0, 2.0}};
  const Trajectory tr =
      Trajectory::Vehicle(path, SpeedProfile::Constant(7.5), kCarLength, 0.0, 10.0);
  for (double t = 0.0; t <= 10.0; t += 0.137) {
    const KinematicState s = tr.At(t);
    EXPECT_NEAR(s.pose.x(), -10.0 + 7.5 * t, 1e-9) << "t = " << t;
    EXPECT_NEAR(s.pose.y(), 2.0, 1e-12) << "t = " << t;
    EXPECT_NEAR(s.pose.yaw, 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(s.speed_mps, 7.5);
    EXPECT_NEAR(s.yaw_rate_radps, 0.0, 1e-12);
    EXPECT_NEAR(s.acceleration_mps2, 0.0, 1e-12);
    EXPECT_TRUE(s.Velocity().isApprox(Vector2d(7.5, 0.0)));
  }
}

TEST(TrajectoryTest, DiagonalPathStaysOnItsLine) {
  const Vector2d start(5.0, -3.0);
  const Vector2d dir = Vector2d(std::cos(0.5), std::sin(0.5));
  const std::vector<Vector2d> path = {start, start + 200.0 * dir};
  const Trajectory tr =
      Trajectory::Vehicle(path, SpeedProfile::Constant(13.0), kCarLength, 0.0, 12.0);
  for (double t = 0.0; t <= 12.0; t += 0.25) {
    const Vector2d r = tr.At(t).pose.translation - start;
    EXPECT_NEAR(r.dot(dir), 13.0 * t, 1e-8) << "t = " << t;
    EXPECT_NEAR(r.x() * dir.y() - r.y() * dir.x(), 0.0, 1e-8) << "t = " << t;
    EXPECT_NEAR(tr.At(t).pose.yaw, 0.5, 1e-9);
  }
}

TEST(TrajectoryTest, RightAngleCornerIsDrivenAsAnArc) {
  const std::vector<Vector2d> path = {{-40.0, 0.0}, {0.0, 0.0}, {0.0, 40.0}};
  const double v = 8.0;
  const TrajectoryOptions opt;
  const Trajectory tr =
      Trajectory::Vehicle(path, SpeedProfile::Constant(v), kCarLength, 0.0, 15.0, opt);
  const double wheelbase = opt.wheelbase_fraction * kCarLength;
  const double max_yaw_rate = v * std::tan(opt.max_steer_rad) / wheelbase;

  double max_deviation = 0.0;
  double max_settled_error = 0.0;
  double prev_yaw = tr.At(0.0).pose.yaw;
  for (double t = opt.step_s; t <= 15.0; t += opt.step_s) {
    const KinematicState s = tr.At(t);
    max_deviation = std::max(max_deviation, DistanceToPolyline(path, s.pose.translation));
    // Smooth: the heading turns by at most the steering limit's yaw rate per step.
    EXPECT_LE(std::abs(WrapAngle(s.pose.yaw - prev_yaw)), max_yaw_rate * opt.step_s + 1e-9)
        << "t = " << t;
    EXPECT_LE(std::abs(s.yaw_rate_radps), max_yaw_rate + 1e-9);
    prev_yaw = s.pose.yaw;
    // Pure pursuit's lateral error decays like exp(-s / lookahead) with damping 1/sqrt(2);
    // four lookaheads past the corner it is gone.
    if (s.pose.y() > 20.0) max_settled_error = std::max(max_settled_error, std::abs(s.pose.x()));
  }
  // Pure pursuit cuts the corner, by a fraction of the 4.8 m lookahead.
  EXPECT_GT(max_deviation, 0.3);
  EXPECT_LT(max_deviation, 1.5);
  EXPECT_LT(max_settled_error, 0.05);

  const KinematicState end = tr.At(15.0);  // 120 m of driving: the 80 m path is done
  EXPECT_NEAR(RadToDeg(end.pose.yaw), 90.0, 1.0);
  EXPECT_NEAR(end.pose.y(), 40.0, 0.05);
  EXPECT_NEAR(end.pose.x(), 0.0, 0.05);
  EXPECT_EQ(end.speed_mps, 0.0);
}

TEST(TrajectoryTest, BrakingToAStopLandsWhereTheIntegralSays) {
  // Breakpoints between integration steps, to exercise the exact integral across them.
  const SpeedProfile brake{{{2.003, 10.0}, {4.007, 0.0}}};
  const Trajectory tr =
      Trajectory::Vehicle({{0.0, 0.0}, {100.0, 0.0}}, brake, kCarLength, 0.0, 8.0);
  const double stop_x = 10.0 * 2.003 + 0.5 * 10.0 * (4.007 - 2.003);
  // Samples are exact; between them At() interpolates linearly, within |a| step^2 / 8.
  const double decel = 10.0 / (4.007 - 2.003);
  const double between = decel * 0.01 * 0.01 / 8.0;
  EXPECT_NEAR(tr.At(4.007).pose.x(), stop_x, between + 1e-9);
  EXPECT_NEAR(tr.At(4.01).pose.x(), stop_x, 1e-9);
  EXPECT_NEAR(tr.At(6.0).pose.x(), stop_x, 1e-9);
  EXPECT_NEAR(tr.At(8.0).pose.x(), stop_x, 1e-9);
  EXPECT_DOUBLE_EQ(tr.At(8.0).speed_mps, 0.0);
  EXPECT_DOUBLE_EQ(tr.At(7.0).acceleration_mps2, 0.0);
  // Half way down the ramp, at a sample and between samples.
  for (const double t : {3.0, 3.005}) {
    const double x = 10.0 * t - 0.5 * decel * (t - 2.003) * (t - 2.003);
    EXPECT_NEAR(tr.At(t).speed_mps, 10.0 - decel * (t - 2.003), 1e-9);
    EXPECT_NEAR(tr.At(t).acceleration_mps2, -decel, 1e-9);
    EXPECT_NEAR(tr.At(t).pose.x(), x, t == 3.0 ? 1e-9 : between + 1e-9);
  }
}

TEST(TrajectoryTest, StopsAtThePathEndAndStays) {
  const Trajectory tr = Trajectory::Vehicle({{0.0, 0.0}, {20.0, 0.0}}, SpeedProfile::Constant(5.0),
                                            kCarLength, 0.0, 10.0);
  EXPECT_NEAR(tr.At(2.0).pose.x(), 10.0, 1e-9);
  for (const double t : {4.01, 6.0, 10.0, 50.0}) {
    const KinematicState s = tr.At(t);
    EXPECT_NEAR(s.pose.x(), 20.0, 1e-9) << "t = " << t;
    EXPECT_NEAR(s.pose.y(), 0.0, 1e-12);
    EXPECT_NEAR(s.speed_mps, 0.0, 1e-9);
    EXPECT_NEAR(s.yaw_rate_radps, 0.0, 1e-12);
    EXPECT_NEAR(s.pose.yaw, 0.0, 1e-12);
  }
  EXPECT_TRUE(tr.Present(10.0));
  EXPECT_FALSE(tr.Present(10.01));
}

TEST(TrajectoryTest, YawRateIsSpeedOverRadiusOnACircle) {
  const double radius = 20.0;
  const double v = 10.0;
  std::vector<Vector2d> circle;
  for (int i = 0; i <= 648; ++i) {  // 0.9 of a turn, counter-clockwise, 0.5 degree chords
    const double a = DegToRad(0.5 * i);
    circle.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  const Trajectory tr =
      Trajectory::Vehicle(circle, SpeedProfile::Constant(v), kCarLength, 0.0, 9.0);
  for (double t = 3.0; t <= 9.0; t += 0.1) {  // once the start transient is over
    const KinematicState s = tr.At(t);
    EXPECT_NEAR(s.yaw_rate_radps, v / radius, 0.005 * v / radius) << "t = " << t;
    EXPECT_NEAR(s.pose.translation.norm(), radius, 0.02) << "t = " << t;
    // Tangent to the circle, counter-clockwise.
    const double tangent = std::atan2(s.pose.y(), s.pose.x()) + kPi / 2;
    EXPECT_NEAR(WrapAngle(s.pose.yaw - tangent), 0.0, 0.01) << "t = " << t;
  }
}

TEST(TrajectoryTest, ZeroSpeedStandsAtTheFirstWaypointAlongTheFirstSegment) {
  const Trajectory tr = Trajectory::Vehicle({{3.0, 4.0}, {3.0, 10.0}, {8.0, 10.0}},
                                            SpeedProfile::Constant(0.0), kCarLength, 0.0, 5.0);
  for (const double t : {-1.0, 0.0, 2.5, 5.0, 9.0}) {
    const KinematicState s = tr.At(t);
    EXPECT_EQ(s.pose.translation, Vector2d(3.0, 4.0)) << "t = " << t;
    EXPECT_NEAR(s.pose.yaw, kPi / 2, 1e-12);
    EXPECT_EQ(s.speed_mps, 0.0);
    EXPECT_EQ(s.yaw_rate_radps, 0.0);
  }
  // Standing until the profile says otherwise, then moving off.
  const SpeedProfile go{{{0.0, 0.0}, {2.0, 0.0}, {4.0, 4.0}}};
  const Trajectory later = Trajectory::Vehicle({{0.0, 0.0}, {50.0, 0.0}}, go, kCarLength, 0.0, 5.0);
  EXPECT_EQ(later.At(1.9).pose.translation, Vector2d(0.0, 0.0));
  EXPECT_NEAR(later.At(4.0).pose.x(), 4.0, 1e-9);
  EXPECT_NEAR(later.At(3.0).acceleration_mps2, 2.0, 1e-12);
}

TEST(TrajectoryTest, ActorTimeWindowClampsAndStartsAtTheFirstWaypoint) {
  const Trajectory tr = Trajectory::Vehicle({{0.0, 0.0}, {0.0, -100.0}},
                                            SpeedProfile::Constant(10.0), kCarLength, 2.0, 6.0);
  EXPECT_FALSE(tr.Present(1.99));
  EXPECT_TRUE(tr.Present(2.0));
  EXPECT_EQ(tr.At(0.0).pose.translation, Vector2d(0.0, 0.0));
  EXPECT_NEAR(tr.At(0.0).pose.yaw, -kPi / 2, 1e-12);
  EXPECT_NEAR(tr.At(3.0).pose.y(), -10.0, 1e-9);
  EXPECT_NEAR(tr.At(6.0).pose.y(), -40.0, 1e-9);
  EXPECT_NEAR(tr.At(7.0).pose.y(), -40.0, 1e-9);  // clamped to stop
}

TEST(TrajectoryTest, HeadingWestInterpolatesAcrossPi) {
  const Trajectory tr = Trajectory::Vehicle({{0.0, 0.0}, {-50.0, 0.0}}, SpeedProfile::Constant(5.0),
                                            kCarLength, 0.0, 2.0);
  for (double t = 0.0; t <= 2.0; t += 0.0037) {
    EXPECT_NEAR(std::cos(tr.At(t).pose.yaw), -1.0, 1e-12) << "t = " << t;
  }
}

TEST(TrajectoryTest, StateIsConsistentWithItsOwnDerivatives) {
  // A corner under braking then accelerating: velocity, yaw rate and acceleration must be the
  // derivatives of pose and speed (central differences over one step, away from kinks).
  const std::vector<Vector2d> path = {{-30.0, 0.0}, {0.0, 0.0}, {15.0, -20.0}, {15.0, -60.0}};
  const SpeedProfile speed{{{0.0, 12.0}, {2.0, 6.0}, {5.0, 6.0}, {8.0, 10.0}}};
  const TrajectoryOptions opt;
  const Trajectory tr = Trajectory::Vehicle(path, speed, 8.0, 0.0, 10.0, opt);
  const double h = opt.step_s;
  for (double t = 0.105; t < 9.9; t += 0.2) {
    const KinematicState a = tr.At(t - h);
    const KinematicState s = tr.At(t);
    const KinematicState b = tr.At(t + h);
    const Vector2d velocity = (b.pose.translation - a.pose.translation) / (2 * h);
    EXPECT_LT((velocity - s.Velocity()).norm(), 0.02 * s.speed_mps + 1e-9) << "t = " << t;
    EXPECT_NEAR(WrapAngle(b.pose.yaw - a.pose.yaw) / (2 * h), s.yaw_rate_radps, 0.05)
        << "t = " << t;
    EXPECT_NEAR((b.speed_mps - a.speed_mps) / (2 * h), s.acceleration_mps2, 1e-6) << "t = " << t;
  }
}

TEST(TrajectoryTest, WalkerFollowsThePolylineAndTurnsAtCorners) {
  const Trajectory tr = Trajectory::Walker({{0.0, 0.0}, {3.0, 0.0}, {3.0, 4.0}},
                                           SpeedProfile::Constant(1.5), 1.0, 10.0);
  EXPECT_EQ(tr.At(0.0).pose.translation, Vector2d(0.0, 0.0));  // before start: clamped
  EXPECT_NEAR(tr.At(1.0).pose.yaw, 0.0, 1e-12);
  EXPECT_NEAR(tr.At(2.0).pose.x(), 1.5, 1e-9);
  EXPECT_NEAR(tr.At(2.0).pose.yaw, 0.0, 1e-12);
  const KinematicState s = tr.At(4.0);  // 4.5 m walked: 1.5 m up the second leg
  EXPECT_NEAR(s.pose.x(), 3.0, 1e-9);
  EXPECT_NEAR(s.pose.y(), 1.5, 1e-9);
  EXPECT_NEAR(s.pose.yaw, kPi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(s.speed_mps, 1.5);
  EXPECT_EQ(s.yaw_rate_radps, 0.0);
  EXPECT_TRUE(s.Velocity().isApprox(Vector2d(0.0, 1.5)));
  for (const double t : {5.7, 6.0, 10.0}) {  // 7 m walked at 5.67 s: at the end, standing
    EXPECT_NEAR(tr.At(t).pose.x(), 3.0, 1e-9);
    EXPECT_NEAR(tr.At(t).pose.y(), 4.0, 1e-9);
    EXPECT_NEAR(tr.At(t).pose.yaw, kPi / 2, 1e-12);
    EXPECT_EQ(tr.At(t).speed_mps, 0.0);
  }
}

TEST(TrajectoryTest, WalkerWithABrakingProfile) {
  const SpeedProfile p{{{0.0, 2.0}, {2.0, 2.0}, {3.0, 0.0}}};
  const Trajectory tr = Trajectory::Walker({{0.0, 0.0}, {0.0, 10.0}}, p, 0.0, 5.0);
  EXPECT_NEAR(tr.At(5.0).pose.y(), 5.0, 1e-9);
  EXPECT_NEAR(tr.At(2.5).acceleration_mps2, -2.0, 1e-12);
}

TEST(TrajectoryTest, DuplicateWaypointsAreHarmless) {
  const Trajectory tr = Trajectory::Vehicle({{0.0, 0.0}, {0.0, 0.0}, {10.0, 0.0}, {10.0, 0.0}},
                                            SpeedProfile::Constant(2.0), kCarLength, 0.0, 10.0);
  EXPECT_NEAR(tr.At(0.0).pose.yaw, 0.0, 1e-12);
  EXPECT_NEAR(tr.At(3.0).pose.x(), 6.0, 1e-9);
  EXPECT_NEAR(tr.At(9.0).pose.x(), 10.0, 1e-9);
  const Trajectory still =
      Trajectory::Walker({{1.0, 1.0}, {1.0, 1.0}}, SpeedProfile::Constant(2.0), 0.0, 3.0);
  EXPECT_EQ(still.At(2.0).pose.translation, Vector2d(1.0, 1.0));
  EXPECT_EQ(still.At(2.0).speed_mps, 0.0);
}

TEST(TrajectoryTest, IsDeterministic) {
  const std::vector<Vector2d> path = {{45, 1.75}, {5, 1.75}, {-1.75, -5}, {-1.75, -60}};
  const Trajectory a =
      Trajectory::Vehicle(path, SpeedProfile::Constant(8.0), kCarLength, 0.0, 12.0);
  const Trajectory b =
      Trajectory::Vehicle(path, SpeedProfile::Constant(8.0), kCarLength, 0.0, 12.0);
  for (double t = 0.0; t <= 12.0; t += 0.013) {
    ASSERT_EQ(a.At(t).pose.translation, b.At(t).pose.translation);
    ASSERT_EQ(a.At(t).pose.yaw, b.At(t).pose.yaw);
  }
}

}  // namespace
}  // namespace lookout::sim
