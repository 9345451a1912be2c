#pragma once

// Seed 004 VI.A: a stereo object is associated with a lidar object only inside a gate that
// grows with the stereo object's depth, "because depth uncertainty of stereo objects increases
// with the distance from the origin".
//
// Lookout's gate is a Mahalanobis (chi-square) gate, not the paper's distance threshold:
//     d^2 = (p_V - p_L)^T S^-1 (p_V - p_L) <= gamma,   S = R_L + R_V(z) + sigma_def^2 I
// with gamma the chi-square (2 dof) quantile of the gate probability. Why: the stereo error is
// an ellipse along the camera's line of sight, 18 times longer than wide at 35 m (1.28 m
// against 7 cm, stereo/depth_model.h). A circular distance gate wide enough for the depth
// error lets in objects beside the true one; this gate is long along the ray and narrow across
// it. It grows with depth through R_V(z): along the ray its half-length is
//     sqrt(gamma (sigma_along(z)^2 + sigma_L^2 + sigma_def^2)),  sigma_along ~ z^2
// (HalfLengthAlongRay), from 0.8 m at 5 m to 4.0 m at 35 m with the defaults (99 %, lidar
// sigma 0.1 m, sigma_def 0.25 m), and a true pair falls outside it with probability 1 - p.

#include <Eigen/Core>

#include "lookout/fusion/fusion_options.h"
#include "lookout/stereo/depth_model.h"

namespace lookout::fusion {

class AssociationGate {
 public:
  explicit AssociationGate(const FusionOptions& options);

  double threshold() const { return threshold_; }  // gamma
  // d^2 of the two points under S.
  double DistanceSquared(const Eigen::Vector2d& stereo_point_m,
                         const Eigen::Matrix2d& stereo_covariance,
                         const Eigen::Vector2d& lidar_point_m,
                         const Eigen::Matrix2d& lidar_covariance) const;
  bool Accepts(double distance_squared) const { return distance_squared <= threshold_; }

  // How far along the camera's line of sight a lidar point (isotropic sigma lidar_sigma_m) may
  // lie from a stereo point at `point_camera_m` (camera frame) and still pair: the gate's
  // half-length, with the stereo covariance of `model`. For the documentation and the tests.
  double HalfLengthAlongRay(const stereo::StereoDepthModel& model,
                            const Eigen::Vector2d& point_camera_m, double lidar_sigma_m) const;

 private:
  double threshold_;
  double definition_variance_;
};

}  // namespace lookout::fusion
