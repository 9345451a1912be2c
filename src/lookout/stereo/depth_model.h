#pragma once

// How uncertain a stereo camera's position is, as a function of where the point is: the
// triangulation model that the simulator draws its noise from (sim/stereo_sensor.h), written
// here again because a stage must not link the simulator. The defaults are the simulator's,
// and depth_model_test.cc checks the two agree.
//
// Depth z = f B / d for a disparity d (px), focal length f (px) and baseline B (m); a
// disparity error sigma_d gives
//     sigma_z(z) = sqrt((z^2 sigma_d / (f B))^2 + floor^2)
// along the line of sight (the pixel, hence the ray, is fixed, so a depth error moves the point
// along the ray by sigma_z r / z, r the range). The image position error sigma_theta (rad)
// moves it across the ray by sqrt((r sigma_theta)^2 + floor^2). With f = 800 px, B = 0.3 m,
// sigma_d = 0.25 px: sigma_z = 2.6 cm at 5 m, 0.32 m at 17.5 m, 1.28 m at 35 m. So the
// variance along the ray grows with the fourth power of depth, the one across it with the
// square of the range: at 35 m the error ellipse is 18 times longer than wide.

#include <Eigen/Core>

namespace lookout::stereo {

struct StereoDepthModel {
  double focal_length_px = 800.0;
  double baseline_m = 0.3;
  double disparity_sigma_px = 0.25;
  double bearing_sigma_rad = 0.002;
  double position_sigma_floor_m = 0.02;  // calibration and box fitting, at short range

  // Throws std::invalid_argument naming the first field out of range.
  void Validate() const;

  double DepthSigma(double depth_m) const;  // sigma_z(z), floor included
  // Standard deviations along and across the camera's line of sight of a point at
  // `point_camera_m` (camera frame, depth x > 0).
  double AlongRaySigma(const Eigen::Vector2d& point_camera_m) const;
  double AcrossRaySigma(const Eigen::Vector2d& point_camera_m) const;
  // The covariance (m^2, camera frame) of a point at `point_camera_m` (depth x > 0): diagonal
  // in (along, across) the line of sight, rotated by its bearing.
  Eigen::Matrix2d PointCovariance(const Eigen::Vector2d& point_camera_m) const;
};

}  // namespace lookout::stereo
