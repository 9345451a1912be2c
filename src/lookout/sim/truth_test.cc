#include "lookout/sim/truth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "lookout/core/random.h"

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

ActorTruth BoxActor(int index, const Pose2& pose, double length, double width, double speed,
                    double yaw_rate) {
  ActorTruth a;
  a.index = index;
  a.id = "actor" + std::to_string(index);
  a.state.pose = pose;
  a.state.speed_mps = speed;
  a.state.yaw_rate_radps = yaw_rate;
  a.footprint = Shape::Box(pose, length, width, index);
  return a;
}

int CountOccupied(const TruthRaster& r) {
  int n = 0;
  for (const std::uint8_t o : r.occupied) n += o;
  return n;
}

// The slow literal reference: every cell against every shape, in painting order.
std::vector<int> ReferenceOwners(const TruthFrame& frame, const std::vector<Shape>& world,
                                 const GridGeometry& g) {
  std::vector<int> owner(static_cast<std::size_t>(g.CellCount()), kFreeCell);
  for (int i = 0; i < g.CellCount(); ++i) {
    const Vector2d c = g.CellCenter(g.FromLinear(i));
    for (const Shape& s : world) {
      if (Contains(s, c)) owner[static_cast<std::size_t>(i)] = kStaticOwner;
    }
    for (const ActorTruth& a : frame.actors) {
      if (Contains(a.footprint, c)) owner[static_cast<std::size_t>(i)] = a.index;
    }
  }
  return owner;
}

