#pragma once

// Scores the lidar objects (the grid's rigid clusters, grid/grid_objects.h) against the
// simulator's ground truth after every lidar cycle: the lidar_objects.* keys of
// docs/cli-contract.md, defined in eval/object_detection_metrics.h. Here: which point of an
// object is compared (its centroid: the middle of the cluster's cells), which objects count
// (the dynamic ones), and which actors count for recall (those the lidar sees at that frame,
// visible_fraction_lidar > 0, with their footprint's centre inside the grid's window: an
// object can come only from there).
//
// Frames: objects are in the vehicle frame of their LidarObjectFrame; its ego_pose (the
// estimate, in the odometry frame) and the odometry frame's true pose in the world bring them
// into the world, so dead-reckoning drift counts as object error, as it would on a real car.

#include <cstdint>
#include <map>
#include <string>

#include "lookout/core/grid_geometry.h"
#include "lookout/core/messages.h"
#include "lookout/eval/object_detection_metrics.h"
#include "lookout/sim/truth.h"

namespace lookout::app {

class LidarObjectScorer {
 public:
  // `world_from_odom`: the odometry frame in the world (the ego's true pose at t = 0).
  explicit LidarObjectScorer(const Pose2& world_from_odom,
                             const eval::DetectionMatchOptions& options = {});

  // After a cycle: `objects` and the truth at the same stamp; `window_odom` the grid's window
  // in the odometry frame (ScrollingGridGeometry::WindowGeometry).
  void Observe(const LidarObjectFrame& objects, const sim::TruthFrame& truth_world,
               const GridGeometry& window_odom);

  // lidar_objects.precision and .recall (absent without any dynamic object, or without any
  // countable moving actor), and lidar_objects.dynamic_per_frame (mean count).
  void Report(std::map<std::string, double>& metrics) const;

  const eval::DetectionCounts& counts() const { return accumulator_.counts(); }

 private:
  Pose2 world_from_odom_;
  eval::DetectionMatchOptions options_;
  eval::DetectionAccumulator accumulator_;
  std::int64_t frames_ = 0;
};

}  // namespace lookout::app
