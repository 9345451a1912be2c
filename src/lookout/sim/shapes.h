#pragma once

// The 2D shapes the simulated world is made of: polygons (buildings, and the footprints of
// vehicles and parked cars as oriented boxes) and circles (poles, signs, pedestrians).

#include <Eigen/Core>
#include <vector>

#include "lookout/core/pose2.h"

namespace lookout::sim {

// Who a shape belongs to: the static world, or an actor by its index in Scenario::actors.
inline constexpr int kStaticOwner = -1;

struct Shape {
  enum class Kind { kPolygon, kCircle };
  Kind kind = Kind::kPolygon;
  std::vector<Eigen::Vector2d> vertices;  // polygon: a simple closed ring, either orientation
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // circle
  double radius = 0.0;                                // circle
  int owner = kStaticOwner;

  static Shape Circle(const Eigen::Vector2d& center, double radius, int owner);
  static Shape Polygon(std::vector<Eigen::Vector2d> vertices, int owner);
  // A box of `length` along the pose's x axis and `width` along its y axis, centred on it.
  static Shape Box(const Pose2& pose, double length, double width, int owner);
};

bool Contains(const Shape& shape, const Eigen::Vector2d& point);
// True when the two shapes share any point (convex polygons and circles: exact).
bool Overlap(const Shape& a, const Shape& b);

}  // namespace lookout::sim
