#include "lookout/app/pipeline.h"

namespace lookout::app {

Pipeline::Pipeline(const PipelineOptions& options) {
  if (options.grid) {
    auto grid = std::make_unique<GridStage>(grid::GridOptions{}, grid::FilterOptions{},
                                            options.grid_objects);
    grid_ = grid.get();
    stages_.push_back(std::move(grid));
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
}

void Pipeline::OnLidar(const LidarScan& scan) {
  for (const auto& stage : stages_) stage->OnLidar(scan);
}

}  // namespace lookout::app
