#pragma once

// What a road user occupies at one prediction step (seed 004 section VIII.C, and the issue's
// sharper option): an oriented rectangle grown by a radius, the Minkowski sum of the rectangle
// and a disc. A vehicle is its box (the radius its uncertainty margin); a pedestrian, or a
// vehicle whose heading is unknown, is a circle: a rectangle of no extent.
//
// The paper's circles cover a car with a disc of half its diagonal (2.42 m for 4.5 x 1.8 m),
// wider than its lane: two cars passing in adjacent lanes (3.5 m apart) overlap. The boxes
// overlap only where the vehicles would.

#include <Eigen/Core>
#include <vector>

namespace lookout::risk {

// Made by Circle or Box, which also set the derived fields (the collision tests run millions
// of times a step and would otherwise recompute them each time).
struct Footprint {
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;        // direction of the rectangle's length
  double half_length_m = 0.0;  // >= 0
  double half_width_m = 0.0;   // >= 0
  double radius_m = 0.0;       // >= 0, added all round
  // Derived: (cos, sin) of yaw_rad, and the radius of the smallest circle about the centre
  // that holds the footprint.
  Eigen::Vector2d axis = Eigen::Vector2d::UnitX();
  double bounding_radius_m = 0.0;

  static Footprint Circle(const Eigen::Vector2d& centre_m, double radius_m);
  static Footprint Box(const Eigen::Vector2d& centre_m, double yaw_rad, double length_m,
                       double width_m, double margin_m = 0.0);

  double BoundingRadius() const { return bounding_radius_m; }
};

// One road user's footprints at t = 0, dt, 2 dt, ...
using FootprintTrack = std::vector<Footprint>;

// The signed distance between two footprints: their Euclidean distance when apart, minus the
// depth of their overlap (the shortest translation that separates them) when they overlap;
// <= 0 exactly when they touch or overlap. Pure.
double Separation(const Footprint& a, const Footprint& b);

// Whether `a` and `b` moved by `offset_m` touch or overlap. The same test as
// Separation(a, moved b) <= 0, with a bounding-circle shortcut for the common case of
// footprints far apart. Pure.
bool Overlap(const Footprint& a, const Footprint& b, const Eigen::Vector2d& offset_m);

}  // namespace lookout::risk
