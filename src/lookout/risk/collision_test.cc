#include "lookout/risk/collision.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lookout/risk/risk_test_support.h"

namespace lookout::risk {
namespace {

using testing::kDt;
using testing::Straight;

// A box moving along its length at `velocity`.
FootprintTrack StraightBox(const Eigen::Vector2d& start, const Eigen::Vector2d& velocity,
                           double length, double width, double horizon_s = 5.0) {
  FootprintTrack t;
  const double yaw = std::atan2(velocity.y(), velocity.x());
  for (int k = 0; k * kDt <= horizon_s + 1e-9; ++k) {
    t.push_back(Footprint::Box(start + velocity * (k * kDt), yaw, length, width));
  }
  return t;
}

// Head-on: the TTC is the gap between the circles over the closing speed.
TEST(CollisionTest, HeadOnTtcIsGapOverClosingSpeed) {
  const FootprintTrack ego = Straight({0.0, 0.0}, {11.0, 0.0}, 1.2);
  const FootprintTrack car = Straight({47.3, 0.0}, {-9.0, 0.0}, 1.3);
  const auto c = FirstCollision(ego, car, kDt);
  ASSERT_TRUE(c.has_value());
  const double gap = 47.3 - 1.2 - 1.3;
  EXPECT_NEAR(c->ttc_s, gap / 20.0, 1e-12);
  EXPECT_EQ(c->step, 23u);  // 2.24 s: the first step in contact is 2.3 s
}

// Two points on crossing straight paths meet when both reach the crossing; with circles, when
// their distance first equals the radii's sum: solve |p(t)| = r analytically.
TEST(CollisionTest, CrossingPathsGiveTheAnalyticMeetingTime) {
  // Ego east along y = 0 from x = -30 at 10 m/s, the other north along x = 0 from y = -24 at
  // 8 m/s: both reach the crossing at t = 3 s. Relative position d(t) = (-30 + 10 t, 24 - 8 t).
  const FootprintTrack ego = Straight({-30.0, 0.0}, {10.0, 0.0}, 1.0);
  const FootprintTrack other = Straight({0.0, -24.0}, {0.0, 8.0}, 1.0);
  // |d(t)|^2 = 164 (t - 3)^2 = 4: t = 3 - 2 / sqrt(164).
  const double t_exact = 3.0 - 2.0 / std::sqrt(164.0);
  const auto c = FirstCollision(ego, other, kDt);
  ASSERT_TRUE(c.has_value());
  // The distance is not linear in time here (it is |t - 3| sqrt(164) only on the line through
  // the crossing), but on this path it is: the relative motion heads straight for the origin.
  EXPECT_NEAR(c->ttc_s, t_exact, 1e-9);
}

TEST(CollisionTest, PathsThatMissGiveNoCollision) {
  const FootprintTrack ego = Straight({-30.0, 0.0}, {10.0, 0.0}, 1.0);
  const FootprintTrack other = Straight({0.0, -24.0}, {0.0, 4.0}, 1.0);  // reaches y = 0 at 6 s
  EXPECT_FALSE(FirstCollision(ego, other, kDt).has_value());
}

// Boxes head-on: the gap between the fronts over the closing speed; crossing at right angles:
// the ego's front meets the other's side when the x-extents first overlap (the y-extents
// already do), t = (30 - 2.3 - 0.9) / 10.
TEST(CollisionTest, BoxesGiveTheAnalyticContactTimes) {
  const FootprintTrack ego = StraightBox({0.0, 0.0}, {11.0, 0.0}, 4.6, 1.9);
  const FootprintTrack car = StraightBox({47.3, 0.5}, {-9.0, 0.0}, 4.5, 1.8);
  const auto head_on = FirstCollision(ego, car, kDt);
  ASSERT_TRUE(head_on.has_value());
  EXPECT_NEAR(head_on->ttc_s, (47.3 - 2.3 - 2.25) / 20.0, 1e-12);
  const FootprintTrack crossing_ego = StraightBox({-30.0, 0.0}, {10.0, 0.0}, 4.6, 1.9);
  const FootprintTrack crossing = StraightBox({0.0, -24.0}, {0.0, 8.0}, 4.5, 1.8);
  const auto c = FirstCollision(crossing_ego, crossing, kDt);
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->ttc_s, (30.0 - 2.3 - 0.9) / 10.0, 1e-9);
  // A car in the next lane (3.5 m between centres) passes: its box never meets the ego's,
  // where circles of half the diagonal would.
  EXPECT_FALSE(FirstCollision(ego, StraightBox({47.3, 3.5}, {-9.0, 0.0}, 4.5, 1.8), kDt));
  EXPECT_TRUE(FirstCollision(Straight({0.0, 0.0}, {11.0, 0.0}, 2.47),
                             Straight({47.3, 3.5}, {-9.0, 0.0}, 2.42), kDt));
}

TEST(CollisionTest, OverlapAtTheStartIsTtcZero) {
  const FootprintTrack a = Straight({0.0, 0.0}, {1.0, 0.0}, 1.0);
  const FootprintTrack b = Straight({1.5, 0.0}, {1.0, 0.0}, 1.0);
  const auto c = FirstCollision(a, b, kDt);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->ttc_s, 0.0);
}

}  // namespace
}  // namespace lookout::risk
