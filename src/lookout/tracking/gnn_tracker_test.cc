#include "lookout/tracking/gnn_tracker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace lookout::tracking {
namespace {

constexpr TimeNs kTick = 80'000'000;  // 12.5 Hz
constexpr double kTickS = 0.08;

Detection At(double x, double y, ObjectClass c = ObjectClass::kUnknown, int sensors = 1) {
  Detection d;
  d.position_m = {x, y};
  d.covariance = Eigen::Matrix2d::Identity() * 0.01;
  d.object_class = c;
  d.sensors = sensors;
  return d;
}

TEST(GnnTrackerTest, OneSensorConfirmsAfterThreeUpdatesAndLearnsTheVelocity) {
  GnnTracker tracker;
  for (int k = 0; k < 40; ++k) {
    ASSERT_TRUE(tracker.Step(k * kTick, {At(1.5 * kTickS * k, 2.0, ObjectClass::kPedestrian)}));
    if (k < 2) {
      EXPECT_TRUE(tracker.ConfirmedTracks().empty()) << "scan " << k;
    }
    if (k == 2) {
      EXPECT_EQ(tracker.ConfirmedTracks().size(), 1u);
    }
  }
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_NEAR(tracker.tracks()[0].Velocity().x(), 1.5, 0.05);
  EXPECT_NEAR(tracker.tracks()[0].Velocity().y(), 0.0, 0.05);
}

TEST(GnnTrackerTest, TwoSensorsConfirmAtOnce) {
  GnnTracker tracker;
  tracker.Step(0, {At(5.0, 0.0, ObjectClass::kCar, 2)});
  EXPECT_EQ(tracker.ConfirmedTracks().size(), 1u);
}

// Two pedestrians crossing paths at right angles keep their ids through the crossing.
TEST(GnnTrackerTest, CrossingTargetsKeepTheirIds) {
  GnnTracker tracker;
  std::uint32_t east_id = 0, north_id = 0;
  for (int k = 0; k <= 50; ++k) {
    const double t = kTickS * k;
    // East at 1.4 m/s through (0, 0) at t = 2 s; north at 1.2 m/s through it at t = 2 s too.
    tracker.Step(k * kTick, {At(-2.8 + 1.4 * t, 0.0, ObjectClass::kPedestrian),
                             At(0.0, -2.4 + 1.2 * t, ObjectClass::kPedestrian)});
    if (k == 10) {
      ASSERT_EQ(tracker.tracks().size(), 2u);
      east_id = tracker.tracks()[0].Velocity().x() > tracker.tracks()[1].Velocity().x()
                    ? tracker.tracks()[0].id
                    : tracker.tracks()[1].id;
      north_id =
          east_id == tracker.tracks()[0].id ? tracker.tracks()[1].id : tracker.tracks()[0].id;
    }
  }
  ASSERT_EQ(tracker.tracks().size(), 2u);
  for (const Track& track : tracker.tracks()) {
    if (track.id == east_id) {
      EXPECT_GT(track.Position().x(), 2.0);
    }
    if (track.id == north_id) {
      EXPECT_GT(track.Position().y(), 2.0);
    }
  }
}

// A pedestrian hidden for 1.2 s (15 scans) coasts and is picked up again by the same track;
// one that stays hidden longer than max_misses_pedestrian is deleted.
TEST(GnnTrackerTest, CoastsThroughOcclusionThenDeletes) {
  GnnTracker tracker;
  auto walker = [](int k) { return At(1.2 * kTickS * k, 0.0, ObjectClass::kPedestrian); };
  for (int k = 0; k < 20; ++k) tracker.Step(k * kTick, {walker(k)});
  ASSERT_EQ(tracker.ConfirmedTracks().size(), 1u);
  const std::uint32_t id = tracker.tracks()[0].id;
  for (int k = 20; k < 35; ++k) tracker.Step(k * kTick, {});
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_TRUE(tracker.tracks()[0].coasting);
  EXPECT_NEAR(tracker.tracks()[0].Position().x(), 1.2 * kTickS * 34, 0.2) << "predicted through";
  tracker.Step(35 * kTick, {walker(35)});
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_EQ(tracker.tracks()[0].id, id);
  EXPECT_FALSE(tracker.tracks()[0].coasting);
  for (int k = 36; k <= 36 + GnnOptions{}.max_misses_pedestrian; ++k) tracker.Step(k * kTick, {});
  EXPECT_TRUE(tracker.tracks().empty());
}

TEST(GnnTrackerTest, APedestrianNeverJoinsACarTrack) {
  GnnTracker tracker;
  for (int k = 0; k < 5; ++k) {
    tracker.Step(k * kTick, {At(10.0 * kTickS * k, 0.0, ObjectClass::kCar)});
  }
  tracker.Step(5 * kTick, {At(10.0 * kTickS * 5, 0.0, ObjectClass::kPedestrian)});
  ASSERT_EQ(tracker.tracks().size(), 2u);
  EXPECT_EQ(tracker.tracks()[0].misses, 1);
  EXPECT_EQ(tracker.tracks()[1].object_class, ObjectClass::kPedestrian);
}

TEST(GnnTrackerTest, BadInputIsRefusedOrDropped) {
  GnnTracker tracker;
  EXPECT_TRUE(tracker.Step(10 * kTick, {At(1.0, 1.0)}));
  EXPECT_FALSE(tracker.Step(5 * kTick, {At(1.0, 1.0)})) << "time going backwards";
  EXPECT_EQ(tracker.refused_scans(), 1);
  Detection nan = At(std::numeric_limits<double>::quiet_NaN(), 0.0);
  Detection singular = At(2.0, 2.0);
  singular.covariance.setZero();
  EXPECT_TRUE(tracker.Step(11 * kTick, {nan, singular}));
  EXPECT_EQ(tracker.dropped_detections(), 2);
  EXPECT_TRUE(tracker.Step(12 * kTick, {}));  // an empty scan is fine
}

}  // namespace
}  // namespace lookout::tracking
