#pragma once

// The tracking issue's benchmark input: `targets` road users (cars, cyclists and pedestrians in
// turn) on straight paths at their classes' speeds in a 100 m x 100 m square, seen at 10 Hz with
// 0.2 m noise, each detection missed with probability 0.1 and seen by both sensors half of the
// time, plus `false_objects` false detections a scan, of unknown class, uniform over the square.
// Drawn from `seed`, so that bench/mht_bench.cc and `lookout bench` time the same scene.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lookout/core/time.h"
#include "lookout/tracking/tracker.h"

namespace lookout::tracking {

struct BenchmarkScene {
  static constexpr double kSideM = 100.0;  // the square, centred on the origin
  static constexpr TimeNs kScanPeriod = 100'000'000;
  std::vector<TimeNs> stamps;
  std::vector<std::vector<Detection>> scans;               // true detections first, then false
  std::vector<std::vector<Eigen::Vector2d>> truth;          // per scan, per target
  double clutter_density_per_m2 = 0.0;                      // false_objects / side^2
};

BenchmarkScene MakeBenchmarkScene(int targets, int false_objects, int scans, std::uint64_t seed);

}  // namespace lookout::tracking
