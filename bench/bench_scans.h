#pragma once

// Lidar scans of hand-built scenes for the grid benchmarks, cast by the simulator's own ray
// caster (sim/raycast.h): the default lidar, 641 beams over 160 degrees at 0.25 degree, 150 m.

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/sim/raycast.h"
#include "lookout/sim/shapes.h"

namespace lookout::bench {

// An axis-aligned box from its lower-left and upper-right corners, as a static shape.
inline sim::Shape AxisBox(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  return sim::Shape::Polygon({lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}}, sim::kStaticOwner);
}

// The default lidar at `sensor_pose` (world frame) with `mount` recorded in the scan.
inline LidarScan CastDefaultScan(const std::vector<sim::Shape>& shapes, const Pose2& sensor_pose,
                                 const Pose2& mount) {
  LidarScan scan;
  scan.mount = mount;
  scan.angle_increment_rad = DegToRad(0.25);
  scan.angle_min_rad = DegToRad(-80.0);
  scan.max_range_m = 150.0;
  sim::Fan fan;
  fan.origin_m = sensor_pose.translation;
  fan.angle_min_rad = sensor_pose.yaw + scan.angle_min_rad;
  fan.angle_increment_rad = scan.angle_increment_rad;
  fan.count = 641;
  fan.max_range_m = scan.max_range_m;
  const sim::FanHits hits = sim::CastFan(fan, shapes, {}, 0);
  scan.ranges_m.reserve(hits.range_m.size());
  for (const double r : hits.range_m) scan.ranges_m.push_back(static_cast<float>(r));
  return scan;
}

}  // namespace lookout::bench
