#include "lookout/sim/world_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

World FourWay() {
  World w;
  w.preset = "four_way";
  return w;
}

Shape Rect(double x0, double y0, double x1, double y1) {
  return Shape::Polygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, kStaticOwner);
}

TEST(WorldBuilderTest, EmptyWorldHasNoShapes) { EXPECT_TRUE(BuildStaticWorld(World{}).empty()); }

TEST(WorldBuilderTest, FourWayHasFourBlocksPolesAndSigns) {
  const std::vector<Shape> shapes = BuildStaticWorld(FourWay());
  int polygons = 0, poles = 0, signs = 0;
  bool some_edge_not_axis_aligned = false;
  int quadrant_mask = 0;
  for (const Shape& s : shapes) {
    EXPECT_EQ(s.owner, kStaticOwner);
    if (s.kind == Shape::Kind::kCircle) {
      (s.radius == 0.15 ? poles : signs) += 1;
      EXPECT_TRUE(s.radius == 0.15 || s.radius == 0.1);
      continue;
    }
    ++polygons;
    Vector2d mean = Vector2d::Zero();
    for (std::size_t i = 0; i < s.vertices.size(); ++i) {
      mean += s.vertices[i];
      const Vector2d e = s.vertices[(i + 1) % s.vertices.size()] - s.vertices[i];
      some_edge_not_axis_aligned = some_edge_not_axis_aligned || (e.x() != 0.0 && e.y() != 0.0);
    }
    mean /= static_cast<double>(s.vertices.size());
    quadrant_mask |= 1 << ((mean.x() > 0 ? 1 : 0) + (mean.y() > 0 ? 2 : 0));
  }
  EXPECT_EQ(polygons, 4);
  EXPECT_EQ(quadrant_mask, 0b1111);  // one block per corner
  EXPECT_TRUE(some_edge_not_axis_aligned);
  EXPECT_GE(poles, 4);
  EXPECT_GE(signs, 4);
}

TEST(WorldBuilderTest, FourWayKeepsTheRoadsClear) {
  const std::vector<Shape> shapes = BuildStaticWorld(FourWay());
  const double r = kFourWayRoadHalfWidthM;
  const double far = 80.0;
  // Exact: no shape meets either carriageway, kerbs included (shapes are closed).
  const Shape east_west = Rect(-far, -r, far, r);
  const Shape north_south = Rect(-r, -far, r, far);
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    EXPECT_FALSE(Overlap(shapes[i], east_west)) << "shape " << i;
    EXPECT_FALSE(Overlap(shapes[i], north_south)) << "shape " << i;
  }
  // And by sampling, which does not rely on Overlap.
  int samples = 0;
  for (double a = -far; a <= far; a += 0.25) {
    for (double b = -r; b <= r; b += 0.25) {
      for (const Vector2d& p : {Vector2d(a, b), Vector2d(b, a)}) {
        ++samples;
        for (const Shape& s : shapes) ASSERT_FALSE(Contains(s, p)) << p.transpose();
      }
    }
  }
  EXPECT_GT(samples, 10000);
}

TEST(WorldBuilderTest, FourWaySidewalksHoldOnlyStreetFurniture) {
  const std::vector<Shape> shapes = BuildStaticWorld(FourWay());
  // Just inside the building line: the blocks start exactly at it.
  const double w = kFourWayRoadHalfWidthM + kFourWaySidewalkWidthM - 1e-6;
  const Shape band_ew = Rect(-80, -w, 80, w);
  const Shape band_ns = Rect(-w, -80, w, 80);
  for (const Shape& s : shapes) {
    if (s.kind == Shape::Kind::kPolygon) {
      EXPECT_FALSE(Overlap(s, band_ew));
      EXPECT_FALSE(Overlap(s, band_ns));
    } else {
      EXPECT_TRUE(Overlap(s, band_ew) || Overlap(s, band_ns)) << s.center.transpose();
    }
  }
  // The blocks do reach the building line, and 60 m out.
  EXPECT_TRUE(Contains(shapes[0], {6.0, 6.0}));
  EXPECT_TRUE(Contains(shapes[0], {59.0, 59.0}));
  EXPECT_FALSE(Contains(shapes[0], {61.0, 30.0}));
}

