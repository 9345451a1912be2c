#pragma once

// The processing stages and how messages reach them. The runner (runner.h) owns the clock and
// calls the pipeline with every sensor message in timestamp order; each stage sees each
// message at its own sensor's rate. A lidar scan closes a cycle: the stages that run per scan
// (the grid now; objects, fusion, tracking and risk as they land) run then, and the runner
// times that whole step.

#include <memory>
#include <vector>

#include "lookout/app/grid_stage.h"
#include "lookout/app/stage.h"
#include "lookout/core/messages.h"

namespace lookout::app {

struct PipelineOptions {
  bool grid = true;  // the extended grid (docs/extended-grid.md), with its objects
  // How the grid's rigid clusters become lidar objects (grid/grid_objects.h).
  grid::GridObjectOptions grid_objects;
};

class Pipeline {
 public:
  Pipeline() = default;  // no built-in stage: tests assemble their own with Add()
  explicit Pipeline(const PipelineOptions& options);  // the built-in stages the options name

  // Any stage, run after the built-in ones (tests add probes this way).
  void Add(std::unique_ptr<Stage> stage) { stages_.push_back(std::move(stage)); }
  std::size_t size() const { return stages_.size(); }

  // The grid stage, or nullptr when the pipeline runs without it.
  const GridStage* grid() const { return grid_; }
  // The lidar objects of the last cycle (the grid's rigid clusters, vehicle frame), or nullptr
  // before the first cycle or without the grid. Check its stamp: a scan the grid had to skip
  // leaves the previous frame here.
  const LidarObjectFrame* lidar_objects() const;

  void OnOdometry(const EgoOdometry& odometry);
  void OnStereo(const StereoFrame& frame);
  void OnLidar(const LidarScan& scan);

 private:
  std::vector<std::unique_ptr<Stage>> stages_;
  const GridStage* grid_ = nullptr;  // owned by stages_
};

}  // namespace lookout::app
