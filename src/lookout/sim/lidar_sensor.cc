#include "lookout/sim/lidar_sensor.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace lookout::sim {

int LidarBeamCount(const LidarOptions& options) {
  assert(options.fov_rad > 0.0 && options.resolution_rad > 0.0);
  // The tolerance keeps 160 deg / 0.25 deg at 640 intervals although both are rounded radians.
  return static_cast<int>(std::floor(options.fov_rad / options.resolution_rad + 1e-9)) + 1;
}

Pose2 LidarMount(const LidarOptions& options) {
  return Pose2(options.x_m, options.y_m, options.yaw_rad);
}

Fan LidarFan(const LidarOptions& options, const Pose2& ego_pose) {
  const Pose2 sensor = ego_pose * LidarMount(options);
  const int count = LidarBeamCount(options);
  const double half_span_rad = 0.5 * static_cast<double>(count - 1) * options.resolution_rad;
  return Fan{sensor.translation, sensor.yaw - half_span_rad, options.resolution_rad, count,
             options.max_range_m};
}

LidarScan MakeLidarScan(const LidarOptions& options, TimeNs stamp, const FanHits& hits,
                        Rng& rng) {
  constexpr float kNoReturn = std::numeric_limits<float>::infinity();
  LidarScan scan;
  scan.stamp = stamp;
  scan.mount = LidarMount(options);
  const int count = LidarBeamCount(options);
  assert(hits.range_m.size() == static_cast<std::size_t>(count));
  scan.angle_min_rad = -0.5 * static_cast<double>(count - 1) * options.resolution_rad;
  scan.angle_increment_rad = options.resolution_rad;
  scan.max_range_m = options.max_range_m;
  scan.ranges_m.reserve(hits.range_m.size());
  for (std::size_t i = 0; i < hits.range_m.size(); ++i) {
    // Both draws always happen: see the header.
    const bool dropped = rng.Uniform() < options.dropout;
    const double noise_m = options.range_noise_m * rng.Normal();
    const double truth_m = hits.range_m[i];
    if (dropped || !std::isfinite(truth_m)) {
      scan.ranges_m.push_back(kNoReturn);
      continue;
    }
    const double measured_m = std::max(0.0, truth_m + noise_m);
    scan.ranges_m.push_back(measured_m > options.max_range_m ? kNoReturn
                                                             : static_cast<float>(measured_m));
  }
  return scan;
}

LidarScan SimulateLidarScan(const LidarOptions& options, TimeNs stamp, const Pose2& ego_pose,
                            std::span<const Shape> static_world,
                            std::span<const Shape> actor_footprints, int actor_count,
                            Rng& rng) {
  const FanHits hits =
      CastFan(LidarFan(options, ego_pose), static_world, actor_footprints, actor_count);
  return MakeLidarScan(options, stamp, hits, rng);
}

}  // namespace lookout::sim
