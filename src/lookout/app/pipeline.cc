#include "lookout/app/pipeline.h"

namespace lookout::app {

Pipeline::Pipeline(const PipelineOptions& options) {
  if (options.grid) {
    auto grid = std::make_unique<GridStage>(grid::GridOptions{}, grid::FilterOptions{},
                                            options.grid_objects);
    grid_ = grid.get();
    stages_.push_back(std::move(grid));
    if (options.fusion) fusion_.emplace(options.fusion_options);
  }
}

const LidarObjectFrame* Pipeline::lidar_objects() const {
  if (!grid_ || !grid_->last_objects()) return nullptr;
  return &*grid_->last_objects();
}

void Pipeline::OnOdometry(const EgoOdometry& odometry) {
  for (const auto& stage : stages_) stage->OnOdometry(odometry);
}

void Pipeline::OnStereo(const StereoFrame& frame) {
  for (const auto& stage : stages_) stage->OnStereo(frame);
  latest_stereo_ = frame;
}

void Pipeline::OnLidar(const LidarScan& scan) {
  for (const auto& stage : stages_) stage->OnLidar(scan);
  // Fusion closes the cycle: this scan's lidar objects with the newest stereo frame (the
  // engine brings it to the scan's time). A scan the grid skipped has no objects to fuse.
  const LidarObjectFrame* objects = lidar_objects();
  if (fusion_ && objects && objects->stamp == scan.stamp) {
    fused_ = fusion_->Fuse(*objects, latest_stereo_);
  }
}

}  // namespace lookout::app
