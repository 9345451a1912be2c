#include "lookout/app/message_loop.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "lookout/app/grid_recording.h"

namespace lookout::app {

MessageLoopResult RunMessageLoop(const SensorStreams& streams, Pipeline& pipeline,
                                 const MessageLoopOptions& options) {
  MessageLoopResult result;
  result.step_ms.reserve(streams.lidar.size());
  io::Recorder* const recorder = options.recorder;

  std::size_t next_odometry = 0, next_stereo = 0, next_lidar = 0;
  auto key = [](TimeNs stamp, SensorOrder order) { return std::make_pair(stamp, order); };
  constexpr auto kNone = std::make_pair(std::numeric_limits<TimeNs>::max(), SensorOrder::kLidar);
  const std::size_t n_odometry = streams.odometry.size();
  const std::size_t n_stereo = streams.stereo.size();
  const std::size_t n_lidar = streams.lidar.size();
  while (next_odometry < n_odometry || next_stereo < n_stereo || next_lidar < n_lidar) {
    const auto odometry = next_odometry < n_odometry
                              ? key(streams.odometry[next_odometry].stamp, SensorOrder::kOdometry)
                              : kNone;
    const auto stereo = next_stereo < n_stereo
                            ? key(streams.stereo[next_stereo].stamp, SensorOrder::kStereo)
                            : kNone;
    const auto lidar =
        next_lidar < n_lidar ? key(streams.lidar[next_lidar].stamp, SensorOrder::kLidar) : kNone;
    const auto first = std::min({odometry, stereo, lidar});
    if (next_odometry < n_odometry && first == odometry) {
      const EgoOdometry& o = streams.odometry[next_odometry++];
      pipeline.OnOdometry(o);
      if (recorder) recorder->Write(o);
    } else if (next_stereo < n_stereo && first == stereo) {
      const StereoFrame& f = streams.stereo[next_stereo++];
      pipeline.OnStereo(f);
      if (recorder) recorder->Write(f);
    } else {
      const std::size_t k = next_lidar++;
      const LidarScan& scan = streams.lidar[k];
      const WallClock::time_point step_start = WallClock::now();
      pipeline.OnLidar(scan);
      result.step_ms.push_back(1e3 * SecondsSince(step_start));
      // This scan's objects; none when their source had to skip it (no ego pose).
      const LidarObjectFrame* objects = pipeline.lidar_objects();
      if (objects && objects->stamp != scan.stamp) objects = nullptr;
      if (recorder) {
        recorder->Write(scan);
        if (objects) recorder->Write(*objects);
        // The tracks and the risk step of this cycle, and a change of warning level.
        const TrackingStage* tracking = pipeline.tracking();
        if (tracking && tracking->last_stamp() == scan.stamp) {
          recorder->Write(scan.stamp, tracking->tracks());
        }
        const RiskStage* risk = pipeline.risk();
        if (risk && risk->last_stamp() == scan.stamp) {
          recorder->Write(scan.stamp, risk->last_ego(), risk->last_assessment(), risk->level());
          if (!risk->events().empty() && risk->events().back().stamp == scan.stamp) {
            recorder->Write(risk->events().back());
          }
        }
        if (pipeline.grid() && k % kRecordGridEvery == 0) {
          const grid::ExtendedGrid& g = pipeline.grid()->grid();
          recorder->WriteGrid(scan.stamp, g.geometry().WindowGeometry(), GridLayersToRecord(g));
        }
      }
      if (options.after_cycle) {
        const WallClock::time_point callback_start = WallClock::now();
        options.after_cycle(LidarCycle{k, &scan, objects});
        result.after_cycle_s += SecondsSince(callback_start);
      }
    }
  }
  if (recorder) {
    result.messages_per_topic = recorder->message_counts();
    recorder->Finish();
  }
  return result;
}

}  // namespace lookout::app
