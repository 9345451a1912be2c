#include "lookout/sim/odometry_sensor.h"

namespace lookout::sim {

EgoOdometry MakeOdometry(const OdometryOptions& options, TimeNs stamp,
                         const KinematicState& ego, Rng& rng) {
  EgoOdometry odometry;
  odometry.stamp = stamp;
  odometry.speed_mps = rng.Normal(ego.speed_mps, options.speed_noise_mps);
  odometry.yaw_rate_radps = rng.Normal(ego.yaw_rate_radps, options.yaw_rate_noise_radps);
  return odometry;
}

}  // namespace lookout::sim
