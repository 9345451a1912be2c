#include "lookout/fusion/gate.h"

#include <cmath>

#include "lookout/core/chi_square.h"
#include "lookout/fusion/gaussian_fusion.h"

namespace lookout::fusion {

AssociationGate::AssociationGate(const FusionOptions& options)
    : threshold_(ChiSquareQuantile(options.gate_probability, 2.0)),
      definition_variance_(options.point_definition_sigma_m * options.point_definition_sigma_m) {}

double AssociationGate::DistanceSquared(const Eigen::Vector2d& stereo_point_m,
                                        const Eigen::Matrix2d& stereo_covariance,
                                        const Eigen::Vector2d& lidar_point_m,
                                        const Eigen::Matrix2d& lidar_covariance) const {
  const Eigen::Matrix2d s = stereo_covariance + lidar_covariance +
                            definition_variance_ * Eigen::Matrix2d::Identity();
  return MahalanobisSquared(stereo_point_m - lidar_point_m, s);
}

double AssociationGate::HalfLengthAlongRay(const stereo::StereoDepthModel& model,
                                           const Eigen::Vector2d& point_camera_m,
                                           double lidar_sigma_m) const {
  const double along = model.AlongRaySigma(point_camera_m);
  return std::sqrt(threshold_ *
                   (along * along + lidar_sigma_m * lidar_sigma_m + definition_variance_));
}

}  // namespace lookout::fusion
