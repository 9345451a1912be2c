#pragma once

// The footprint of an object on the laser plane (seed 004 V.C.4: the stereo cuboid projected
// onto the ground) and its front line segment.

#include <Eigen/Core>
#include <array>
#include <optional>

namespace lookout::stereo {

// A rectangle: `length_m` along the heading `yaw_rad`, `width_m` across it, centred on
// `center_m`. Any frame; metres and radians.
struct OrientedBox {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;
  double length_m = 0.0;
  double width_m = 0.0;

  // Counter-clockwise from the rear right corner: rear right, front right, front left,
  // rear left.
  std::array<Eigen::Vector2d, 4> Corners() const;
  bool Contains(const Eigen::Vector2d& point_m) const;  // boundary included
};

// The side of a box facing a viewpoint, and its middle: the object's point in seed 004 (V.C:
// "the middle point of the front line segment ... gives better results than the center of
// gravity ... because laser readings also belong to the front end of the object").
struct FrontSegment {
  Eigen::Vector2d start_m;  // counter-clockwise about the box: start, then end
  Eigen::Vector2d end_m;
  Eigen::Vector2d midpoint_m;
  // d midpoint / d yaw: how the point moves when the heading turns (m/rad). The centre moves
  // the point one for one.
  Eigen::Vector2d midpoint_yaw_derivative;
};

// Which side faces `viewpoint_m`: the one the ray from the centre to the viewpoint leaves the
// box through. Seen from afar that is the side with the larger apparent extent (W |u_x| against
// L |u_y|, u the direction to the viewpoint in box axes), the side the laser has the most
// returns from. nullopt when the viewpoint lies inside the box (no side faces it).
//
// Limit: the choice jumps from one side to the next when the ray crosses a corner, and the
// midpoint with it (by up to half the box's diagonal); near such a view a small heading error
// picks the other side. ExpectedFrontPoint (stereo_point.h) accounts for that.
std::optional<FrontSegment> FrontSegmentFacing(const OrientedBox& box,
                                               const Eigen::Vector2d& viewpoint_m);

}  // namespace lookout::stereo
