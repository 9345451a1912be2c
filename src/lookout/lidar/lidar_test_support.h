#pragma once

// Test support (tests only: it uses the simulator, which the lidar library does not link): a
// walled hall with pillars and boxes, and 2D lidar scans cast in it by the simulator's exact
// ray caster.

#include <cmath>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/sim/raycast.h"
#include "lookout/sim/shapes.h"

namespace lookout::lidar::testing {

// A 40 m x 24 m hall (walls 0.3 m thick) around the origin, with box rooms, pillars and a
// few irregular obstacles, so every pose sees structure in both axes.
inline std::vector<sim::Shape> Hall() {
  using sim::Shape;
  const int s = sim::kStaticOwner;
  std::vector<Shape> w;
  w.push_back(Shape::Box(Pose2(0.0, 12.15, 0.0), 40.6, 0.3, s));
  w.push_back(Shape::Box(Pose2(0.0, -12.15, 0.0), 40.6, 0.3, s));
  w.push_back(Shape::Box(Pose2(20.15, 0.0, 0.0), 0.3, 24.6, s));
  w.push_back(Shape::Box(Pose2(-20.15, 0.0, 0.0), 0.3, 24.6, s));
  w.push_back(Shape::Box(Pose2(-8.0, 6.0, 0.3), 4.0, 2.0, s));
  w.push_back(Shape::Box(Pose2(7.0, -6.5, -0.2), 3.0, 5.0, s));
  w.push_back(Shape::Box(Pose2(12.0, 7.0, 0.0), 6.0, 1.0, s));
  w.push_back(Shape::Box(Pose2(-13.0, -7.0, 0.7), 2.0, 2.0, s));
  for (int i = 0; i < 6; ++i) {
    w.push_back(Shape::Circle({-15.0 + 6.0 * i, 2.5 + (i % 2 == 0 ? 0.0 : 1.0)}, 0.3, s));
    w.push_back(Shape::Circle({-14.0 + 6.0 * i, -3.0}, 0.25, s));
  }
  w.push_back(Shape::Polygon({{0.0, 8.0}, {3.0, 9.0}, {1.5, 10.5}}, s));
  return w;
}

// A 360-beam, 270-degree scan from a lidar mounted 1 m ahead of the vehicle's centre.
inline LidarScan CastScan(const std::vector<sim::Shape>& world, const Pose2& vehicle,
                          TimeNs stamp = 0) {
  LidarScan scan;
  scan.stamp = stamp;
  scan.mount = Pose2(1.0, 0.0, 0.0);
  scan.angle_min_rad = -0.75 * kPi;
  scan.angle_increment_rad = 1.5 * kPi / 359.0;
  scan.max_range_m = 30.0;
  const Pose2 sensor = vehicle * scan.mount;
  sim::Fan fan;
  fan.origin_m = sensor.translation;
  fan.angle_min_rad = sensor.yaw + scan.angle_min_rad;
  fan.angle_increment_rad = scan.angle_increment_rad;
  fan.count = 360;
  fan.max_range_m = scan.max_range_m;
  const sim::FanHits hits = sim::CastFan(fan, world, {}, 0);
  scan.ranges_m.reserve(hits.range_m.size());
  for (double r : hits.range_m) scan.ranges_m.push_back(static_cast<float>(r));
  return scan;
}

}  // namespace lookout::lidar::testing
