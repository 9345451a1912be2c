#pragma once

// Scores the grid stage against the simulator's ground truth after every lidar cycle: the
// grid.* keys of docs/cli-contract.md. The grid lives in the odometry frame; the truth is
// brought into it through the ego's true pose at the first odometry reading (the odometry
// frame's origin), so dead-reckoning drift counts as grid error, as it would on a real car.

#include <map>
#include <string>
#include <vector>

#include "lookout/app/grid_stage.h"
#include "lookout/eval/grid_class_metrics.h"
#include "lookout/eval/grid_metrics.h"
#include "lookout/sim/shapes.h"
#include "lookout/sim/truth.h"

namespace lookout::app {

class GridScorer {
 public:
  // `world_from_odom`: the odometry frame in the world (the ego's true pose at t = 0).
  GridScorer(const Pose2& world_from_odom, const std::vector<sim::Shape>& static_world,
             double lidar_max_range_m);

  // After a grid cycle at truth.stamp.
  void Observe(const GridStage& stage, const sim::TruthFrame& truth_world);

  // The grid.* metrics; a key is absent when nothing was there to score (no actor ever hidden).
  void Report(std::map<std::string, double>& metrics, const GridStage& stage) const;

  // The last belief, in window order (for snapshots).
  const eval::GridBelief& last_belief() const { return belief_; }

 private:
  Pose2 odom_from_world_;
  std::vector<sim::Shape> static_world_odom_;
  double lidar_max_range_m_;
  eval::ActorVisibilityClock visibility_;
  eval::VelocityRmseAccumulator velocity_;
  eval::VelocityRmseAccumulator velocity_after_1s_;
  eval::FalseDynamicAccumulator false_dynamic_;
  eval::OccupancyBrierAccumulator brier_;
  eval::OccludedRetentionAccumulator retention_;
  eval::ClassAccuracyAccumulator class_accuracy_;
  eval::GridBelief belief_;
};

// The grid's belief as window-ordered layers, for metrics and images.
eval::GridBelief BeliefOf(const grid::ExtendedGrid& grid);

}  // namespace lookout::app
