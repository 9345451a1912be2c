#pragma once

// The sensor mounts the fusion tests share (vehicle frame, origin at the rear axle): the camera
// 0.8 m and the lidar 2.2 m ahead of it, so that the two sensors' origins differ and a test
// would see a frame mixed up.

#include "lookout/core/pose2.h"

namespace lookout::fusion::testing {

inline const Pose2 kCameraMount(0.8, 0.0, 0.0);
inline const Pose2 kLidarMount(2.2, 0.0, 0.0);

}  // namespace lookout::fusion::testing
