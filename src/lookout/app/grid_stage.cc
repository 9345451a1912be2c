#include "lookout/app/grid_stage.h"

#include <chrono>

namespace lookout::app {
namespace {

// The first scan has no predecessor. Its grid holds only priors, so nothing moves and the step
// only scales the (empty) prediction: any positive value does; this is a lidar period.
constexpr double kFirstCycleDt_s = 0.08;

}  // namespace

GridStage::GridStage(const grid::GridOptions& grid_options,
                     const grid::FilterOptions& filter_options,
                     const grid::GridObjectOptions& object_options,
                     const EgoPoseSource* pose_source)
    : options_(grid_options),
      object_options_(object_options),
      pose_source_(pose_source ? pose_source : &ego_),
      grid_(grid::ScrollingGridGeometry(grid_options), filter_options),
      measurement_{grid::ScrollingGridGeometry(grid_options), 0, {}, {}, {}} {
  object_options_.Validate();
}

void GridStage::OnOdometry(const EgoOdometry& odometry) { ego_.Add(odometry); }

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
