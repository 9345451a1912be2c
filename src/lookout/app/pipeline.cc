#include "lookout/app/pipeline.h"

#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::app {

void PipelineOptions::Validate() const {
  if (ego_pose == EgoPoseMode::kLidarLocalisation && grid && !lidar_chain) {
    throw InputError("pipeline options", 0, "ego_pose",
                     "lidar localisation needs the lidar chain (lidar_chain = true)");
  }
  if (lidar_objects == LidarObjectSource::kSegmentation && !lidar_chain) {
    throw InputError("pipeline options", 0, "lidar_objects",
                     "segmentation objects need the lidar chain (lidar_chain = true)");
  }
  if (lidar_objects == LidarObjectSource::kGrid && fusion && !grid) {
    throw InputError("pipeline options", 0, "lidar_objects",
                     "grid objects need the grid (grid = true)");
  }
}

Pipeline::Pipeline(const PipelineOptions& options) : object_source_(options.lidar_objects) {
  options.Validate();
  // The chain runs first on every scan: the grid may ask it for the scan's pose.
  if (options.lidar_chain) {
    auto chain = std::make_unique<LidarChainStage>(options.lidar_chain_options);
    lidar_chain_ = chain.get();
    stages_.push_back(std::move(chain));
  }
  if (options.grid) {
    const EgoPoseSource* source = options.ego_pose == EgoPoseMode::kLidarLocalisation
                                      ? &lidar_chain_->localisation()
                                      : nullptr;
    auto grid = std::make_unique<GridStage>(grid::GridOptions{}, options.grid_filter,
                                            options.grid_objects, source, options.stereo_class);
    grid_ = grid.get();
    stages_.push_back(std::move(grid));
  }
  if (options.fusion && lidar_objects_available()) {
    fusion_.emplace(options.fusion_options);
    if (options.tracking) {
      tracking_.emplace(options.tracking_options);
      if (options.risk) risk_.emplace(options.risk_options);
    }
  }
}

bool Pipeline::lidar_objects_available() const {
  return object_source_ == LidarObjectSource::kGrid ? grid_ != nullptr : lidar_chain_ != nullptr;
}

const LidarObjectFrame* Pipeline::lidar_objects() const {
  if (object_source_ == LidarObjectSource::kSegmentation) {
    if (!lidar_chain_ || !lidar_chain_->last_objects()) return nullptr;
    return &*lidar_chain_->last_objects();
  }
  if (!grid_ || !grid_->last_objects()) return nullptr;
  return &*grid_->last_objects();
}

void Pipeline::SetEgoRoute(std::vector<Eigen::Vector2d> route_m) {
  if (risk_) risk_->SetRoute(std::move(route_m));
}

void Pipeline::SetCarriageways(risk::Carriageways roads_m) {
  if (risk_) risk_->SetCarriageways(std::move(roads_m));
}

void Pipeline::SetBuildings(BuildingOutlines buildings_m) {
  if (tracking_) tracking_->SetBuildings(std::move(buildings_m));
}

void Pipeline::OnOdometry(const EgoOdometry& odometry) {
  for (const auto& stage : stages_) stage->OnOdometry(odometry);
  if (risk_) risk_->OnOdometry(odometry);
}

void Pipeline::OnStereo(const StereoFrame& frame) {
  for (const auto& stage : stages_) stage->OnStereo(frame);
  latest_stereo_ = frame;
  stereo_received_ = true;
}

void Pipeline::OnLidar(const LidarScan& scan) {
  for (const auto& stage : stages_) stage->OnLidar(scan);
  // Fusion closes the cycle: this scan's lidar objects with the newest stereo frame (the
  // engine brings it to the scan's time). A scan the source skipped has no objects to fuse.
  const LidarObjectFrame* objects = lidar_objects();
  if (fusion_ && objects && objects->stamp == scan.stamp) {
    fused_ = fusion_->Fuse(*objects, latest_stereo_);
    // Tracks in the odometry frame, then the risk they pose to the ego at this stamp. The
    // camera's silence counts against lidar-only objects only when its latest frame is recent
    // enough for fusion (an empty frame too: the camera saw nothing), not when it has stopped.
    if (tracking_) {
      std::optional<Pose2> camera;
      if (stereo_received_ && std::abs(ToSeconds(scan.stamp - latest_stereo_.stamp)) <=
                                  fusion_->options().max_stereo_age_s) {
        camera = latest_stereo_.mount;
      }
      tracking_->Step(*fused_, camera, &scan);
      if (risk_ && tracking_->last_stamp() == fused_->stamp) {
        risk_->Step(fused_->stamp, fused_->ego_pose, tracking_->tracks());
      }
    }
  }
}

}  // namespace lookout::app
