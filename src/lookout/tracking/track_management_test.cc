#include "lookout/tracking/track_management.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::tracking {
namespace {

constexpr TimeNs kScan = 80'000'000;  // 12.5 Hz
constexpr ViewFraction kInView{1.0, 1.0};
constexpr ViewFraction kHidden{1.0, 0.2};     // in view, mostly behind something nearer
constexpr ViewFraction kOutOfView{0.3, 0.3};  // mostly outside the fan

Detection Seen(int sensors, ObjectClass c = ObjectClass::kCar) {
  Detection d;
  d.sensors = sensors;
  d.object_class = c;
  return d;
}

TEST(TrackManagement, ConfirmedAfterOneUpdateWithTwoSensorsAndThreeWithOne) {
  const TrackManagementOptions o;
  EXPECT_EQ(BornTrack(o, Seen(2), 0).status, TrackStatus::kConfirmed);
  Track t = BornTrack(o, Seen(1), 0);
  EXPECT_EQ(t.status, TrackStatus::kTentative);
  t = AfterDetection(o, t, Seen(1), 0);
  EXPECT_EQ(t.status, TrackStatus::kTentative);
  t = AfterDetection(o, t, Seen(1), 0);
  EXPECT_EQ(t.status, TrackStatus::kConfirmed);
  EXPECT_EQ(t.updates, 3);
  // A second-sensor sighting confirms a tentative track at once.
  Track u = AfterDetection(o, BornTrack(o, Seen(1), 0), Seen(2), 0);
  EXPECT_EQ(u.status, TrackStatus::kConfirmed);
}

TEST(TrackManagement, MissesCoastThenExpireByClass) {
  TrackManagementOptions o;
  o.max_misses_pedestrian = 4;
  o.max_misses_tentative = 1;
  Track walker = BornTrack(o, Seen(2, ObjectClass::kPedestrian), 0);
  for (int miss = 1; miss <= 4; ++miss) {
    walker = AfterMiss(o, walker, kInView, miss * kScan);
    EXPECT_TRUE(walker.coasting);
    EXPECT_EQ(walker.misses, miss);
    EXPECT_FALSE(Expired(o, walker)) << miss;
  }
  EXPECT_TRUE(Expired(o, AfterMiss(o, walker, kInView, 5 * kScan)));
  walker = AfterDetection(o, walker, Seen(1), 5 * kScan);
  EXPECT_EQ(walker.misses, 0);
  EXPECT_FALSE(walker.coasting);
  EXPECT_EQ(walker.last_detected, 5 * kScan);

  Track tentative = BornTrack(o, Seen(1, ObjectClass::kCar), 0);
  EXPECT_FALSE(Expired(o, AfterMiss(o, tentative, kInView, kScan)));
  EXPECT_TRUE(
      Expired(o, AfterMiss(o, AfterMiss(o, tentative, kInView, kScan), kInView, 2 * kScan)));
}

// A confirmed track that something nearer hid is not missed while its prediction is worth
// something, max_hidden_s for a walker, max_hidden_distance_m for a faster road user; then it
// is lost. Seen from min_visible_fraction on; a track out of the view, or a tentative one, is
// missed.
TEST(TrackManagement, AHiddenTrackCoastsWithoutMissesWhileItsPredictionHolds) {
  TrackManagementOptions o;
  o.max_misses_pedestrian = 4;
  o.max_hidden_s = 3.0;
  o.max_hidden_distance_m = 6.0;
  EXPECT_TRUE(Hidden(o, kHidden));
  EXPECT_FALSE(Hidden(o, kInView));
  EXPECT_FALSE(Hidden(o, kOutOfView));
  EXPECT_FALSE(Hidden(o, {1.0, o.min_visible_fraction}));

  // A walker at 1.5 m/s: 3 s hidden (4.5 m) without a miss, then misses.
  Track walker = BornTrack(o, Seen(2, ObjectClass::kPedestrian), 0);
  walker.state.mean = Eigen::Vector4d(0.0, 0.0, 1.5, 0.0);
  int k = 1;
  for (; ToSeconds(k * kScan) <= o.max_hidden_s; ++k) {
    walker = AfterMiss(o, walker, kHidden, k * kScan);
    EXPECT_TRUE(walker.coasting);
    ASSERT_EQ(walker.misses, 0) << k;
    ASSERT_FALSE(Expired(o, walker)) << k;
  }
  EXPECT_TRUE(Expired(o, AfterMiss(o, walker, kHidden, k * kScan)));
  EXPECT_EQ(AfterMiss(o, walker, kInView, k * kScan).misses, 1);
  EXPECT_EQ(AfterMiss(o, walker, kOutOfView, k * kScan).misses, 1);
  EXPECT_FALSE(Expired(o, AfterMiss(o, walker, kInView, k * kScan)));

  // Seen again: the clock starts anew.
  walker = AfterDetection(o, walker, Seen(2), k * kScan);
  EXPECT_FALSE(Expired(o, AfterMiss(o, walker, kHidden, (k + 1) * kScan)));

  // A cyclist at 5 m/s: 6 m unseen after 1.2 s.
  Track cyclist = BornTrack(o, Seen(2, ObjectClass::kCyclist), 0);
  cyclist.state.mean = Eigen::Vector4d(0.0, 0.0, 3.0, -4.0);
  k = 1;
  for (; ToSeconds(k * kScan) * 5.0 <= o.max_hidden_distance_m; ++k) {
    cyclist = AfterMiss(o, cyclist, kHidden, k * kScan);
    ASSERT_FALSE(Expired(o, cyclist)) << k;
  }
  EXPECT_EQ(k, 16);  // 1.28 s
  EXPECT_TRUE(Expired(o, AfterMiss(o, cyclist, kHidden, k * kScan)));

  const Track tentative = BornTrack(o, Seen(1, ObjectClass::kPedestrian), 0);
  EXPECT_EQ(AfterMiss(o, tentative, kHidden, kScan).misses, 1);
}

TEST(TrackManagement, AnUnknownTrackLearnsItsClass) {
  const TrackManagementOptions o;
  Track t = BornTrack(o, Seen(1, ObjectClass::kUnknown), 0);
  t = AfterDetection(o, t, Seen(1, ObjectClass::kCyclist), 0);
  EXPECT_EQ(t.object_class, ObjectClass::kCyclist);
  t = AfterDetection(o, t, Seen(1, ObjectClass::kUnknown), 0);
  EXPECT_EQ(t.object_class, ObjectClass::kCyclist) << "kept once known";
}

Detection WithCamera(CameraEvidence e, int sensors = 1) {
  Detection d = Seen(sensors);
  d.camera = e;
  return d;
}

// The camera's evidence moves the existence log odds by its likelihood ratios; no evidence
// leaves them; the odds are clamped.
TEST(TrackManagement, TheCamerasEvidenceMovesTheExistenceOdds) {
  const TrackManagementOptions o;
  const double seen = std::log(0.9 / 0.05), unseen = std::log(0.1 / 0.95);
  EXPECT_DOUBLE_EQ(ExistenceAfter(o, 0.0, CameraEvidence::kSeen), seen);
  EXPECT_DOUBLE_EQ(ExistenceAfter(o, 0.0, CameraEvidence::kUnseen), unseen);
  EXPECT_DOUBLE_EQ(ExistenceAfter(o, 1.5, CameraEvidence::kNone), 1.5);
  EXPECT_DOUBLE_EQ(ExistenceAfter(o, 4.0, CameraEvidence::kSeen), o.existence_log_odds_limit);
  EXPECT_DOUBLE_EQ(ExistenceAfter(o, -4.0, CameraEvidence::kUnseen), -o.existence_log_odds_limit);
  EXPECT_DOUBLE_EQ(BornTrack(o, WithCamera(CameraEvidence::kUnseen), 0).existence_log_odds, unseen);
}

// A lidar-only object that the camera, looking at it, never reports ends on its second such
// detection (existence 0.01, below 0.05), before three updates could confirm it; a road user the
// camera sees survives an occasional miss of the camera's, and one outside the camera's view is
// not judged.
TEST(TrackManagement, TheCamerasSilenceEndsAGhost) {
  const TrackManagementOptions o;
  Track ghost = BornTrack(o, WithCamera(CameraEvidence::kUnseen), 0);
  EXPECT_FALSE(Expired(o, ghost));
  ghost = AfterDetection(o, ghost, WithCamera(CameraEvidence::kUnseen), kScan);
  EXPECT_TRUE(Expired(o, ghost));
  EXPECT_EQ(ghost.status, TrackStatus::kTentative);

  Track walker = BornTrack(o, WithCamera(CameraEvidence::kSeen, 2), 0);
  for (int k = 0; k < 20; ++k) {
    const bool camera_missed = k % 5 == 4;  // one frame in five
    walker =
        AfterDetection(o, walker,
                       WithCamera(camera_missed ? CameraEvidence::kUnseen : CameraEvidence::kSeen,
                                  camera_missed ? 1 : 2),
                       (k + 1) * kScan);
    EXPECT_FALSE(Expired(o, walker)) << k;
  }
  EXPECT_GT(walker.existence_log_odds, 0.0);

  Track beside = BornTrack(o, WithCamera(CameraEvidence::kNone), 0);
  for (int k = 0; k < 10; ++k) {
    beside = AfterDetection(o, beside, WithCamera(CameraEvidence::kNone), (k + 1) * kScan);
  }
  EXPECT_FALSE(Expired(o, beside));
  EXPECT_EQ(beside.existence_log_odds, 0.0);
  EXPECT_EQ(beside.status, TrackStatus::kConfirmed);
}

TEST(TrackManagement, ValidateNamesTheField) {
  TrackManagementOptions o;
  o.max_misses_cyclist = -1;
  try {
    o.Validate("test");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("max_misses_cyclist"), std::string::npos) << e.what();
  }
  o = TrackManagementOptions{};
  o.camera_detection_probability = 1.0;  // a camera that never misses makes one miss fatal
  EXPECT_THROW(o.Validate(), InputError);
  o = TrackManagementOptions{};
  o.min_existence_probability = 0.5;
  EXPECT_THROW(o.Validate(), InputError);
}

}  // namespace
}  // namespace lookout::tracking
