#pragma once

// The lidar chain of seed 004 section IV as a pipeline stage, on every scan:
//   A. localisation: the particle filter with the car-like motion model localises the scan in
//      the local map (lidar/localiser.h); the odometry it needs is the dead-reckoned wheel
//      odometry (EgoOdometry carries speed and yaw rate, the localiser wants poses);
//   B. moving and static hits: each return against the map as it was (lidar/hit_classification.h),
//      then what the scan pair shows moving where the map cannot tell: returns of the last
//      scan now seen through, a moving segment's returns carried to where it went
//      (lidar/segment_motion.h);
//   C-D. segmentation: the scan's clusters as LidarObjects in the vehicle frame at the scan's
//      stamp (lidar/scan_segmentation.h);
//   then the scan enters the map: the returns of static segments as hits, those of dynamic
//   segments only clearing the space in front of them (LidarChainOptions::map_static_only).
// Its localisation is an EgoPoseSource: the grid takes its ego pose from it when the pipeline
// says so (PipelineOptions::ego_pose). Nothing here knows of the simulator: the same stage
// serves recorded logs.
//
// Bad input: a scan whose stamp is not after the previous accepted one is refused and counted
// (refused_scans); a scan without an odometry pose for its time (odometry missing, stopped, or
// too far behind) is skipped and counted (skipped_scans). Beams that are not returns (NaN,
// infinite, negative, too near) are counted per scan in the hit classes.

#include <cstdint>
#include <optional>
#include <vector>

#include "lookout/app/stage.h"
#include "lookout/core/dead_reckoning.h"
#include "lookout/lidar/hit_classification.h"
#include "lookout/lidar/lidar_chain_options.h"
#include "lookout/lidar/local_map.h"
#include "lookout/lidar/localiser.h"
#include "lookout/lidar/scan_segmentation.h"
#include "lookout/lidar/segment_motion.h"

namespace lookout::app {

class LidarChainStage : public Stage {
 public:
  // Validates the options (lookout::InputError).
  explicit LidarChainStage(const lidar::LidarChainOptions& options = {},
                           const DeadReckoningOptions& odometry = {});

  void OnOdometry(const EgoOdometry& odometry) override;
  void OnLidar(const LidarScan& scan) override;

  // The lidar localisation (in the odometry frame of the dead reckoning, which the first scan
  // fixes) and the dead reckoning it starts from.
  const EgoPoseSource& localisation() const { return localiser_; }
  const EgoPoseSource& dead_reckoning() const { return odometry_; }
  const lidar::LidarLocaliser& localiser() const { return localiser_; }

  // The stamp of the last scan processed, its localised state, the class of each of its beams
  // and its objects; nullopt / empty before the first.
  const std::optional<TimeNs>& last_stamp() const { return last_stamp_; }
  const std::optional<EgoState>& last_state() const { return last_state_; }
  const lidar::ScanHitClasses& last_hits() const { return hits_; }
  const std::optional<LidarObjectFrame>& last_objects() const { return last_objects_; }

  // Wall time per scan, ms: localisation (A), classification and mapping (B), segmentation.
  const std::vector<double>& localise_ms() const { return localise_ms_; }
  const std::vector<double>& hits_ms() const { return hits_ms_; }
  const std::vector<double>& segment_ms() const { return segment_ms_; }

  std::int64_t refused_scans() const { return refused_scans_; }
  std::int64_t skipped_scans() const { return skipped_scans_; }
  std::int64_t no_returns() const { return no_returns_; }  // over every scan processed

 private:
  // `unmapped[i]`: beam i only clears space (its segment is dynamic); empty: none. Into the
  // localiser's map and the far map, at the scan's localised pose.
  void MapScan(const LidarScan& scan, const Pose2& pose, const std::vector<bool>& unmapped);

  lidar::LidarChainOptions options_;
  DeadReckoning odometry_;
  lidar::LidarLocaliser localiser_;
  // Beyond the localiser's map, for the classification of far returns (far_map_enabled).
  std::optional<lidar::LocalMap> far_map_;
  std::optional<TimeNs> last_stamp_;
  std::optional<EgoState> last_state_;
  lidar::ScanHitClasses hits_;
  std::optional<LidarObjectFrame> last_objects_;
  // The last scan's segments, for the next scan's motion cues (lidar/segment_motion.h).
  std::optional<lidar::ScanSegments> previous_segments_;
  std::vector<double> localise_ms_;
  std::vector<double> hits_ms_;
  std::vector<double> segment_ms_;
  std::int64_t refused_scans_ = 0;
  std::int64_t skipped_scans_ = 0;
  std::int64_t no_returns_ = 0;
};

}  // namespace lookout::app
