#include "lookout/sim/world_builder.h"

#include <stdexcept>
#include <string>

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

constexpr double kPoleRadiusM = 0.15;
constexpr double kSignRadiusM = 0.1;

// Distance of the back of the sidewalk (the building line) from the junction's axes.
constexpr double kBuildingLineM = kFourWayRoadHalfWidthM + kFourWaySidewalkWidthM;
// Street furniture stands this far from the kerb: out of the carriageway and of the mirrors
// of passing vehicles, and clear of pedestrians walking mid-sidewalk.
constexpr double kFurnitureLineM = kFourWayRoadHalfWidthM + 0.5;

// The four_way preset. The blocks are not all alike, so that the lidar sees more than one
// corner geometry: the NE and SW blocks are plain squares, the NW block has its corner cut
// by an irregular (not 45 degree) chamfer, which opens the view round it a little, and the SE
// block is an L with a forecourt recessed into its corner, a non-convex outline.
std::vector<std::vector<Vector2d>> FourWayBlocks() {
  const double b = kBuildingLineM;
  const double e = kFourWayBlockExtentM;
  // Every ring counter-clockwise; in order NE, NW, SW, SE.
  return {{{b, b}, {e, b}, {e, e}, {b, e}},
          {{-e, b}, {-(b + 4.0), b}, {-b, b + 3.0}, {-b, e}, {-e, e}},
          {{-e, -e}, {-b, -e}, {-b, -b}, {-e, -b}},
          {{b, -e}, {e, -e}, {e, -b}, {b + 8.0, -b}, {b + 8.0, -(b + 6.0)}, {b, -(b + 6.0)}}};
}

void AddFourWay(std::vector<Shape>& shapes) {
  for (std::vector<Vector2d>& block : FourWayBlocks()) {
    shapes.push_back(Shape::Polygon(std::move(block), kStaticOwner));
  }

  // Lamp posts: one on each sidewalk corner and a few along the approaches, staggered.
  const double f = kFurnitureLineM;
  for (const Vector2d& c :
       {Vector2d(f, f), Vector2d(-f, f), Vector2d(-f, -f), Vector2d(f, -f), Vector2d(25.0, -f),
        Vector2d(-25.0, f), Vector2d(f, 25.0), Vector2d(-f, -25.0)}) {
    shapes.push_back(Shape::Circle(c, kPoleRadiusM, kStaticOwner));
  }
  // Give-way signs 9 m from the centre, on the right of each approach (right-hand traffic):
  // eastbound traffic (y < 0) passes the one at (-9, -f), and so on round the junction.
  for (const Vector2d& c :
       {Vector2d(-9.0, -f), Vector2d(9.0, f), Vector2d(f, -9.0), Vector2d(-f, 9.0)}) {
    shapes.push_back(Shape::Circle(c, kSignRadiusM, kStaticOwner));
  }
}

Shape ObstacleShape(const Obstacle& o) {
  switch (o.kind) {
    case ObstacleKind::kBuilding:
      return Shape::Polygon(o.polygon, kStaticOwner);
    case ObstacleKind::kPole:
    case ObstacleKind::kSign:
      return Shape::Circle(o.center_m, o.radius_m, kStaticOwner);
    case ObstacleKind::kParkedCar:
      return Shape::Box(Pose2(o.center_m, o.heading_rad), o.length_m, o.width_m, kStaticOwner);
  }
  throw std::invalid_argument("unknown obstacle kind");
}

}  // namespace

std::vector<std::vector<Vector2d>> BuildingOutlines(const World& world) {
  std::vector<std::vector<Vector2d>> out;
  if (world.preset) {
    if (*world.preset != "four_way") {
      throw std::invalid_argument("unknown world preset \"" + *world.preset + "\"");
    }
    out = FourWayBlocks();
  }
  for (const Obstacle& o : world.obstacles) {
    if (o.kind == ObstacleKind::kBuilding) out.push_back(o.polygon);
  }
  return out;
}

std::vector<Shape> BuildStaticWorld(const World& world) {
  std::vector<Shape> shapes;
  if (world.preset) {
    if (*world.preset != "four_way") {
      throw std::invalid_argument("unknown world preset \"" + *world.preset + "\"");
    }
    AddFourWay(shapes);
  }
  shapes.reserve(shapes.size() + world.obstacles.size());
  for (const Obstacle& o : world.obstacles) shapes.push_back(ObstacleShape(o));
  return shapes;
}

}  // namespace lookout::sim
