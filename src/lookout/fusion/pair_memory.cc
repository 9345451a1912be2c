#include "lookout/fusion/pair_memory.h"

namespace lookout::fusion {

using Eigen::Matrix2d;

PairMemory RememberPair(const FusedObject& f, TimeNs stamp, const Pose2& ego_pose) {
  const Matrix2d r = ego_pose.Rotation();
  PairMemory m;
  m.stamp = stamp;
  m.point_m = ego_pose * f.point_m;
  m.covariance = r * f.point_covariance * r.transpose();
  m.velocity_mps = r * f.velocity_mps;
  m.velocity_covariance = r * f.velocity_covariance * r.transpose();
  return m;
}

std::optional<stereo::CartesianPoint> PredictPairPrior(const PairMemory& memory, TimeNs stamp,
                                                       const Pose2& ego_pose,
                                                       double acceleration_sigma_mps2,
                                                       double max_age_s) {
  const double dt = ToSeconds(stamp - memory.stamp);
  if (!(dt > 0.0) || dt > max_age_s) return std::nullopt;
  const double a = 0.5 * acceleration_sigma_mps2 * dt * dt;
  const Matrix2d odometry_covariance =
      memory.covariance + dt * dt * memory.velocity_covariance + a * a * Matrix2d::Identity();
  const Pose2 vehicle_from_odometry = ego_pose.Inverse();
  const Matrix2d r = vehicle_from_odometry.Rotation();
  return stereo::CartesianPoint{vehicle_from_odometry * (memory.point_m + dt * memory.velocity_mps),
                                r * odometry_covariance * r.transpose()};
}

}  // namespace lookout::fusion
