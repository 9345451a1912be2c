#include "lookout/fusion/stereo_prediction.h"

#include <cassert>

namespace lookout::fusion {

using Eigen::Matrix2d;
using Eigen::Vector2d;

stereo::StereoPoint PredictStereoPoint(const stereo::StereoPoint& point, double dt_s,
                                       const Pose2& lidar_from_stereo_vehicle,
                                       const Pose2& lidar_mount, double acceleration_sigma_mps2) {
  const Pose2& motion = lidar_from_stereo_vehicle;
  const Matrix2d rotation = motion.Rotation();
  const Vector2d displacement = point.velocity_mps * dt_s;  // over the ground
  auto carry = [&](const Vector2d& p) -> Vector2d { return motion * (p + displacement); };

  stereo::StereoPoint out = point;
  out.footprint.center_m = carry(point.footprint.center_m);
  out.footprint.yaw_rad = WrapAngle(point.footprint.yaw_rad + motion.yaw);
  out.front.start_m = carry(point.front.start_m);
  out.front.end_m = carry(point.front.end_m);
  out.front.midpoint_m = carry(point.front.midpoint_m);
  out.front.midpoint_yaw_derivative = rotation * point.front.midpoint_yaw_derivative;
  out.velocity_mps = rotation * point.velocity_mps;
  out.heading_share.other_side_offset_m = rotation * point.heading_share.other_side_offset_m;
  out.heading_share.heading_slope_m = rotation * point.heading_share.heading_slope_m;

  const double position_noise = 0.5 * acceleration_sigma_mps2 * dt_s * dt_s;
  const double velocity_noise = acceleration_sigma_mps2 * dt_s;
  const Matrix2d position_covariance = point.point.covariance +
                                       dt_s * dt_s * point.velocity_covariance +
                                       position_noise * position_noise * Matrix2d::Identity();
  const Matrix2d velocity_covariance =
      point.velocity_covariance + velocity_noise * velocity_noise * Matrix2d::Identity();
  // The chosen side's middle, carried, with the covariance of ExpectedFrontPoint's two-sided
  // mixture: near a corner view the fusion takes the likelier side, not the mixture's mean,
  // which lies between two sides' middles where no body's side is (carried as the mean: one
  // car of intersafe-fig8 fused 1.6 m from its side, docs/fusion.md "A body's own history").
  out.point.point_m = out.front.midpoint_m;
  out.point.covariance = rotation * position_covariance * rotation.transpose();
  out.velocity_covariance = rotation * velocity_covariance * rotation.transpose();
  out.polar = stereo::ToRangeBearing(out.point, lidar_mount);
  return out;
}

Pose2 InterpolatePose(TimeNs t0, const Pose2& pose0, TimeNs t1, const Pose2& pose1, TimeNs t) {
  assert(t1 != t0);
  const double s = ToSeconds(t - t0) / ToSeconds(t1 - t0);
  return Pose2(pose0.translation + s * (pose1.translation - pose0.translation),
               WrapAngle(pose0.yaw + s * WrapAngle(pose1.yaw - pose0.yaw)));
}

}  // namespace lookout::fusion
