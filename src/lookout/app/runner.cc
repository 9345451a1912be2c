#include "lookout/app/runner.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <tbb/task_arena.h>

#include "lookout/app/grid_scoring.h"
#include "lookout/app/lidar_object_scoring.h"
#include "lookout/eval/fusion_metrics.h"
#include "lookout/eval/statistics.h"
#include "lookout/io/grid_images.h"
#include "lookout/io/png_writer.h"
#include "lookout/io/recorder.h"
#include "lookout/sim/simulator.h"

namespace lookout::app {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The grid is recorded at a fifth of the lidar rate (2.5 Hz): 400 x 400 cells a frame, enough
// to watch it in Foxglove without making the recording ten times larger.
constexpr std::size_t kRecordGridEvery = 5;

// The grid's belief as the recording's uint8 layers: occupancy x 255, and speed over 0-20 m/s.
std::vector<io::GridLayer8> GridLayersToRecord(const eval::GridBelief& b) {
  std::vector<std::uint8_t> occupancy, speed;
  occupancy.reserve(b.occupancy.size());
  speed.reserve(b.occupancy.size());
  for (std::size_t i = 0; i < b.occupancy.size(); ++i) {
    const double o = std::clamp(static_cast<double>(b.occupancy[i]), 0.0, 1.0);
    const double v = static_cast<double>(std::hypot(b.velocity_x_mps[i], b.velocity_y_mps[i]));
    occupancy.push_back(static_cast<std::uint8_t>(std::lround(255.0 * o)));
    speed.push_back(static_cast<std::uint8_t>(std::lround(255.0 * std::min(v / 20.0, 1.0))));
  }
  return {{"occupancy", std::move(occupancy)}, {"speed", std::move(speed)}};
}

// The grid at one instant as PNG images: occupancy, and the speed map of the paper's Fig. 6
// (hue = direction, brightness = speed).
std::vector<std::string> WriteSnapshot(const grid::ExtendedGrid& grid, const std::string& dir,
                                       TimeNs stamp) {
  const eval::GridBelief b = BeliefOf(grid);
  const std::string stem = fmt::format("{}/snapshot-{:.2f}s", dir, ToSeconds(stamp));
  const std::vector<std::string> files = {stem + "-occupancy.png", stem + "-speed.png"};
  io::WritePng(files[0], io::RenderOccupancy(b.geometry, b.occupancy));
  io::WritePng(files[1], io::RenderSpeedMap(b.geometry, b.velocity_x_mps, b.velocity_y_mps,
                                            b.occupancy, b.velocity_confidence));
  return files;
}

RunResult RunInArena(const sim::Scenario& scenario, Pipeline& pipeline, const RunOptions& options) {
  const Clock::time_point run_start = Clock::now();
  RunResult result;
  result.scenario = scenario.name;
  result.simulated_s = scenario.duration_s;

  const sim::Simulator simulator(scenario);
  for (std::size_t i = 0; i < scenario.actors.size(); ++i) {
    if (const auto& t = simulator.contact_times_s()[i]) {
      result.contacts.emplace_back(scenario.actors[i].id, *t);
    }
  }
  const Clock::time_point sim_start = Clock::now();
  const sim::SensorLog log = simulator.Run(options.threads);
  result.simulation_wall_s = SecondsSince(sim_start);
  result.lidar_frames = static_cast<std::int64_t>(log.lidar.size());
  result.stereo_frames = static_cast<std::int64_t>(log.stereo.size());
  result.odometry_frames = static_cast<std::int64_t>(log.odometry.size());

  // The odometry frame (where the grid lives) is the ego's true pose at the first reading.
  std::optional<GridScorer> grid_scorer;
  std::optional<LidarObjectScorer> object_scorer;
  std::optional<eval::FusionMetricsAccumulator> fusion_scorer;
  if (pipeline.fusion()) fusion_scorer.emplace();
  if (pipeline.grid()) {
    const Pose2 world_from_odom = simulator.ego_trajectory().At(0.0).pose;
    grid_scorer.emplace(world_from_odom, simulator.static_world(),
                        scenario.sensors.lidar.max_range_m);
    object_scorer.emplace(world_from_odom);
  }
  double scoring_s = 0.0;  // not the pipeline's time: excluded from the real-time factor
  bool snapshot_due = options.snapshot_s.has_value() && pipeline.grid() != nullptr;
  const TimeNs snapshot_at = options.snapshot_s ? FromSeconds(*options.snapshot_s) : 0;

  std::optional<io::Recorder> recorder;
  if (options.recording_path) {
    recorder.emplace(*options.recording_path);
    const sim::LidarOptions& l = scenario.sensors.lidar;
    const sim::StereoOptions& s = scenario.sensors.stereo;
    recorder->WriteStaticWorld(0, simulator.static_world());
    recorder->WriteMounts(0, Pose2(l.x_m, l.y_m, l.yaw_rad), Pose2(s.x_m, s.y_m, s.yaw_rad));
    if (pipeline.grid()) {
      recorder->WriteTransform(0, io::frames::kWorld, io::frames::kOdom,
                               simulator.ego_trajectory().At(0.0).pose);
    }
  }

  // The simulated clock: the three sensor streams merged by (stamp, SensorOrder).
  std::size_t next_odometry = 0, next_stereo = 0, next_lidar = 0;
  auto key = [](TimeNs stamp, SensorOrder order) { return std::make_pair(stamp, order); };
  constexpr auto kNone = std::make_pair(std::numeric_limits<TimeNs>::max(), SensorOrder::kLidar);
  std::vector<double> step_ms;
  step_ms.reserve(log.lidar.size());
  while (true) {
    const auto odometry = next_odometry < log.odometry.size()
                              ? key(log.odometry[next_odometry].stamp, SensorOrder::kOdometry)
                              : kNone;
    const auto stereo = next_stereo < log.stereo.size()
                            ? key(log.stereo[next_stereo].stamp, SensorOrder::kStereo)
                            : kNone;
    const auto lidar = next_lidar < log.lidar.size()
                           ? key(log.lidar[next_lidar].stamp, SensorOrder::kLidar)
                           : kNone;
    const auto first = std::min({odometry, stereo, lidar});
    if (first == kNone) break;  // every stream is exhausted
    if (first == odometry) {
      const EgoOdometry& o = log.odometry[next_odometry++];
      pipeline.OnOdometry(o);
      if (recorder) recorder->Write(o);
    } else if (first == stereo) {
      const StereoFrame& f = log.stereo[next_stereo++];
      pipeline.OnStereo(f);
      if (recorder) recorder->Write(f);
    } else {
      const std::size_t k = next_lidar++;
      const LidarScan& scan = log.lidar[k];
      const Clock::time_point step_start = Clock::now();
      pipeline.OnLidar(scan);
      step_ms.push_back(1e3 * SecondsSince(step_start));
      // This scan's objects; none when the grid had to skip it (no ego pose).
      const LidarObjectFrame* objects = pipeline.lidar_objects();
      if (objects && objects->stamp != scan.stamp) objects = nullptr;
      if (grid_scorer) {
        const Clock::time_point scoring_start = Clock::now();
        grid_scorer->Observe(*pipeline.grid(), log.truth[k]);
        if (objects) {
          object_scorer->Observe(*objects, log.truth[k],
                                 pipeline.grid()->grid().geometry().WindowGeometry());
        }
        const fusion::FusedObjectFrame* fused = pipeline.fused_objects();
        if (fusion_scorer && objects && fused && fused->stamp == scan.stamp) {
          fusion_scorer->AddFrame(*fused, *objects, pipeline.fusion()->stereo_at_lidar_time(),
                                  eval::TrueObjectsInVehicleFrame(log.truth[k]));
        }
        scoring_s += SecondsSince(scoring_start);
      }
      if (snapshot_due && scan.stamp >= snapshot_at) {
        result.snapshots = WriteSnapshot(pipeline.grid()->grid(), options.snapshot_dir, scan.stamp);
        snapshot_due = false;
      }
      if (recorder) {
        recorder->Write(scan);
        recorder->Write(log.truth[k]);
        if (objects) recorder->Write(*objects);
        if (pipeline.grid() && k % kRecordGridEvery == 0) {
          const eval::GridBelief belief = BeliefOf(pipeline.grid()->grid());
          recorder->WriteGrid(scan.stamp, belief.geometry, GridLayersToRecord(belief));
        }
      }
      if (options.progress) options.progress(ToSeconds(scan.stamp), scenario.duration_s);
    }
  }

  if (recorder) {
    result.messages_per_topic = recorder->message_counts();
    recorder->Finish();
  }
  result.wall_s = SecondsSince(run_start) - scoring_s;
  result.metrics.scenario = scenario.name;
  result.metrics.values["timing.frames"] = static_cast<double>(result.lidar_frames);
  result.metrics.values["timing.pipeline_ms_median"] = eval::Median(step_ms);
  result.metrics.values["timing.realtime_factor"] = scenario.duration_s / result.wall_s;
  if (grid_scorer) grid_scorer->Report(result.metrics.values, *pipeline.grid());
  if (object_scorer) object_scorer->Report(result.metrics.values);
  if (fusion_scorer) {
    for (const auto& [name, value] : fusion_scorer->Values()) result.metrics.values[name] = value;
  }
  if (pipeline.grid() && !pipeline.grid()->objects_ms().empty()) {
    result.metrics.values["lidar_objects.extract_ms_median"] =
        eval::Median(pipeline.grid()->objects_ms());
  }
  return result;
}

}  // namespace

RunResult RunScenario(const sim::Scenario& scenario, Pipeline& pipeline, const RunOptions& options) {
  // Every parallel loop of the run (simulator and stages) shares this many threads; the
  // output does not depend on the number (each loop writes distinct cells in a fixed order).
  tbb::task_arena arena(options.threads);
  RunResult result;
  arena.execute([&] { result = RunInArena(scenario, pipeline, options); });
  return result;
}

}  // namespace lookout::app
