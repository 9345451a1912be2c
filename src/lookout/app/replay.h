#pragma once

// Runs the pipeline on a recorded log (io/replay_log.h): the log's messages through the same
// message loop as a simulated run (message_loop.h), recorded, and scored against whatever
// truth the log holds (docs/replay.md):
//   - annotated people (the leg_tracker bag): the share of annotated positions with a lidar
//     object within 0.5 m (people_scoring.h), per object source;
//   - reference poses (CARMEN's corrected poses, a SLAM result): the pipeline's ego pose at
//     each scan against them, as localisation.ate_rmse_m and localisation.heading_rmse_deg,
//     after the rigid alignment `lookout slam` uses (the log's frame and the odometry frame
//     have no known relation).
// Plus timing.* as for a simulated run, with the log's span as its duration, and replay.*
// counts of what the pipeline could not use.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "lookout/app/pipeline.h"
#include "lookout/eval/metrics.h"
#include "lookout/io/replay_log.h"

namespace lookout::app {

struct ReplayOptions {
  int threads = 1;  // for the stages' parallel loops; the output does not depend on it
  std::optional<std::string> recording_path;  // none: record nothing
  // Called after each lidar cycle with the log time and the log's duration.
  std::function<void(double t_s, double duration_s)> progress;
};

struct ReplayResult {
  double duration_s = 0.0;
  std::int64_t lidar_frames = 0;
  std::int64_t stereo_frames = 0;
  std::int64_t odometry_frames = 0;
  std::map<std::string, std::uint64_t> messages_per_topic;  // as recorded
  double wall_s = 0.0;  // the whole run, less the scoring against the log's truth
  eval::ScenarioMetrics metrics;
};

ReplayResult RunReplay(const io::ReplayLog& log, Pipeline& pipeline, const ReplayOptions& options);

}  // namespace lookout::app
