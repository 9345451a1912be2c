#pragma once

#include "lookout/core/messages.h"

namespace lookout::app {

// One processing stage, as the pipeline sees it: each sensor message arrives at its own rate,
// in timestamp order. Stages keep their own state; a stage never reaches into another's.
class Stage {
 public:
  virtual ~Stage() = default;
  virtual void OnOdometry(const EgoOdometry& /*odometry*/) {}
  virtual void OnStereo(const StereoFrame& /*frame*/) {}
  virtual void OnLidar(const LidarScan& /*scan*/) {}
};

}  // namespace lookout::app
