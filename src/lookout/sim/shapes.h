#pragma once

// The 2D shapes the simulated world is made of: polygons (buildings, and the footprints of
// vehicles and parked cars as oriented boxes) and circles (poles, signs, pedestrians).

#include <Eigen/Core>
#include <vector>

#include "lookout/core/planar_geometry.h"
#include "lookout/core/pose2.h"

namespace lookout::sim {

// Who a shape belongs to: the static world, or an actor by its index in Scenario::actors.
inline constexpr int kStaticOwner = -1;

using lookout::Cross;  // core/planar_geometry.h

struct Shape {
  enum class Kind { kPolygon, kCircle };
  Kind kind = Kind::kPolygon;
  std::vector<Eigen::Vector2d> vertices;  // polygon: a simple closed ring, either orientation
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // circle
  double radius = 0.0;                                // circle
  int owner = kStaticOwner;

  static Shape Circle(const Eigen::Vector2d& center, double radius, int owner);
  // At least 3 vertices; consecutive duplicates and collinear vertices are allowed.
  static Shape Polygon(std::vector<Eigen::Vector2d> vertices, int owner);
  // A box of `length` along the pose's x axis and `width` along its y axis, centred on it.
  // Vertices counter-clockwise from the rear right corner: rear right, front right, front
  // left, rear left.
  static Shape Box(const Pose2& pose, double length, double width, int owner);
};

// Shapes are closed sets: a point on the boundary is contained, and shapes that only touch
// overlap. Exact up to the rounding of the orientation tests (no robust predicates): a point
// within about 1e-15 relative of a boundary may go either way.
bool Contains(const Shape& shape, const Eigen::Vector2d& point);
// True when the two shapes share any point. Circles and convex polygons: distance tests and
// the separating axis theorem. Non-convex (simple) polygons: edge intersection plus
// containment of one vertex, which is exact as well.
bool Overlap(const Shape& a, const Shape& b);

// Axis-aligned bounding box of a shape, world frame, metres.
struct Aabb {
  Eigen::Vector2d min = Eigen::Vector2d::Zero();
  Eigen::Vector2d max = Eigen::Vector2d::Zero();
  bool Intersects(const Aabb& o) const {
    return min.x() <= o.max.x() && o.min.x() <= max.x() && min.y() <= o.max.y() &&
           o.min.y() <= max.y();
  }
};
Aabb BoundingBox(const Shape& shape);

}  // namespace lookout::sim
