#pragma once

// The ego vehicle's state as the localisation emits it (docs/ARCHITECTURE.md: EgoState), and
// the one interface through which every consumer (the extended grid first) obtains it.
//
// The odometry frame: a local frame fixed to the ground, in which the ego pose is continuous
// (no jumps from loop closures or relocalisation) but drifts slowly with respect to the world.
// It is where the extended grid lives and scrolls (docs/extended-grid.md). Dead reckoning
// starts it at the pose it is given (by default the vehicle frame at the first odometry
// reading); the lidar-chain localisation will supply a better pose in the same frame.

#include <Eigen/Core>
#include <optional>

#include "lookout/core/pose2.h"
#include "lookout/core/time.h"

namespace lookout {

struct EgoState {
  TimeNs stamp = 0;
  Pose2 pose;                   // vehicle frame in the odometry frame
  double speed_mps = 0.0;       // along the vehicle's x axis
  double yaw_rate_radps = 0.0;  // counter-clockwise
  // Covariance of (x_m, y_m, yaw_rad) of `pose`, in the odometry frame: m^2, m rad, rad^2.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

// "The ego pose comes through one interface": dead-reckoned odometry now (DeadReckoning),
// the lidar-chain localisation later. Implementations are deterministic: the same inputs
// give the same answers, whatever the thread or the order of queries.
class EgoPoseSource {
 public:
  virtual ~EgoPoseSource() = default;

  // The ego state at time t, or nullopt when the source cannot tell (no data yet, or t too far
  // from its data to be trusted). Const and free of side effects: safe to call from several
  // threads while no one feeds the source.
  virtual std::optional<EgoState> PoseAt(TimeNs t) const = 0;
};

}  // namespace lookout
