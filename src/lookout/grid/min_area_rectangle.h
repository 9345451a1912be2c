#pragma once

// The smallest-area rectangle enclosing a set of points in the plane: the oriented extent of a
// grid object (LidarObject's length, width and yaw; grid_objects.h).
//
// Why hand-written: none of the project's Debian dependencies has it (Eigen has no hull;
// CGAL's min_rectangle_2 would pull in a large library for some forty lines). The method is the
// classical one (Freeman and Shapira, 1975): the minimum-area rectangle has a side collinear
// with an edge of the convex hull, so trying each hull edge's direction is exact. The hull is
// Andrew's monotone chain; O(n log n) for the hull, O(h^2) for the h hull edges, which is small
// for the few hundred cells of an object's outline.

#include <Eigen/Core>
#include <vector>

namespace lookout::grid {

struct OrientedRectangle {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;   // direction of the length axis, in [-pi/2, pi/2): an axis, not a heading
  double length_m = 0.0;  // along yaw_rad; length_m >= width_m
  double width_m = 0.0;
};

// The convex hull of `points`, counter-clockwise, without collinear points; a single point or
// a segment's two ends for degenerate input; empty for no points.
std::vector<Eigen::Vector2d> ConvexHull(std::vector<Eigen::Vector2d> points);

// The minimum-area rectangle about `points`. Ties between hull edges of equal area go to the
// first edge of the hull (deterministic). No points: a zero rectangle at the origin.
OrientedRectangle MinAreaRectangle(const std::vector<Eigen::Vector2d>& points);

}  // namespace lookout::grid
