#pragma once

// The extended grid as a pipeline stage: the ego pose comes through the EgoPoseSource
// interface (its own dead reckoning of the odometry, or the lidar chain's localisation), and
// each lidar scan runs
// one cycle: scroll the window to the ego, compute the inverse sensor model, update the filter
// (docs/extended-grid.md steps 1-8), and take the rigid clusters of dynamic cells out of the
// grid as lidar objects (grid/grid_objects.h). The newest stereo frame not yet used, when
// there is one within max_stereo_age_s of the scan, gives the cycle's class step the camera's
// classes (app/stereo_class_evidence.h): one frame per cycle, since the camera's reports of one
// tracked object in frames 50 ms apart are not independent evidence.
//
// Why the objects come out of this stage rather than a stage of their own: they are a reading
// of the grid's state right after its cycle, in the vehicle frame at the scan's ego pose, and
// only this stage holds both the grid and that pose; a separate stage would have to reach into
// this one's internals (stage.h forbids it) or be handed a copy of a 400 x 400 x 18-layer state.

#include <cstdint>
#include <optional>
#include <vector>

#include "lookout/app/stage.h"
#include "lookout/app/stereo_class_evidence.h"
#include "lookout/core/dead_reckoning.h"
#include "lookout/grid/extended_grid.h"
#include "lookout/grid/grid_objects.h"
#include "lookout/grid/grid_options.h"
#include "lookout/grid/inverse_sensor_model.h"

namespace lookout::app {

class GridStage : public Stage {
 public:
  // Validates the options (lookout::InputError). `pose_source`: where the ego pose of each
  // scan comes from (the lidar chain's localisation, which must outlive this stage and have
  // seen the scan first); nullptr: the stage's own dead reckoning of the odometry.
  explicit GridStage(const grid::GridOptions& grid_options = {},
                     const grid::FilterOptions& filter_options = {},
                     const grid::GridObjectOptions& object_options = {},
                     const EgoPoseSource* pose_source = nullptr,
                     const StereoClassEvidenceOptions& stereo_class = {});

  void OnOdometry(const EgoOdometry& odometry) override;
  void OnStereo(const StereoFrame& frame) override;
  void OnLidar(const LidarScan& scan) override;

  const grid::ExtendedGrid& grid() const { return grid_; }
  // Where the stage takes its ego pose from.
  const EgoPoseSource& pose_source() const { return *pose_source_; }
  // The lidar's pose in the odometry frame at the last cycle; nullopt before the first.
  const std::optional<Pose2>& last_sensor_pose() const { return last_sensor_pose_; }
  // The measurement grid of the last cycle, in the grid's window of that cycle.
  const grid::MeasurementGrid& last_measurement() const { return measurement_; }
  // Wall time of each grid cycle (ISM and filter), ms.
  const std::vector<double>& cycle_ms() const { return cycle_ms_; }
  // The objects of the last cycle (vehicle frame, stamped with its scan); nullopt before the
  // first cycle.
  const std::optional<LidarObjectFrame>& last_objects() const { return last_objects_; }
  // Wall time of each object extraction, ms (not part of cycle_ms).
  const std::vector<double>& objects_ms() const { return objects_ms_; }
  // Scans that could not be used: no ego pose for their time (odometry missing or stopped).
  std::int64_t skipped_scans() const { return skipped_scans_; }
  // The camera's class evidence: stereo frames given to a cycle, the regions they made, and
  // the stereo objects dropped as unusable (stereo/stereo_validation.h).
  struct StereoClassStats {
    std::int64_t frames_used = 0;
    std::int64_t regions = 0;
    std::int64_t objects_dropped = 0;
  };
  const StereoClassStats& stereo_class_stats() const { return stereo_class_stats_; }
  // The regions given to the last cycle (odometry frame), for tests and display.
  const std::vector<grid::StereoClassRegion>& last_stereo_regions() const {
    return last_stereo_regions_;
  }

 private:
  grid::GridOptions options_;
  grid::GridObjectOptions object_options_;
  DeadReckoning ego_;
  const EgoPoseSource* pose_source_;  // &ego_ unless the constructor was given another
  grid::ExtendedGrid grid_;
  grid::MeasurementGrid measurement_;
  std::optional<TimeNs> last_stamp_;
  std::optional<Pose2> last_sensor_pose_;
  std::vector<double> cycle_ms_;
  std::optional<LidarObjectFrame> last_objects_;
  std::vector<double> objects_ms_;
  std::int64_t skipped_scans_ = 0;
  StereoClassEvidenceOptions stereo_class_options_;
  std::optional<StereoFrame> pending_stereo_;  // the newest frame no cycle has used
  StereoClassStats stereo_class_stats_;
  std::vector<grid::StereoClassRegion> last_stereo_regions_;

  // The camera's regions for the scan at `scan` (empty without a usable frame).
  std::vector<grid::StereoClassRegion> TakeStereoRegions(const LidarScan& scan);
};

}  // namespace lookout::app
