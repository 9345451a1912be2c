#include "lookout/stereo/depth_model.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "lookout/core/pose2.h"

namespace lookout::stereo {
namespace {

void Require(bool ok, const char* field, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("StereoDepthModel.") + field + ": " + what);
}

}  // namespace

void StereoDepthModel::Validate() const {
  Require(focal_length_px > 0.0, "focal_length_px", "must be > 0");
  Require(baseline_m > 0.0, "baseline_m", "must be > 0");
  Require(disparity_sigma_px >= 0.0, "disparity_sigma_px", "must be >= 0");
  Require(bearing_sigma_rad >= 0.0, "bearing_sigma_rad", "must be >= 0");
  // A strictly positive floor keeps every covariance invertible.
  Require(position_sigma_floor_m > 0.0, "position_sigma_floor_m", "must be > 0");
}

double StereoDepthModel::DepthSigma(double depth_m) const {
  const double disparity_term =
      depth_m * depth_m * disparity_sigma_px / (focal_length_px * baseline_m);
  return std::hypot(disparity_term, position_sigma_floor_m);
}

double StereoDepthModel::AlongRaySigma(const Eigen::Vector2d& point_camera_m) const {
  const double depth_m = point_camera_m.x();
  return DepthSigma(depth_m) * point_camera_m.norm() / depth_m;
}

double StereoDepthModel::AcrossRaySigma(const Eigen::Vector2d& point_camera_m) const {
  return std::hypot(point_camera_m.norm() * bearing_sigma_rad, position_sigma_floor_m);
}

Eigen::Matrix2d StereoDepthModel::PointCovariance(const Eigen::Vector2d& point_camera_m) const {
  const double along = AlongRaySigma(point_camera_m);
  const double across = AcrossRaySigma(point_camera_m);
  const double bearing = std::atan2(point_camera_m.y(), point_camera_m.x());
  const Eigen::Matrix2d rotation = Pose2(0.0, 0.0, bearing).Rotation();
  const Eigen::Vector2d variances(along * along, across * across);
  return rotation * variances.asDiagonal() * rotation.transpose();
}

}  // namespace lookout::stereo
