#pragma once

// The messages that flow between stages (docs/ARCHITECTURE.md has the data flow). Every one
// carries its timestamp; SI units; frames as docs/conventions.md says: the vehicle frame has
// its origin at the centre of the footprint, x forward, y left; a sensor frame is given by its
// mount pose in the vehicle frame.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "lookout/core/object_class.h"
#include "lookout/core/pose2.h"
#include "lookout/core/time.h"

namespace lookout {

// One sweep of a 2D lidar, taken at `stamp` (the sweep is treated as instantaneous).
// Beam i points at angle_min_rad + i * angle_increment_rad in the sensor frame.
// Ranges follow REP 117: +infinity means no return within max_range_m (dropouts too);
// NaN is an erroneous reading that consumers must skip.
struct LidarScan {
  TimeNs stamp = 0;
  Pose2 mount;  // sensor frame in the vehicle frame
  double angle_min_rad = 0.0;
  double angle_increment_rad = 0.0;
  double max_range_m = 0.0;
  std::vector<float> ranges_m;

  double BeamAngle(std::size_t i) const {
    return angle_min_rad + static_cast<double>(i) * angle_increment_rad;
  }
};

// An object reported by the stereo camera, in the camera frame (x forward along the optical
// axis projected on the ground plane, y left). Seed 004 section V: an oriented cuboid with
// class, speed and variances; Lookout works in the laser plane, so the cuboid is its footprint.
struct StereoObject {
  std::uint32_t id = 0;              // the camera's own track id, stable while it tracks
  ObjectClass object_class = ObjectClass::kUnknown;
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;              // heading of the box's length axis
  double length_m = 0.0;
  double width_m = 0.0;
  double speed_longitudinal_mps = 0.0;  // along the camera's x axis
  double speed_lateral_mps = 0.0;       // along the camera's y axis
  Eigen::Matrix2d center_covariance = Eigen::Matrix2d::Identity();  // m^2
  double yaw_variance = 0.0;            // rad^2
  double speed_variance = 0.0;          // (m/s)^2, each component
  std::uint32_t history = 0;  // frames this id has been tracked, this one included
};

struct StereoFrame {
  TimeNs stamp = 0;
  Pose2 mount;  // camera frame in the vehicle frame
  std::vector<StereoObject> objects;
};

// Wheel odometry and yaw-rate sensor of the ego vehicle.
struct EgoOdometry {
  TimeNs stamp = 0;
  double speed_mps = 0.0;
  double yaw_rate_radps = 0.0;
};

}  // namespace lookout
