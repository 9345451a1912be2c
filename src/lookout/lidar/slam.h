#pragma once

// The slam loop of `lookout slam` as a library function: raw odometry and scans in, the
// trajectory (one pose per record), the per-scan states and the map out. Only the raw
// odometry and the scans go in: a log's reference poses are for scoring and never reach it.

#include <optional>
#include <span>
#include <vector>

#include "lookout/core/ego_state.h"
#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/lidar/local_map.h"
#include "lookout/lidar/slam_options.h"

namespace lookout::lidar {

// One reading of a log: the raw odometry pose at t_s, and a scan taken then, if any.
struct SlamRecord {
  double t_s = 0.0;  // the log's own time base
  Pose2 odometry;
  std::optional<LidarScan> scan;
};

struct TrajectoryPoint {
  double t_s = 0.0;
  Pose2 pose;
};

struct SlamResult {
  // One per record: at a scan, the scan's estimate; between scans, the latest estimate
  // composed with the odometry since (before the first scan, the odometry itself).
  std::vector<TrajectoryPoint> trajectory;
  std::vector<EgoState> scan_states;  // one per scan used
  MapRaster map;
  std::int64_t scans_used = 0;
  std::int64_t records_refused = 0;  // time going backwards or non-finite odometry
};

// With odometry_only, the poses are the raw odometry (the baseline) and the map is built at
// them. Throws lookout::InputError for invalid options.
SlamResult RunSlam(std::span<const SlamRecord> records, const SlamOptions& options,
                   bool odometry_only = false);

}  // namespace lookout::lidar
