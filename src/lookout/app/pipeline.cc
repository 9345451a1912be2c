#include "lookout/app/pipeline.h"

namespace lookout::app {

Pipeline::Pipeline(const PipelineOptions& options) {
  if (options.grid) {
    auto grid = std::make_unique<GridStage>(grid::GridOptions{}, grid::FilterOptions{},
                                            options.grid_objects);
    grid_ = grid.get();
    stages_.push_back(std::move(grid));
    if (options.fusion) {
      fusion_.emplace(options.fusion_options);
      if (options.tracking) {
        tracking_.emplace(options.tracking_options);
        if (options.risk) risk_.emplace(options.risk_options);
      }
    }
  }
}

const LidarObjectFrame* Pipeline::lidar_objects() const {
  if (!grid_ || !grid_->last_objects()) return nullptr;
  return &*grid_->last_objects();
}

void Pipeline::SetEgoRoute(std::vector<Eigen::Vector2d> route_m) {
  if (risk_) risk_->SetRoute(std::move(route_m));
}

void Pipeline::OnOdometry(const EgoOdometry& odometry) {
  for (const auto& stage : stages_) stage->OnOdometry(odometry);
  if (risk_) risk_->OnOdometry(odometry);
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
    // Tracks in the odometry frame, then the risk they pose to the ego at this stamp.
    if (tracking_) {
      tracking_->Step(*fused_);
      if (risk_ && tracking_->last_stamp() == fused_->stamp) {
        risk_->Step(fused_->stamp, fused_->ego_pose, tracking_->tracks());
      }
    }
  }
}

}  // namespace lookout::app
