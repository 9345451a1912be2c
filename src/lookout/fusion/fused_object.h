#pragma once

// The fusion stage's output (seed 004 VI.C): per object its position (the middle of the front
// line segment) with covariance, velocity, class, dynamic state, how many sensors saw it, and
// the ids of the objects it came from. Vehicle frame at the lidar frame's stamp.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "lookout/core/object_class.h"
#include "lookout/core/pose2.h"
#include "lookout/core/time.h"

namespace lookout::fusion {

struct FusedObject {
  std::uint32_t id = 0;  // index in its frame
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d point_covariance = Eigen::Matrix2d::Identity();  // m^2
  // Over the ground, vehicle axes (as LidarObject::velocity_mps).
  Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();
  Eigen::Matrix2d velocity_covariance = Eigen::Matrix2d::Identity();  // (m/s)^2
  // The front line segment, for display: the lidar's when it saw the object, else the camera's.
  Eigen::Vector2d front_start_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d front_end_m = Eigen::Vector2d::Zero();
  // Indexed by ObjectClass (kAllObjectClasses order); sums to 1. The camera's when it saw the
  // object (it classifies from appearance), the lidar's otherwise.
  std::array<double, kAllObjectClasses.size()> class_pmf{};
  bool dynamic = false;
  int sensor_count = 0;                    // 1 or 2
  // Both sensors saw it on different sides: the point is the camera's (fuse_objects.h).
  bool footprint_pair = false;
  std::optional<std::uint32_t> lidar_id;   // LidarObject::id in the lidar frame
  std::optional<std::uint32_t> stereo_id;  // StereoObject::id, the camera's track id
};

struct FusedObjectFrame {
  TimeNs stamp = 0;  // the lidar frame's
  Pose2 mount;       // lidar frame in the vehicle frame
  Pose2 ego_pose;    // vehicle frame in the odometry frame at `stamp`
  // The lidar's objects first, in their order (fused with a stereo object or alone), then the
  // stereo objects no lidar object took, in the camera's order.
  std::vector<FusedObject> objects;
};

}  // namespace lookout::fusion
