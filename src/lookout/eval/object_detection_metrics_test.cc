#include "lookout/eval/object_detection_metrics.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace lookout::eval {
namespace {

using Eigen::Vector2d;

// A 4 x 2 m car centred on (x, y), heading along +x at `speed`.
sim::ActorTruth Car(int index, double x, double y, double speed) {
  sim::ActorTruth a;
  a.index = index;
  a.state.pose = Pose2(x, y, 0.0);
  a.state.speed_mps = speed;
  a.footprint = sim::Shape::Box(a.state.pose, 4.0, 2.0, index);
  return a;
}

TEST(ObjectDetectionMetricsTest, GateIsOnTheDistanceToTheFootprint) {
  const std::vector<sim::ActorTruth> actors = {Car(0, 0.0, 0.0, 5.0)};
  // The car's front edge is at x = 2: 0.9 m beyond it matches, 1.1 m does not.
  EXPECT_EQ(MatchObjectsToMovingActors({{2.9, 0.0}}, actors, {}).matched_objects, 1);
  EXPECT_EQ(MatchObjectsToMovingActors({{3.1, 0.0}}, actors, {}).matched_objects, 0);
  // Inside the footprint (far from its centre) is distance 0.
  const DetectionCounts inside = MatchObjectsToMovingActors({{-1.8, 0.9}}, actors, {});
  EXPECT_EQ(inside.objects, 1);
  EXPECT_EQ(inside.matched_objects, 1);
  EXPECT_EQ(inside.actors, 1);
  EXPECT_EQ(inside.matched_actors, 1);
}

TEST(ObjectDetectionMetricsTest, OneToOneNearestFirst) {
  // Two cars 5 m apart and three objects: one on each car, and a second one on car 0 (a split
  // cluster), which is a false object.
  const std::vector<sim::ActorTruth> actors = {Car(0, 0.0, 0.0, 5.0), Car(1, 0.0, 5.0, 5.0)};
  const DetectionCounts c =
      MatchObjectsToMovingActors({{0.0, 1.5}, {0.0, 0.0}, {0.0, 5.0}}, actors, {});
  EXPECT_EQ(c.objects, 3);
  EXPECT_EQ(c.matched_objects, 2);
  EXPECT_EQ(c.actors, 2);
  EXPECT_EQ(c.matched_actors, 2);
  // Cars 3.5 m apart (a 1.5 m gap): object (0, 1.8) is 0.8 m from car 0 and 0.7 m from car 1,
  // object (0, 1.3) 0.3 m from car 0 only. Nearest first: (0, 1.3) takes car 0, (0, 1.8) car 1.
  const std::vector<sim::ActorTruth> close = {Car(0, 0.0, 0.0, 5.0), Car(1, 0.0, 3.5, 5.0)};
  const DetectionCounts d = MatchObjectsToMovingActors({{0.0, 1.8}, {0.0, 1.3}}, close, {});
  EXPECT_EQ(d.matched_objects, 2);
  EXPECT_EQ(d.matched_actors, 2);
  // Alone, (0, 1.8) takes the nearer car 1: with car 1 not counted, no counted actor is matched.
  const DetectionCounts e = MatchObjectsToMovingActors({{0.0, 1.8}}, close, {true, false});
  EXPECT_EQ(e.matched_objects, 1);
  EXPECT_EQ(e.actors, 1);
  EXPECT_EQ(e.matched_actors, 0);
}

TEST(ObjectDetectionMetricsTest, StandingActorsAreNeitherMatchedNorCounted) {
  const std::vector<sim::ActorTruth> actors = {Car(0, 0.0, 0.0, 0.4), Car(1, 10.0, 0.0, 0.6)};
  const DetectionCounts c = MatchObjectsToMovingActors({{0.0, 0.0}}, actors, {});
  EXPECT_EQ(c.objects, 1);
  EXPECT_EQ(c.matched_objects, 0);  // a dynamic object on a parked car is a false one
  EXPECT_EQ(c.actors, 1);           // only the car at 0.6 m/s is moving
  EXPECT_EQ(c.matched_actors, 0);
}

TEST(ObjectDetectionMetricsTest, UncountableActorsStillAbsolveTheirObjects) {
  const std::vector<sim::ActorTruth> actors = {Car(0, 0.0, 0.0, 5.0), Car(1, 0.0, 10.0, 5.0)};
  // Actor 1 is out of sight: not counted for recall, but an object on it is no false object.
  const DetectionCounts c = MatchObjectsToMovingActors({{0.0, 10.0}}, actors, {true, false});
  EXPECT_EQ(c.matched_objects, 1);
  EXPECT_EQ(c.actors, 1);
  EXPECT_EQ(c.matched_actors, 0);
  EXPECT_THROW(MatchObjectsToMovingActors({}, actors, {true}), std::invalid_argument);
}

TEST(ObjectDetectionMetricsTest, AccumulatorPoolsFrames) {
  DetectionAccumulator acc;
  EXPECT_FALSE(acc.Precision());
  EXPECT_FALSE(acc.Recall());
  acc.AddFrame({4, 3, 2, 2});
  acc.AddFrame({0, 0, 2, 0});
  EXPECT_DOUBLE_EQ(*acc.Precision(), 0.75);
  EXPECT_DOUBLE_EQ(*acc.Recall(), 0.5);
}

}  // namespace
}  // namespace lookout::eval
