#include "lookout/sim/footprint.h"

#include <gtest/gtest.h>

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

TEST(FootprintTest, ActorsGetTheirClassShapeAndDefaults) {
  ActorSpec walker;
  walker.object_class = ObjectClass::kPedestrian;
  walker.radius_m = 0.35;
  const Footprint w = Footprint::ForActor(walker);
  EXPECT_EQ(w.kind, Footprint::Kind::kCircle);
  EXPECT_EQ(w.radius_m, 0.35);

  ActorSpec car;
  car.object_class = ObjectClass::kCar;  // no size given
  const Footprint c = Footprint::ForActor(car);
  EXPECT_EQ(c.kind, Footprint::Kind::kBox);
  EXPECT_EQ(c.length_m, DefaultLength(ObjectClass::kCar));
  EXPECT_EQ(c.width_m, DefaultWidth(ObjectClass::kCar));

  ActorSpec truck;
  truck.object_class = ObjectClass::kTruck;
  truck.length_m = 10.0;
  truck.width_m = 2.6;
  const Footprint t = Footprint::ForActor(truck);
  EXPECT_EQ(t.length_m, 10.0);
  EXPECT_EQ(t.width_m, 2.6);

  EgoSpec ego;
  const Footprint e = Footprint::ForEgo(ego);
  EXPECT_EQ(e.length_m, 4.6);
  EXPECT_EQ(e.width_m, 1.9);
}

TEST(FootprintTest, ShapesArePlacedAtThePose) {
  const Shape box = FootprintAt(Footprint::Box(4.0, 2.0), Pose2(1.0, 2.0, kPi / 2), 3);
  EXPECT_EQ(box.owner, 3);
  EXPECT_TRUE(Contains(box, {1.9, 3.9}));
  EXPECT_FALSE(Contains(box, {2.1, 2.0}));
  const Shape circle = FootprintAt(Footprint::Circle(0.3), Pose2(1.0, 2.0, 1.0), 4);
  EXPECT_EQ(circle.kind, Shape::Kind::kCircle);
  EXPECT_EQ(circle.center, Vector2d(1.0, 2.0));
  EXPECT_EQ(circle.radius, 0.3);
  EXPECT_EQ(circle.owner, 4);
}

}  // namespace
}  // namespace lookout::sim
