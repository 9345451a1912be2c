#include "lookout/sim/contact.h"

#include <gtest/gtest.h>

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

constexpr double kEgoLength = 4.6;
constexpr double kEgoWidth = 1.9;

Trajectory Car(const std::vector<Vector2d>& path, double speed, double start_s = 0.0,
               double stop_s = 20.0) {
  return Trajectory::Vehicle(path, SpeedProfile::Constant(speed), 4.5, start_s, stop_s);
}

TEST(ContactTest, HeadOnContactAtGapOverClosingSpeed) {
  const Trajectory ego =
      Trajectory::Vehicle({{0, 0}, {200, 0}}, SpeedProfile::Constant(10.0), kEgoLength, 0.0, 20.0);
  const Trajectory actor = Car({{100, 0}, {-100, 0}}, 5.0);
  const auto t =
      FirstContactTime(ego, kEgoLength, kEgoWidth, actor, Footprint::Box(4.5, 1.8), 0.0, 20.0);
  ASSERT_TRUE(t.has_value());
  const double expected = (100.0 - (kEgoLength + 4.5) / 2) / 15.0;
  EXPECT_NEAR(*t, expected, 1e-3);
  // The returned time is a touching one: never before the exact contact, 1e-4 s after at most.
  EXPECT_GE(*t, expected - 1e-9);
  EXPECT_LE(*t, expected + 1e-4 + 1e-9);
}

TEST(ContactTest, ActorAppearingLaterIsOnlyHitOnceItIsThere) {
  const Trajectory ego =
      Trajectory::Vehicle({{0, 0}, {200, 0}}, SpeedProfile::Constant(10.0), kEgoLength, 0.0, 20.0);
  // Appears at its first waypoint at t = 8, when the ego is at x = 80.
  const Trajectory late = Car({{100, 0}, {-100, 0}}, 5.0, 8.0, 20.0);
  const auto t =
      FirstContactTime(ego, kEgoLength, kEgoWidth, late, Footprint::Box(4.5, 1.8), 0.0, 20.0);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 8.0 + (20.0 - (kEgoLength + 4.5) / 2) / 15.0, 1e-3);
  // Removed before it would be reached.
  const Trajectory gone = Car({{100, 0}, {-100, 0}}, 5.0, 0.0, 6.0);
  EXPECT_FALSE(
      FirstContactTime(ego, kEgoLength, kEgoWidth, gone, Footprint::Box(4.5, 1.8), 0.0, 20.0));
  // Outside the asked window.
  const Trajectory actor = Car({{100, 0}, {-100, 0}}, 5.0);
  EXPECT_FALSE(
      FirstContactTime(ego, kEgoLength, kEgoWidth, actor, Footprint::Box(4.5, 1.8), 0.0, 6.0));
  // Appearing on top of the ego: contact the moment it exists.
  const Trajectory parked = Car({{50, 0}, {60, 0}}, 0.0, 5.0, 20.0);
  const auto at_once =
      FirstContactTime(ego, kEgoLength, kEgoWidth, parked, Footprint::Box(4.5, 1.8), 0.0, 20.0);
  ASSERT_TRUE(at_once.has_value());
  EXPECT_EQ(*at_once, 5.0);
}

TEST(ContactTest, CrossingPathsMeetWhenBothIntervalsOverlap) {
  // Ego east along y = 0 from x = -40 at 10 m/s; a car north along x = 0 from y = -30 at
  // 8 m/s. Both stay axis-aligned, so they touch when their x and y extents both overlap:
  // x from t = (40 - 2.3 - 0.9) / 10 = 3.68, y from t = (30 - 2.25 - 0.95) / 8 = 3.35.
  const Trajectory ego =
      Trajectory::Vehicle({{-40, 0}, {40, 0}}, SpeedProfile::Constant(10.0), kEgoLength, 0.0, 10.0);
  const Trajectory actor = Car({{0, -30}, {0, 30}}, 8.0);
  const auto t =
      FirstContactTime(ego, kEgoLength, kEgoWidth, actor, Footprint::Box(4.5, 1.8), 0.0, 10.0);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 3.68, 1e-3);
}

TEST(ContactTest, NearMissReturnsNothing) {
  // As above with the ego 10 m further on: it has left the car's lane (x extent clear from
  // t = 3.32) just before the car reaches its side (y extent from t = 3.35).
  const Trajectory ego =
      Trajectory::Vehicle({{-30, 0}, {40, 0}}, SpeedProfile::Constant(10.0), kEgoLength, 0.0, 10.0);
  const Trajectory actor = Car({{0, -30}, {0, 30}}, 8.0);
  EXPECT_FALSE(
      FirstContactTime(ego, kEgoLength, kEgoWidth, actor, Footprint::Box(4.5, 1.8), 0.0, 10.0));
}

TEST(ContactTest, PedestrianInTheLaneIsHitByTheFrontEdge) {
  // The walker is at y = -3.5 + 0.5 t, inside the ego's lateral extent [-2.7, -0.8] when the
  // front edge (x = -50 + 10 t + 2.3) reaches x = -0.3, at t = 4.74.
  const Trajectory ego = Trajectory::Vehicle({{-50, -1.75}, {50, -1.75}},
                                             SpeedProfile::Constant(10.0), kEgoLength, 0.0, 10.0);
  const Trajectory walker =
      Trajectory::Walker({{0, -3.5}, {0, 10}}, SpeedProfile::Constant(0.5), 0.0, 10.0);
  const auto t =
      FirstContactTime(ego, kEgoLength, kEgoWidth, walker, Footprint::Circle(0.3), 0.0, 10.0);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 4.74, 1e-3);
}

TEST(ContactTest, MatchesADenseScanOnACurvedPath) {
  // The default scenario's left turn across the ego's path.
  const Trajectory ego = Trajectory::Vehicle({{-60, -1.75}, {60, -1.75}},
                                             SpeedProfile::Constant(11.1), kEgoLength, 0.0, 12.0);
  const Trajectory actor = Car({{45, 1.75}, {5, 1.75}, {-1.75, -5}, {-1.75, -60}}, 8.0, 0.0, 12.0);
  const Footprint fp = Footprint::Box(4.5, 1.8);
  const auto t = FirstContactTime(ego, kEgoLength, kEgoWidth, actor, fp, 0.0, 12.0);
  ASSERT_TRUE(t.has_value());
  double dense = -1.0;
  for (int i = 0; i <= 120000; ++i) {
    const double s = 1e-4 * i;
    if (Overlap(FootprintAt(Footprint::Box(kEgoLength, kEgoWidth), ego.At(s).pose, -1),
                FootprintAt(fp, actor.At(s).pose, 0))) {
      dense = s;
      break;
    }
  }
  ASSERT_GE(dense, 0.0);
  EXPECT_NEAR(*t, dense, 2e-4);
}

}  // namespace
}  // namespace lookout::sim
