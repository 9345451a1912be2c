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

}  // namespace
}  // namespace lookout::app
