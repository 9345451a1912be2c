#pragma once

// `lookout slam LOG [--trajectory FILE] [--map FILE.png] [--odometry-only]`
// (docs/cli-contract.md): localisation and local mapping of the lidar chain on a recorded
// CARMEN log. The log's reference poses are read only to score the result (the summary's ATE
// line); the localisation sees the raw odometry and the scans alone.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lookout/eval/relation_error.h"
#include "lookout/eval/trajectory_error.h"
#include "lookout/io/carmen_log.h"
#include "lookout/io/png_writer.h"
#include "lookout/lidar/local_map.h"
#include "lookout/lidar/slam.h"

namespace lookout::app {

struct SlamCommandOptions {
  std::string log_path;
  std::string trajectory_path;  // empty: not written
  std::string map_path;         // empty: not written; must end in .png
  bool odometry_only = false;
  std::uint64_t seed = lidar::ParticleFilterOptions{}.seed;  // of the particle filter
};

// The localisation options `lookout slam` runs CARMEN logs with: robot logs, so the
// differential-drive motion model.
lidar::SlamOptions CarmenSlamOptions();

// The records the localisation may see: time, raw odometry and scan (no reference pose).
std::vector<lidar::SlamRecord> SlamRecordsOf(const io::CarmenLog& log);

// The estimate and the log's reference pose at each scan that has both, in scan order.
struct ScanPairs {
  std::vector<Pose2> estimate;
  std::vector<Pose2> reference;
};
ScanPairs PairsAtScans(const io::CarmenLog& log, const lidar::SlamResult& result);

// The estimate at each scan against the log's reference pose there (the corrected poses of the
// Radish logs): ATE after a rigid alignment (eval/trajectory_error.h). `matched` 0 when fewer
// than two scans pair up.
eval::AbsoluteTrajectoryError ReferenceError(const io::CarmenLog& log,
                                             const lidar::SlamResult& result);

// The relation error of Kuemmerle et al. (eval/relation_error.h) of the estimate at each scan,
// relations between each scan and the first scan at least `min_travel_m` further along the
// reference path, as the dead-reckoning baseline of docs/carmen.md has them. Scans are paired
// by their order: five of the Radish logs have no usable time base. `used` 0 when fewer than
// two scans pair up.
eval::RelationError ReferenceRelationError(const io::CarmenLog& log,
                                           const lidar::SlamResult& result,
                                           double min_travel_m = 10.0);

// The map as a picture: white free, black occupied, grey unknown (gray level 255 (1 - p)),
// north up, one pixel per cell.
io::Image8 MapImage(const lidar::MapRaster& map);

// Runs the command: checks every input first (lookout::InputError: nothing is written), then
// localises, writes the files and prints a summary on stdout. Returns the exit code.
int RunSlamCommand(const SlamCommandOptions& options);

}  // namespace lookout::app