TEST(WorldBuilderTest, ObstaclesAreAppendedWithTheirGeometry) {
  World w = FourWay();
  Obstacle building;
  building.kind = ObstacleKind::kBuilding;
  building.polygon = {{-40, 10}, {-10, 10}, {-10, 40}, {-40, 40}};
  Obstacle pole;
  pole.kind = ObstacleKind::kPole;
  pole.center_m = {8, -6};
  pole.radius_m = 0.15;
  Obstacle car;
  car.kind = ObstacleKind::kParkedCar;
  car.center_m = {5, -4.5};
  car.heading_rad = kPi / 2;
  car.length_m = 4.5;
  car.width_m = 1.8;
  Obstacle sign;
  sign.kind = ObstacleKind::kSign;
  sign.center_m = {12, -5};
  sign.radius_m = 0.1;
  w.obstacles = {building, pole, car, sign};

  const std::size_t preset_count = BuildStaticWorld(FourWay()).size();
  const std::vector<Shape> shapes = BuildStaticWorld(w);
  ASSERT_EQ(shapes.size(), preset_count + 4);
  const Shape& b = shapes[preset_count];
  EXPECT_EQ(b.kind, Shape::Kind::kPolygon);
  EXPECT_EQ(b.vertices, building.polygon);
  EXPECT_EQ(b.owner, kStaticOwner);

  const Shape& p = shapes[preset_count + 1];
  EXPECT_EQ(p.kind, Shape::Kind::kCircle);
  EXPECT_EQ(p.center, Vector2d(8, -6));
  EXPECT_EQ(p.radius, 0.15);

  // Heading north: 4.5 m along y, 1.8 m along x.
  const Shape& c = shapes[preset_count + 2];
  ASSERT_EQ(c.kind, Shape::Kind::kPolygon);
  const Aabb box = BoundingBox(c);
  EXPECT_NEAR(box.min.x(), 4.1, 1e-12);
  EXPECT_NEAR(box.max.x(), 5.9, 1e-12);
  EXPECT_NEAR(box.min.y(), -6.75, 1e-12);
  EXPECT_NEAR(box.max.y(), -2.25, 1e-12);
  EXPECT_EQ(c.owner, kStaticOwner);

  const Shape& s = shapes[preset_count + 3];
  EXPECT_EQ(s.kind, Shape::Kind::kCircle);
  EXPECT_EQ(s.center, Vector2d(12, -5));
  EXPECT_EQ(s.radius, 0.1);

  // Without a preset the obstacles are all there is.
  w.preset.reset();
  EXPECT_EQ(BuildStaticWorld(w).size(), 4u);
}

TEST(WorldBuilderTest, BuildingOutlinesAreThePresetsBlocksAndTheFilesBuildings) {
  World w = FourWay();
  const std::vector<Shape> shapes = BuildStaticWorld(w);
  const std::vector<std::vector<Vector2d>> blocks = BuildingOutlines(w);
  ASSERT_EQ(blocks.size(), 4u);
  for (std::size_t i = 0; i < blocks.size(); ++i) EXPECT_EQ(blocks[i], shapes[i].vertices);
  Obstacle building;
  building.kind = ObstacleKind::kBuilding;
  building.polygon = {{-40, 10}, {-10, 10}, {-10, 40}, {-40, 40}};
  Obstacle car;  // a parked car is no building: it leaves, and is no part of a map
  car.kind = ObstacleKind::kParkedCar;
  car.length_m = 4.5;
  car.width_m = 1.8;
  w.obstacles = {car, building};
  const std::vector<std::vector<Vector2d>> all = BuildingOutlines(w);
  ASSERT_EQ(all.size(), 5u);
  EXPECT_EQ(all[4], building.polygon);
  EXPECT_TRUE(BuildingOutlines(World{}).empty());
}

TEST(WorldBuilderTest, UnknownPresetIsAProgrammingError) {
  World w;
  w.preset = "roundabout";
  EXPECT_THROW(BuildStaticWorld(w), std::invalid_argument);
  EXPECT_THROW(BuildingOutlines(w), std::invalid_argument);
}

}  // namespace
}  // namespace lookout::sim
