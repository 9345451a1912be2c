#pragma once

// The processing stages and how messages reach them. The runner (runner.h) owns the clock and
// calls the pipeline with every sensor message in timestamp order; each stage sees each
// message at its own sensor's rate. A lidar scan closes a cycle: the stages that run per scan
// (grid, objects, fusion, tracking, risk, as they land) run then, and the runner times that
// whole step.

#include <memory>
#include <vector>

#include "lookout/core/messages.h"

namespace lookout::app {

// One processing stage, as the pipeline sees it. Stages keep their own state; a stage never
// reaches into another's.
class Stage {
 public:
  virtual ~Stage() = default;
  virtual void OnOdometry(const EgoOdometry& /*odometry*/) {}
  virtual void OnStereo(const StereoFrame& /*frame*/) {}
  virtual void OnLidar(const LidarScan& /*scan*/) {}
};

class Pipeline {
 public:
  void Add(std::unique_ptr<Stage> stage) { stages_.push_back(std::move(stage)); }
  std::size_t size() const { return stages_.size(); }

  void OnOdometry(const EgoOdometry& odometry);
  void OnStereo(const StereoFrame& frame);
  void OnLidar(const LidarScan& scan);

 private:
  std::vector<std::unique_ptr<Stage>> stages_;
};

}  // namespace lookout::app
