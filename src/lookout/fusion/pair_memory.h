#pragma once

// A camera track's last pair, and where it puts the body a lidar frame later. Beyond the paper,
// which pairs each frame afresh: the camera's depth error along its ray (0.45 m at 20 m) makes
// its gate long enough to hold a walker's neighbour, and where the walker's own segment is
// missing (hidden behind another walker, merged with a post) the gate pairs the walker's camera
// object with the neighbour's segment. The crowd's 21 pairs whose lidar point lay more than
// 0.5 m from the same camera track's fused point of the frame before held 29 % of its fused
// NEES sum (docs/fusion.md, "A camera track keeps its body"). The fused point of the last pair
// knows the body to centimetres; predicted to this frame with the fused velocity, it is a
// second gate the lidar point must pass. A pair refused by it leaves the camera object unpaired
// (kept, as the paper keeps every stereo object), and no memory: the next frame pairs afresh, so
// a memory of a wrong pair misleads for one frame at most.
//
// The memory is in the odometry frame, which the ego's motion does not move:
//     p' = p + v dt,   P' = P + dt^2 C_v + (sigma_a dt^2 / 2)^2 I
// (as PredictStereoPoint), then carried into the vehicle frame at the lidar stamp.

#include <Eigen/Core>
#include <optional>

#include "lookout/core/pose2.h"
#include "lookout/core/time.h"
#include "lookout/fusion/fused_object.h"
#include "lookout/stereo/range_bearing.h"

namespace lookout::fusion {

struct PairMemory {
  TimeNs stamp = 0;
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();  // odometry frame
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
  Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();  // odometry axes
  Eigen::Matrix2d velocity_covariance = Eigen::Matrix2d::Identity();
};

// The memory of fused object `f` of the frame at `stamp` whose vehicle pose (odometry frame) is
// `ego_pose`. Pure.
PairMemory RememberPair(const FusedObject& f, TimeNs stamp, const Pose2& ego_pose);

// Where `memory` puts its body at `stamp`, in the vehicle frame of `ego_pose`; nullopt when the
// memory is not older than `stamp` or older by more than `max_age_s`. Pure.
std::optional<stereo::CartesianPoint> PredictPairPrior(const PairMemory& memory, TimeNs stamp,
                                                       const Pose2& ego_pose,
                                                       double acceleration_sigma_mps2,
                                                       double max_age_s);

}  // namespace lookout::fusion