TEST(TruthTest, MovingBoxCoversItsAreaWithRigidBodyVelocity) {
  const GridGeometry g{Vector2d(0.0, 0.0), 0.1, 300, 200};
  TruthFrame frame;
  const Pose2 pose(10.33, 5.21, 0.4);
  frame.actors.push_back(BoxActor(2, pose, 4.5, 1.8, 8.0, 0.3));
  const TruthRaster r = RasteriseTruth(frame, {}, g);

  ASSERT_EQ(r.occupied.size(), 60000u);
  ASSERT_EQ(r.velocity.size(), 60000u);
  ASSERT_EQ(r.owner.size(), 60000u);
  const double expected_cells = 4.5 * 1.8 / (0.1 * 0.1);
  EXPECT_NEAR(CountOccupied(r), expected_cells, 0.03 * expected_cells);

  const Vector2d v = 8.0 * Vector2d(std::cos(0.4), std::sin(0.4));
  for (int i = 0; i < g.CellCount(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Vector2d c = g.CellCenter(g.FromLinear(i));
    if (!r.occupied[k]) {
      EXPECT_EQ(r.owner[k], kFreeCell);
      EXPECT_EQ(r.velocity[k], Eigen::Vector2f::Zero());
      continue;
    }
    EXPECT_EQ(r.owner[k], 2);
    // v + w x (c - p), w x r = w (-r_y, r_x): 0.3 rad/s at up to 2.4 m from the centre.
    const Vector2d arm = c - pose.translation;
    const Vector2d expected = v + 0.3 * Vector2d(-arm.y(), arm.x());
    EXPECT_NEAR(r.velocity[k].x(), expected.x(), 1e-5);
    EXPECT_NEAR(r.velocity[k].y(), expected.y(), 1e-5);
  }
}

TEST(TruthTest, StaticShapesAreStillAndActorsPaintOverThem) {
  const GridGeometry g{Vector2d(-5.0, -5.0), 0.2, 50, 50};
  const std::vector<Shape> world = {
      Shape::Polygon({{-4, -4}, {0, -4}, {0, 0}, {-4, 0}}, kStaticOwner),
      Shape::Circle({3.0, 3.0}, 0.5, kStaticOwner)};
  TruthFrame frame;
  ActorTruth walker;
  walker.index = 0;
  walker.object_class = ObjectClass::kPedestrian;
  walker.state.pose = Pose2(0.0, -2.0, kPi / 2);
  walker.state.speed_mps = 1.4;
  walker.footprint = Shape::Circle({0.0, -2.0}, 0.6, 0);
  frame.actors.push_back(walker);
  const TruthRaster r = RasteriseTruth(frame, world, g);

  int statics = 0;
  for (std::size_t k = 0; k < r.owner.size(); ++k) {
    if (r.owner[k] == kStaticOwner) {
      ++statics;
      EXPECT_EQ(r.occupied[k], 1);
      EXPECT_EQ(r.velocity[k], Eigen::Vector2f::Zero());
    }
  }
  EXPECT_GT(statics, 350);  // 16 m^2 / 0.04 m^2 = 400 cells, less what the walker covers
  // A cell under both the building and the walker (centre (-0.1, -2.1)) is the walker's.
  const auto centre = static_cast<std::size_t>(g.LinearIndex(*g.CellAt({-0.05, -2.05})));
  EXPECT_EQ(r.owner[centre], 0);
  EXPECT_NEAR(r.velocity[centre].y(), 1.4, 1e-6);
  EXPECT_EQ(r.owner, ReferenceOwners(frame, world, g));
}

TEST(TruthTest, ShapesOutsideTheGridSetNothing) {
  const GridGeometry g{Vector2d(100.0, 100.0), 0.15, 40, 40};
  TruthFrame frame;
  frame.actors.push_back(BoxActor(0, Pose2(0.0, 0.0, 0.0), 4.5, 1.8, 10.0, 0.0));
  const std::vector<Shape> world = {
      Shape::Polygon({{-1e12, -1e12}, {-1e11, -1e12}, {-1e11, -1e11}}, kStaticOwner),
      Shape::Circle({1e15, 1e15}, 3.0, kStaticOwner)};
  const TruthRaster r = RasteriseTruth(frame, world, g);
  EXPECT_EQ(CountOccupied(r), 0);
  for (const int o : r.owner) ASSERT_EQ(o, kFreeCell);

  // An empty grid is fine too.
  const TruthRaster empty = RasteriseTruth(frame, world, GridGeometry{});
  EXPECT_TRUE(empty.occupied.empty());
}

TEST(TruthTest, ShapePartlyOutsideIsClipped) {
  const GridGeometry g{Vector2d(0.0, 0.0), 0.25, 20, 20};
  TruthFrame frame;
  frame.actors.push_back(BoxActor(0, Pose2(0.0, 2.5, 0.0), 4.0, 2.0, 0.0, 0.0));
  const TruthRaster r = RasteriseTruth(frame, {}, g);
  // x in [0, 2] (the half inside), y in [1.5, 3.5]: 8 x 8 cells.
  EXPECT_EQ(CountOccupied(r), 64);
  EXPECT_EQ(r.owner, ReferenceOwners(frame, {}, g));
}

TEST(TruthTest, RandomScenesMatchTheSlowReference) {
  const std::uint64_t seed = 77;
  SCOPED_TRACE("seed " + std::to_string(seed));
  Rng rng(seed);
  for (int scene = 0; scene < 20; ++scene) {
    const GridGeometry g{Vector2d{rng.Uniform(-12, -8), rng.Uniform(-12, -8)},
                         rng.Uniform(0.1, 0.4), 80, 70};
    std::vector<Shape> world;
    for (int i = 0; i < 4; ++i) {
      const Vector2d centre{rng.Uniform(-15, 15), rng.Uniform(-15, 15)};
      world.push_back(Shape::Circle(centre, rng.Uniform(0.1, 2.0), kStaticOwner));
      const Pose2 pose{rng.Uniform(-15, 15), rng.Uniform(-15, 15), rng.Uniform(-kPi, kPi)};
      const double length = rng.Uniform(1, 8);
      world.push_back(Shape::Box(pose, length, rng.Uniform(1, 8), kStaticOwner));
    }
    TruthFrame frame;
    for (int i = 0; i < 5; ++i) {
      const Pose2 pose{rng.Uniform(-12, 12), rng.Uniform(-12, 12), rng.Uniform(-kPi, kPi)};
      const double length = rng.Uniform(0.5, 6), width = rng.Uniform(0.5, 2.5);
      const double speed = rng.Uniform(0, 15);
      frame.actors.push_back(BoxActor(i, pose, length, width, speed, rng.Uniform(-1, 1)));
    }
    const TruthRaster r = RasteriseTruth(frame, world, g);
    ASSERT_EQ(r.owner, ReferenceOwners(frame, world, g)) << "scene " << scene;
  }
}

}  // namespace
}  // namespace lookout::sim
