#pragma once

// Bringing a stereo object to the lidar frame's time. The camera runs at 20 Hz and the lidar
// at 12.5 Hz, so the latest stereo frame is up to 50 ms older (or, from a log, newer) than
// the lidar frame; an object at 15 m/s moves 0.75 m in that time, and the ego as much, which
// is more than the lidar's error. Two motions are undone:
//   - the ego's: the stereo point is in the vehicle frame at the stereo stamp; it is carried
//     into the vehicle frame at the lidar stamp by lidar_from_stereo_vehicle =
//     ego(t_lidar)^-1 * ego(t_stereo) (poses in the odometry frame);
//   - the object's: constant velocity over the ground for dt = t_lidar - t_stereo, with
//     white-noise acceleration of sigma_a:
//         p' = p + v dt,  P' = P + dt^2 C_v + (sigma_a dt^2 / 2)^2 I,
//         v' = v,         C_v' = C_v + (sigma_a dt)^2 I
//     (position and velocity errors independent, as the camera reports no cross term).

#include "lookout/core/pose2.h"
#include "lookout/stereo/stereo_point.h"

namespace lookout::fusion {

// `point` predicted by dt_s and carried by `lidar_from_stereo_vehicle`; its range and bearing
// recomputed from the lidar at `lidar_mount`. Pure.
stereo::StereoPoint PredictStereoPoint(const stereo::StereoPoint& point, double dt_s,
                                       const Pose2& lidar_from_stereo_vehicle,
                                       const Pose2& lidar_mount, double acceleration_sigma_mps2);

// The ego pose at `t` from the two poses around it (or before it), moving at constant speed
// and turn rate between them: translation and yaw interpolated (or extrapolated) linearly. For
// the 50 ms between frames at the ego's speeds the chord of an arc is within millimetres of it.
Pose2 InterpolatePose(TimeNs t0, const Pose2& pose0, TimeNs t1, const Pose2& pose1, TimeNs t);

}  // namespace lookout::fusion
