#include "lookout/app/people_scoring.h"

#include <gtest/gtest.h>

#include <map>
#include <string>

namespace lookout::app {
namespace {

LidarObject ObjectAt(double x, double y, bool dynamic) {
  LidarObject o;
  o.centroid_m = Eigen::Vector2d(x, y);
  o.point_m = Eigen::Vector2d(x + 5.0, y);  // the front point is not what is compared
  o.dynamic = dynamic;
  return o;
}

TEST(PeopleScorerTest, SharesOfAnnotatedPositionsWithAnObjectWithinTheDistance) {
  // The laser 1 m ahead of the vehicle, turned left by 90 deg: bearing 0 in the laser frame is
  // the vehicle's +y.
  const Pose2 mount(1.0, 0.0, kPi / 2);
  io::PeopleFrame people;
  people.people = {{1, {1.0, 3.0}},    // bearing 0: in the sector; a dynamic object 0.4 m away
                   {2, {4.0, 1.0}},    // bearing -71.6 deg: in; a static object 0.3 m away
                   {3, {-3.0, 0.5}},   // bearing 82.9 deg: outside; nothing within 0.5 m
                   {4, {1.0, -2.0}}};  // bearing 180 deg: outside; dynamic 0.5 m away exactly
  LidarObjectFrame objects;
  objects.objects = {ObjectAt(1.4, 3.0, true), ObjectAt(4.3, 1.0, false),
                     ObjectAt(-3.0, 1.2, true), ObjectAt(1.0, -2.5, true)};
  PeopleScorer scorer("people.test");
  scorer.Observe(people, mount, &objects);
  // A frame the pipeline had no objects for: its person is missed.
  io::PeopleFrame missed;
  missed.people = {{5, {1.0, 2.0}}};  // bearing 0, in the sector
  scorer.Observe(missed, mount, nullptr);

  std::map<std::string, double> m;
  scorer.Report(m);
  EXPECT_EQ(m.at("people.test.positions"), 5.0);
  EXPECT_DOUBLE_EQ(m.at("people.test.dynamic_share"), 2.0 / 5.0);  // persons 1 and 4
  EXPECT_DOUBLE_EQ(m.at("people.test.any_share"), 3.0 / 5.0);      // 1, 2 and 4
  EXPECT_EQ(m.at("people.test.sector_positions"), 3.0);            // 1, 2 and 5
  EXPECT_DOUBLE_EQ(m.at("people.test.sector_dynamic_share"), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(m.at("people.test.sector_any_share"), 2.0 / 3.0);
}

TEST(PeopleScorerTest, NothingAnnotatedNothingReported) {
  PeopleScorer scorer("people.test");
  LidarObjectFrame objects;
  objects.objects = {ObjectAt(1, 1, true)};
  scorer.Observe(io::PeopleFrame{}, Pose2(), &objects);
  std::map<std::string, double> m;
  scorer.Report(m);
  EXPECT_TRUE(m.empty());
}

tracking::Track TrackAt(std::uint32_t id, double x, double y) {
  tracking::Track t;
  t.id = id;
  t.state.mean = Eigen::Vector4d(x, y, 0.0, 0.0);
  return t;
}

// CLEAR MOT as the benchmark's clear_mot.py counts it: a match within 0.75 m, the sector only,
// a frame without annotations still a frame (its tracks are false).
TEST(PeopleTrackingScorerTest, ClearMotOverTheSectorWithTheBenchmarksThreshold) {
  const Pose2 mount;  // the laser at the vehicle's origin: bearings are the vehicle's
  const Pose2 ego(10.0, 5.0, kPi / 2);  // tracks are in the odometry frame
  const auto in_odom = [&](double x, double y) { return ego * Eigen::Vector2d(x, y); };
  PeopleTrackingScorer scorer("people.t");
  io::PeopleFrame frame;
  frame.people = {{1, {3.0, -1.0}}, {2, {-3.0, 0.0}}};  // person 2 behind: outside the sector
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d near = in_odom(3.0 + 0.1 * k, -1.0);   // 0-0.2 m off person 1
    const Eigen::Vector2d behind = in_odom(-3.0, 0.0);           // on person 2: not scored
    scorer.Observe(&frame, mount, ego, {TrackAt(7, near.x(), near.y()),
                                        TrackAt(8, behind.x(), behind.y())});
  }
  // A frame with no annotation and a track in the sector: a false positive.
  const Eigen::Vector2d ghost = in_odom(4.0, 0.0);
  scorer.Observe(nullptr, mount, ego, {TrackAt(9, ghost.x(), ghost.y())});
  // A track 0.8 m off the person: no match (0.75 m), a miss and a false positive.
  const Eigen::Vector2d far = in_odom(3.8, -1.0);
  scorer.Observe(&frame, mount, ego, {TrackAt(7, far.x(), far.y())});

  std::map<std::string, double> m;
  scorer.Report(m);
  EXPECT_EQ(m.at("people.t.frames"), 5.0);
  EXPECT_EQ(m.at("people.t.misses"), 1.0);
  EXPECT_EQ(m.at("people.t.false_positives"), 2.0);
  EXPECT_EQ(m.at("people.t.id_switches"), 0.0);
  EXPECT_NEAR(m.at("people.t.mota"), 1.0 - 3.0 / 4.0, 1e-12);
  EXPECT_NEAR(m.at("people.t.motp_m"), 0.1, 1e-9);  // (0 + 0.1 + 0.2) / 3
}

}  // namespace
}  // namespace lookout::app
