#include "lookout/stereo/range_bearing.h"

#include <Eigen/LU>
#include <cassert>
#include <cmath>

namespace lookout::stereo {

using Eigen::Matrix2d;
using Eigen::Vector2d;

Matrix2d PolarToCartesianJacobian(double range_m, double bearing_rad) {
  const double c = std::cos(bearing_rad);
  const double s = std::sin(bearing_rad);
  Matrix2d j;
  j << c, -range_m * s,  //
      s, range_m * c;
  return j;
}

RangeBearing ToRangeBearing(const CartesianPoint& point, const Pose2& origin) {
  const Vector2d local = origin.Inverse() * point.point_m;
  RangeBearing polar;
  polar.range_m = local.norm();
  assert(polar.range_m > 0.0);
  polar.bearing_rad = std::atan2(local.y(), local.x());
  const Matrix2d rotation = origin.Rotation();
  const Matrix2d local_covariance = rotation.transpose() * point.covariance * rotation;
  // The inverse of the polar-to-Cartesian Jacobian at the point.
  const Matrix2d inverse_jacobian =
      PolarToCartesianJacobian(polar.range_m, polar.bearing_rad).inverse();
  polar.covariance = inverse_jacobian * local_covariance * inverse_jacobian.transpose();
  polar.covariance = 0.5 * (polar.covariance + polar.covariance.transpose()).eval();
  return polar;
}

CartesianPoint ToCartesian(const RangeBearing& polar, const Pose2& origin) {
  const Vector2d local(polar.range_m * std::cos(polar.bearing_rad),
                       polar.range_m * std::sin(polar.bearing_rad));
  const Matrix2d jacobian =
      origin.Rotation() * PolarToCartesianJacobian(polar.range_m, polar.bearing_rad);
  CartesianPoint point;
  point.point_m = origin * local;
  point.covariance = jacobian * polar.covariance * jacobian.transpose();
  point.covariance = 0.5 * (point.covariance + point.covariance.transpose()).eval();
  return point;
}

}  // namespace lookout::stereo
