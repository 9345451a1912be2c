#pragma once

// A point as range and bearing from a sensor's origin, with its covariance (seed 004 V.C and
// VI.B: stereo objects are handed to fusion as range and bearing from the lidar's origin), and
// the conversions to and from Cartesian coordinates with first-order (Jacobian) propagation of
// the covariance.
//
// Linearisation error: the conversion to Cartesian bends a range/bearing Gaussian into a
// banana; its mean shifts by about r sigma_theta^2 / 2 along the ray. For the sensors here
// (sigma_theta <= 0.01 rad, r <= 40 m) that is under 2 mm, far below the range error, so the
// first-order propagation is used (range_bearing_test.cc checks it against Monte Carlo).

#include <Eigen/Core>

#include "lookout/core/pose2.h"

namespace lookout::stereo {

struct RangeBearing {
  double range_m = 0.0;
  double bearing_rad = 0.0;  // in the sensor frame, counter-clockwise from its x axis
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // of (range m, bearing rad)
};

struct CartesianPoint {
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // m^2
};

// d(x, y) / d(range, bearing) in the sensor's own axes, at (range, bearing).
Eigen::Matrix2d PolarToCartesianJacobian(double range_m, double bearing_rad);

// `point` (with covariance) in the parent frame, seen from a sensor whose frame is `origin` in
// the parent frame. The point must not be at the origin (range > 0).
RangeBearing ToRangeBearing(const CartesianPoint& point, const Pose2& origin);

// The inverse: back into the parent frame, covariance J C J^T rotated by the origin's yaw.
CartesianPoint ToCartesian(const RangeBearing& polar, const Pose2& origin);

}  // namespace lookout::stereo
