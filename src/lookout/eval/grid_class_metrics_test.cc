#include "lookout/eval/grid_class_metrics.h"

#include <gtest/gtest.h>

namespace lookout::eval {
namespace {

// The identity-like table of the test: static 0, pedestrian 1, cyclist 2, vehicle 3, unknown 4.
GridClassOfObjectClass Table() {
  GridClassOfObjectClass t{};
  t[static_cast<std::size_t>(ObjectClass::kUnknown)] = 4;
  t[static_cast<std::size_t>(ObjectClass::kPedestrian)] = 1;
  t[static_cast<std::size_t>(ObjectClass::kCyclist)] = 2;
  t[static_cast<std::size_t>(ObjectClass::kCar)] = 3;
  t[static_cast<std::size_t>(ObjectClass::kTruck)] = 3;
  t[static_cast<std::size_t>(ObjectClass::kPole)] = 0;
  return t;
}

TEST(ClassAccuracyTest, CountsTrueActorCellsBelievedOccupied) {
  // Six cells: a pedestrian's (actor 0) three, a truck's (actor 3) two, one static.
  sim::TruthRaster raster;
  raster.owner = {0, 0, 0, 3, 3, -1};
  std::vector<sim::ActorTruth> actors(2);
  actors[0].index = 0;
  actors[0].object_class = ObjectClass::kPedestrian;
  actors[1].index = 3;
  actors[1].object_class = ObjectClass::kTruck;
  const std::vector<float> occupancy = {0.9f, 0.9f, 0.4f, 0.7f, 0.8f, 0.9f};
  const std::vector<std::uint8_t> best = {1, 3, 1, 3, 1, 0};
  ClassAccuracyAccumulator accuracy(Table());
  EXPECT_FALSE(accuracy.Value());
  accuracy.AddFrame(occupancy, best, raster, actors);
  // Scored: cells 0, 1 (pedestrian; the third is not believed occupied), 3, 4 (truck ->
  // vehicle); the static cell is not an actor's. Right: cells 0 and 3.
  EXPECT_EQ(accuracy.cells(), 4);
  ASSERT_TRUE(accuracy.Value());
  EXPECT_DOUBLE_EQ(*accuracy.Value(), 0.5);
}

}  // namespace
}  // namespace lookout::eval
