#include "lookout/tracking/track_management.h"

#include <gtest/gtest.h>

#include "lookout/core/input_error.h"

namespace lookout::tracking {
namespace {

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
  t = AfterDetection(o, t, Seen(1));
  EXPECT_EQ(t.status, TrackStatus::kTentative);
  t = AfterDetection(o, t, Seen(1));
  EXPECT_EQ(t.status, TrackStatus::kConfirmed);
  EXPECT_EQ(t.updates, 3);
  // A second-sensor sighting confirms a tentative track at once.
  Track u = AfterDetection(o, BornTrack(o, Seen(1), 0), Seen(2));
  EXPECT_EQ(u.status, TrackStatus::kConfirmed);
}

TEST(TrackManagement, MissesCoastThenExpireByClass) {
  TrackManagementOptions o;
  o.max_misses_pedestrian = 4;
  o.max_misses_tentative = 1;
  Track walker = BornTrack(o, Seen(2, ObjectClass::kPedestrian), 0);
  for (int miss = 1; miss <= 4; ++miss) {
    walker = AfterMiss(walker);
    EXPECT_TRUE(walker.coasting);
    EXPECT_EQ(walker.misses, miss);
    EXPECT_FALSE(Expired(o, walker)) << miss;
  }
  EXPECT_TRUE(Expired(o, AfterMiss(walker)));
  walker = AfterDetection(o, walker, Seen(1));
  EXPECT_EQ(walker.misses, 0);
  EXPECT_FALSE(walker.coasting);

  Track tentative = BornTrack(o, Seen(1, ObjectClass::kCar), 0);
  EXPECT_FALSE(Expired(o, AfterMiss(tentative)));
  EXPECT_TRUE(Expired(o, AfterMiss(AfterMiss(tentative))));
}

TEST(TrackManagement, AnUnknownTrackLearnsItsClass) {
  const TrackManagementOptions o;
  Track t = BornTrack(o, Seen(1, ObjectClass::kUnknown), 0);
  t = AfterDetection(o, t, Seen(1, ObjectClass::kCyclist));
  EXPECT_EQ(t.object_class, ObjectClass::kCyclist);
  t = AfterDetection(o, t, Seen(1, ObjectClass::kUnknown));
  EXPECT_EQ(t.object_class, ObjectClass::kCyclist) << "kept once known";
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
}

}  // namespace
}  // namespace lookout::tracking
