#include "lookout/app/grid_stage.h"

#include <chrono>
#include <cmath>

namespace lookout::app {
namespace {

// The first scan has no predecessor. Its grid holds only priors, so nothing moves and the step
// only scales the (empty) prediction: any positive value does; this is a lidar period.
constexpr double kFirstCycleDt_s = 0.08;

}  // namespace

GridStage::GridStage(const grid::GridOptions& grid_options,
                     const grid::FilterOptions& filter_options,
                     const grid::GridObjectOptions& object_options,
                     const EgoPoseSource* pose_source,
                     const StereoClassEvidenceOptions& stereo_class)
    : options_(grid_options),
      object_options_(object_options),
      pose_source_(pose_source ? pose_source : &ego_),
      grid_(grid::ScrollingGridGeometry(grid_options), filter_options),
      measurement_{grid::ScrollingGridGeometry(grid_options), 0, {}, {}, {}},
      stereo_class_options_(stereo_class) {
  object_options_.Validate();
  stereo_class_options_.Validate();
}

void GridStage::OnOdometry(const EgoOdometry& odometry) { ego_.Add(odometry); }

void GridStage::OnStereo(const StereoFrame& frame) {
  if (stereo_class_options_.enabled) pending_stereo_ = frame;
}

std::vector<grid::StereoClassRegion> GridStage::TakeStereoRegions(const LidarScan& scan) {
  if (!pending_stereo_) return {};
  const StereoFrame frame = std::move(*pending_stereo_);
  pending_stereo_.reset();
  const double dt_s = ToSeconds(scan.stamp - frame.stamp);
  if (std::abs(dt_s) > stereo_class_options_.max_stereo_age_s) return {};
  const std::optional<EgoState> ego = pose_source_->PoseAt(frame.stamp);
  if (!ego) return {};
  const stereo::ProjectedStereoFrame projected =
      stereo::ProjectStereoFrame(frame, scan.mount, stereo_class_options_.stereo);
  std::vector<grid::StereoClassRegion> regions =
      StereoClassRegions(projected, ego->pose, dt_s, stereo_class_options_);
  ++stereo_class_stats_.frames_used;
  stereo_class_stats_.regions += static_cast<std::int64_t>(regions.size());
  stereo_class_stats_.objects_dropped += static_cast<std::int64_t>(projected.drops.size());
  return regions;
}

void GridStage::OnLidar(const LidarScan& scan) {
  const std::optional<EgoState> ego = pose_source_->PoseAt(scan.stamp);
  // A scan from before the previous one, or at its time, has nothing to add: dt must be > 0.
  if (!ego || (last_stamp_ && scan.stamp <= *last_stamp_)) {
    ++skipped_scans_;
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  const Pose2 sensor_pose = ego->pose * scan.mount;
  grid_.Recenter(ego->pose.translation);
  grid::ComputeInverseSensorModel(scan, sensor_pose, grid_.geometry(),
                                  options_.inverse_sensor_model, measurement_);
  const double dt_s = last_stamp_ ? ToSeconds(scan.stamp - *last_stamp_) : kFirstCycleDt_s;
  last_stereo_regions_ = TakeStereoRegions(scan);
  grid_.SetStereoClassEvidence(last_stereo_regions_);
  grid_.Update(measurement_, dt_s);
  const auto updated = std::chrono::steady_clock::now();
  cycle_ms_.push_back(std::chrono::duration<double, std::milli>(updated - start).count());

  grid::ObjectFrameContext context;
  context.stamp = scan.stamp;
  context.ego_pose = ego->pose;
  context.lidar_mount = scan.mount;
  context.dt_s = dt_s;
  last_objects_ = grid::ExtractGridObjects(grid_, context, object_options_);
  const auto extracted = std::chrono::steady_clock::now();
  objects_ms_.push_back(std::chrono::duration<double, std::milli>(extracted - updated).count());
  last_stamp_ = scan.stamp;
  last_sensor_pose_ = sensor_pose;
}

}  // namespace lookout::app
