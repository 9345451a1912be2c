#pragma once

// Runs one scenario: simulates the sensors, delivers every message to the pipeline in
// timestamp order (the message loop of message_loop.h), records everything with the ground
// truth, scores the stages against it, and measures the run.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lookout/app/message_loop.h"
#include "lookout/app/pipeline.h"
#include "lookout/eval/metrics.h"
#include "lookout/sim/scenario.h"

namespace lookout::app {

struct RunOptions {
  int threads = 1;                             // for the simulator; output does not depend on it
  std::optional<std::string> recording_path;   // none: record nothing
  // Called after each lidar cycle with the simulated time and the scenario's duration.
  std::function<void(double t_s, double duration_s)> progress;
  // Write PNG images of the grid (occupancy, speed map, class map) at the first lidar cycle at or
  // after this time, into snapshot_dir.
  std::optional<double> snapshot_s;
  std::string snapshot_dir = ".";
  // The speed map's brightness saturates at this speed (io::SpeedMapOptions): 20 m/s shows
  // cars, a few m/s shows pedestrians.
  double snapshot_max_speed_mps = 20.0;
};

struct RunResult {
  std::string scenario;
  double simulated_s = 0.0;
  std::int64_t lidar_frames = 0;
  std::int64_t stereo_frames = 0;
  std::int64_t odometry_frames = 0;
  std::map<std::string, std::uint64_t> messages_per_topic;  // as recorded
  // The whole run, less what only the ground truth needs (its scoring and recording).
  double wall_s = 0.0;
  double simulation_wall_s = 0.0;  // of which simulating the sensors
  eval::ScenarioMetrics metrics;   // the keys of docs/cli-contract.md that have run
  // Ground truth: actors whose footprint touches the ego's, and when (scenario time, s).
  std::vector<std::pair<std::string, double>> contacts;
  std::vector<std::string> snapshots;  // PNG files written
  // The risk stage's warning events (level changes, each naming its object and TTC), and the
  // class of each event's object as tracked.
  std::vector<risk::WarningEvent> warnings;
  std::vector<ObjectClass> warning_classes;
  // Degradations the stages logged (refused frames, dropped objects), the first few of them,
  // and how many there were.
  std::vector<std::string> stage_warnings;
  std::int64_t stage_warning_count = 0;
};

RunResult RunScenario(const sim::Scenario& scenario, Pipeline& pipeline, const RunOptions& options);

// `options` with what a scenario's sensor block says that the stages assume: the camera's field
// of view and depth, inside which the tracking stage counts the camera's silence against a
// lidar-only object (DetectionOptions). Pure.
PipelineOptions ForSensors(PipelineOptions options, const sim::Sensors& sensors);

// The carriageways of a scenario's world as the ego's map holds them, in the frame that
// `frame_from_world` maps the world into: the four_way preset's two roads (sim/world_builder.h);
// none for empty ground. Pure.
risk::Carriageways CarriagewaysOf(const sim::World& world, const Pose2& frame_from_world);

}  // namespace lookout::app
