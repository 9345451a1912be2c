#include "lookout/app/runner.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <utility>
#include <vector>

#include "lookout/eval/statistics.h"
#include "lookout/io/recorder.h"
#include "lookout/sim/simulator.h"

namespace lookout::app {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

RunResult RunScenario(const sim::Scenario& scenario, Pipeline& pipeline, const RunOptions& options) {
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

  std::optional<io::Recorder> recorder;
  if (options.recording_path) {
    recorder.emplace(*options.recording_path);
    const sim::LidarOptions& l = scenario.sensors.lidar;
    const sim::StereoOptions& s = scenario.sensors.stereo;
    recorder->WriteStaticWorld(0, simulator.static_world());
    recorder->WriteMounts(0, Pose2(l.x_m, l.y_m, l.yaw_rad), Pose2(s.x_m, s.y_m, s.yaw_rad));
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
      if (recorder) {
        recorder->Write(scan);
        recorder->Write(log.truth[k]);
      }
      if (options.progress) options.progress(ToSeconds(scan.stamp), scenario.duration_s);
    }
  }

  if (recorder) {
    result.messages_per_topic = recorder->message_counts();
    recorder->Finish();
  }
  result.wall_s = SecondsSince(run_start);
  result.metrics.scenario = scenario.name;
  result.metrics.values["timing.frames"] = static_cast<double>(result.lidar_frames);
  result.metrics.values["timing.pipeline_ms_median"] = eval::Median(step_ms);
  result.metrics.values["timing.realtime_factor"] = scenario.duration_s / result.wall_s;
  return result;
}

}  // namespace lookout::app
