#pragma once

// Test-only (included by the lidar tests, not by the library, which never depends on the
// simulator): a 160-degree scan at 0.25 degrees from the origin, cast exactly (no noise) against
// a world of shapes, so that a test knows every range it feeds the chain.

#include <numbers>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/sim/raycast.h"
#include "lookout/sim/shapes.h"

namespace lookout::lidar::testing {

inline LidarScan CastScan(const std::vector<sim::Shape>& world) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  LidarScan scan;
  scan.angle_min_rad = -80.0 * kDeg;
  scan.angle_increment_rad = 0.25 * kDeg;
  scan.max_range_m = 80.0;
  sim::Fan fan;
  fan.angle_min_rad = scan.angle_min_rad;
  fan.angle_increment_rad = scan.angle_increment_rad;
  fan.count = 641;
  fan.max_range_m = scan.max_range_m;
  const sim::FanHits hits = sim::CastFan(fan, world, {}, 0);
  for (double r : hits.range_m) scan.ranges_m.push_back(static_cast<float>(r));
  return scan;
}

}  // namespace lookout::lidar::testing
