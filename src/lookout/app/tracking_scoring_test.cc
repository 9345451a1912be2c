#include "lookout/app/tracking_scoring.h"

#include <gtest/gtest.h>

#include <vector>

namespace lookout::app {
namespace {

sim::ActorTruth ActorAt(int index, double x, double y) {
  sim::ActorTruth a;
  a.index = index;
  a.state.pose = Pose2(x, y, 0.0);
  return a;
}

std::vector<std::int64_t> Ids(const std::vector<eval::PointObject>& objects) {
  std::vector<std::int64_t> ids;
  for (const eval::PointObject& o : objects) ids.push_back(o.id);
  return ids;
}

// A track on an actor that does not count (the nearest, within the match distance, or one
// whose footprint holds it) is neither a match nor a false track; a track on none, or nearer a
// counted actor, stays to be scored.
TEST(TrackingScorerTest, TracksOnUncountedActorsAreLeftOut) {
  sim::TruthFrame truth;
  truth.actors = {ActorAt(0, 0.0, 0.0), ActorAt(1, 10.0, 0.0)};
  const std::vector<bool> countable = {true, false};
  const std::vector<eval::PointObject> tracks = {
      {1, {0.5, 0.0}},   // on the counted actor
      {2, {11.0, 0.5}},  // on the uncounted one: left out
      {3, {20.0, 0.0}},  // on nothing: a false track
      {4, {7.5, 0.0}},   // nearest the uncounted actor but beyond the match distance
      {5, {8.1, 0.0}},   // within it: left out
  };
  EXPECT_EQ(Ids(WithoutTracksOnUncountedActors(tracks, truth, countable, 2.0)),
            (std::vector<std::int64_t>{1, 3, 4}));
  // With every actor counted, nothing is left out.
  EXPECT_EQ(WithoutTracksOnUncountedActors(tracks, truth, {true, true}, 2.0).size(), 5u);

  // A truck that does not count, tracked on its front 2.9 m from its centre: inside its
  // footprint, left out; the same point beside a car's footprint stays.
  sim::TruthFrame trucks;
  trucks.actors = {ActorAt(0, 30.0, 0.0)};
  trucks.actors[0].footprint = sim::Shape::Box(trucks.actors[0].state.pose, 8.0, 2.5, 0);
  const std::vector<eval::PointObject> on_front = {{1, {27.1, 0.2}}};
  EXPECT_TRUE(WithoutTracksOnUncountedActors(on_front, trucks, {false}, 2.0).empty());
  EXPECT_EQ(WithoutTracksOnUncountedActors(on_front, trucks, {true}, 2.0).size(), 1u);
  trucks.actors[0].footprint = sim::Shape::Box(trucks.actors[0].state.pose, 4.5, 1.8, 0);
  EXPECT_EQ(WithoutTracksOnUncountedActors(on_front, trucks, {false}, 2.0).size(), 1u);
}

// Frames from the first contact on are not scored: the contact time of any actor present, at
// or before the frame's stamp.
TEST(TrackingScorerTest, FramesFromTheFirstContactOnAreNotScored) {
  sim::TruthFrame truth;
  truth.stamp = FromSeconds(7.4);
  truth.actors = {ActorAt(0, 0.0, 0.0), ActorAt(1, 10.0, 0.0)};
  EXPECT_FALSE(AfterContact(truth));
  truth.actors[1].contact_time_s = 7.42;
  EXPECT_FALSE(AfterContact(truth));
  truth.stamp = FromSeconds(7.42);
  EXPECT_TRUE(AfterContact(truth));
  truth.stamp = FromSeconds(9.0);
  EXPECT_TRUE(AfterContact(truth));
}

}  // namespace
}  // namespace lookout::app
