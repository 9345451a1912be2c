#include "lookout/risk/turn_hypotheses.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace lookout::risk {
namespace {

constexpr double kPi = std::numbers::pi;

// The four_way junction: two 7 m roads crossing at the origin, turned by `yaw` about it and
// moved by `offset` (a frame that is not the world's).
Carriageways FourWay(double yaw = 0.0, const Eigen::Vector2d& offset = Eigen::Vector2d::Zero()) {
  return {Footprint::Box(offset, yaw, 120.0, 7.0),
          Footprint::Box(offset, yaw + 0.5 * kPi, 120.0, 7.0)};
}

Eigen::Vector2d Turned(double yaw, const Eigen::Vector2d& p) {
  return Eigen::Rotation2Dd(yaw) * p;
}

double AngleGap(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * kPi)); }

// A westbound car in its lane (y = 1.75) 20 m east of the junction, at 8 m/s. Its left turn
// into the south arm's lane (x = -1.75) has the radius of the lateral-acceleration limit,
// v^2 / a = 64 / 5 = 12.8 m, tangent to both lane lines: centre (-1.75 + R, 1.75 - R), turn-in
// 21.75 - R metres ahead.
TEST(TurnHypothesesTest, ALeftTurnIsTheArcTangentToBothLanes) {
  const std::optional<TurnPath> t =
      PlanTurn(FourWay(), {20.0, 1.75}, kPi, 8.0, Manoeuvre::kLeftTurn, TurnLimits{});
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(t->radius_m, 12.8, 1e-9);
  EXPECT_NEAR(t->turn_angle_rad, 0.5 * kPi, 1e-9);
  EXPECT_NEAR((t->centre_m - Eigen::Vector2d(-1.75 + 12.8, 1.75 - 12.8)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(t->turn_in_m, 21.75 - 12.8, 1e-9);
}

// Along the turn at constant speed: on the line up to the turn-in, then on the closed-form
// circle (distance R from the centre, heading along its tangent, swept angle = arc length / R),
// then down the exit lane heading south.
TEST(TurnHypothesesTest, ThePathFollowsTheClosedFormCircle) {
  const double v = 8.0;
  const Eigen::Vector2d start(20.0, 1.75);
  const TurnPath t = *PlanTurn(FourWay(), start, kPi, v, Manoeuvre::kLeftTurn, TurnLimits{});
  const std::vector<PathPose> poses = AlongTurn(start, kPi, v, t, 5.0, 0.1);
  ASSERT_EQ(poses.size(), 51u);
  const double arc_m = t.radius_m * 0.5 * kPi;
  int on_arc = 0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const double s = v * 0.1 * static_cast<double>(k);
    const PathPose& p = poses[k];
    if (s <= t.turn_in_m) {
      EXPECT_NEAR((p.position_m - Eigen::Vector2d(20.0 - s, 1.75)).norm(), 0.0, 1e-9) << k;
      EXPECT_NEAR(AngleGap(p.yaw_rad, kPi), 0.0, 1e-12) << k;
    } else if (s <= t.turn_in_m + arc_m) {
      ++on_arc;
      const Eigen::Vector2d r = p.position_m - t.centre_m;
      EXPECT_NEAR(r.norm(), t.radius_m, 1e-9) << k;
      const Eigen::Vector2d heading(std::cos(p.yaw_rad), std::sin(p.yaw_rad));
      EXPECT_NEAR(r.dot(heading), 0.0, 1e-9) << "tangent at " << k;
      EXPECT_NEAR(AngleGap(p.yaw_rad, kPi + (s - t.turn_in_m) / t.radius_m), 0.0, 1e-9) << k;
    } else {
      EXPECT_NEAR(p.position_m.x(), -1.75, 1e-9) << "in the exit lane at " << k;
      EXPECT_NEAR(p.position_m.y(), 1.75 - t.radius_m - (s - t.turn_in_m - arc_m), 1e-9) << k;
      EXPECT_NEAR(AngleGap(p.yaw_rad, 1.5 * kPi), 0.0, 1e-9) << k;
    }
  }
  EXPECT_GT(on_arc, 10);
}

// With no limit on the lateral acceleration the radius is the smallest whose inner side (half
// the car's width, 0.9 m) clears the kerb corner (3.5, -3.5): |centre - corner| = R - 0.9.
TEST(TurnHypothesesTest, TheTightestTurnJustClearsTheKerbCorner) {
  TurnLimits limits;
  limits.max_lateral_acceleration_mps2 = 1e6;
  const TurnPath t =
      *PlanTurn(FourWay(), {20.0, 1.75}, kPi, 8.0, Manoeuvre::kLeftTurn, limits);
  EXPECT_NEAR((t.centre_m - Eigen::Vector2d(3.5, -3.5)).norm(), t.radius_m - 0.9, 1e-9);
  EXPECT_LT(t.radius_m, 5.25);
}

// Speed rules turns out: the widest left turn the corner allows is 15.75 m (v <= 8.87 m/s at
// 5 m/s^2), the widest right turn 3.80 m (v <= 4.36 m/s).
TEST(TurnHypothesesTest, AVehicleTooFastForTheCornerDoesNotTurn) {
  const Carriageways roads = FourWay();
  const TurnLimits limits;
  EXPECT_FALSE(PlanTurn(roads, {40.0, 1.75}, kPi, 20.0, Manoeuvre::kLeftTurn, limits));
  EXPECT_FALSE(PlanTurn(roads, {40.0, 1.75}, kPi, 20.0, Manoeuvre::kRightTurn, limits));
  EXPECT_FALSE(PlanTurn(roads, {40.0, 1.75}, kPi, 10.0, Manoeuvre::kLeftTurn, limits));
  EXPECT_TRUE(PlanTurn(roads, {40.0, 1.75}, kPi, 8.5, Manoeuvre::kLeftTurn, limits).has_value());
  EXPECT_FALSE(PlanTurn(roads, {40.0, 1.75}, kPi, 8.0, Manoeuvre::kRightTurn, limits));
  // 3 m/s: the right turn into the north arm's lane (x = 1.75), radius 9 / 5 = 1.8 m.
  const std::optional<TurnPath> right =
      PlanTurn(roads, {40.0, 1.75}, kPi, 3.0, Manoeuvre::kRightTurn, limits);
  ASSERT_TRUE(right.has_value());
  EXPECT_NEAR(right->radius_m, 1.8, 1e-9);
  EXPECT_NEAR(right->turn_angle_rad, -0.5 * kPi, 1e-9);
  const PathPose end = AlongTurn({40.0, 1.75}, kPi, 3.0, *right, 30.0, 0.1).back();
  EXPECT_NEAR(end.position_m.x(), 1.75, 1e-9);
  EXPECT_GT(end.position_m.y(), 3.5);
}

// No turn in the junction, past it, off the roads, or across a road's axis.
TEST(TurnHypothesesTest, OnlyAVehicleApproachingAJunctionAlongARoadTurns) {
  const Carriageways roads = FourWay();
  const TurnLimits limits;
  EXPECT_FALSE(PlanTurn(roads, {2.0, 1.75}, kPi, 3.0, Manoeuvre::kLeftTurn, limits));
  EXPECT_FALSE(PlanTurn(roads, {-20.0, 1.75}, kPi, 3.0, Manoeuvre::kLeftTurn, limits));
  EXPECT_FALSE(PlanTurn(roads, {20.0, 8.0}, kPi, 3.0, Manoeuvre::kLeftTurn, limits));
  EXPECT_FALSE(PlanTurn(roads, {20.0, 1.75}, 0.75 * kPi, 3.0, Manoeuvre::kLeftTurn, limits));
  EXPECT_FALSE(PlanTurn(roads, {20.0, 1.75}, kPi, 3.0, Manoeuvre::kStraight, limits));
  EXPECT_FALSE(PlanTurn({}, {20.0, 1.75}, kPi, 3.0, Manoeuvre::kLeftTurn, limits));
}

// The geometry does not depend on the frame: the junction and the car turned by 0.7 rad and
// moved give the same radius, turn-in and angle, and the centre moved with them.
TEST(TurnHypothesesTest, TheTurnIsTheSameInAnyFrame) {
  const double yaw = 0.7;
  const Eigen::Vector2d offset(12.0, -30.0);
  const TurnPath a = *PlanTurn(FourWay(), {20.0, 1.75}, kPi, 8.0, Manoeuvre::kLeftTurn, {});
  const TurnPath b = *PlanTurn(FourWay(yaw, offset), offset + Turned(yaw, {20.0, 1.75}),
                               kPi + yaw, 8.0, Manoeuvre::kLeftTurn, {});
  EXPECT_NEAR(a.radius_m, b.radius_m, 1e-9);
  EXPECT_NEAR(a.turn_in_m, b.turn_in_m, 1e-9);
  EXPECT_NEAR(a.turn_angle_rad, b.turn_angle_rad, 1e-9);
  EXPECT_NEAR((offset + Turned(yaw, a.centre_m) - b.centre_m).norm(), 0.0, 1e-9);
}

// The weights sum to one; an impossible turn gets none, the others share its prior in
// proportion to theirs.
TEST(TurnHypothesesTest, TheWeightsSumToOne) {
  for (const double left : {0.0, 0.1, 1.0 / 3.0, 0.5}) {
    for (const double right : {0.0, 0.2, 1.0 / 3.0, 0.5}) {
      for (const bool can_left : {false, true}) {
        for (const bool can_right : {false, true}) {
          const ManoeuvreWeights w = WeighManoeuvres(left, right, can_left, can_right);
          EXPECT_NEAR(w.straight + w.left + w.right, 1.0, 1e-12);
          if (!can_left) {
            EXPECT_EQ(w.left, 0.0);
          }
          if (!can_right) {
            EXPECT_EQ(w.right, 0.0);
          }
          if (can_left && can_right) {
            EXPECT_NEAR(w.left, left, 1e-12);
            EXPECT_NEAR(w.right, right, 1e-12);
          }
        }
      }
    }
  }
  const ManoeuvreWeights w = WeighManoeuvres(1.0 / 3.0, 1.0 / 3.0, true, false);
  EXPECT_NEAR(w.straight, 0.5, 1e-12);
  EXPECT_NEAR(w.left, 0.5, 1e-12);
  const ManoeuvreWeights none = WeighManoeuvres(0.5, 0.5, false, false);
  EXPECT_EQ(none.straight, 1.0);
}

}  // namespace
}  // namespace lookout::risk
