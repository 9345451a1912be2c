#pragma once

// The one message loop of every run, simulated (runner.h) or replayed from a recorded log
// (replay.h): the sensor streams merged into timestamp order, each message handed to the
// pipeline and to the recording, each lidar cycle timed. What differs between the two (the
// ground truth, its scoring and recording, snapshots, progress) comes in through the
// after-cycle callback, whose time is not the pipeline's.
//
// Order. Messages are delivered by (stamp, SensorOrder): at one stamp odometry first (the
// newest ego motion before anything uses it), then stereo, then the lidar scan that closes the
// cycle. Within one stream, messages keep their order; a stream must not go back in time (the
// importers drop or refuse such messages before they get here), otherwise the merge is still
// total and deterministic, but a late message is delivered where its stream's order puts it.
//
// Recording, when a recorder is given: every message as it is delivered; after each lidar
// cycle, this scan's lidar objects, the tracks and the risk step when they ran, a warning event
// when the level changed, and the grid's belief at every kRecordGridEvery-th scan. After the
// last message the recording is finished (io::Recorder::Finish): the loop is all a run records.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "lookout/app/pipeline.h"
#include "lookout/core/messages.h"
#include "lookout/io/recorder.h"

namespace lookout::app {

// Wall time of the runs and their parts.
using WallClock = std::chrono::steady_clock;
inline double SecondsSince(WallClock::time_point start) {
  return std::chrono::duration<double>(WallClock::now() - start).count();
}

// The order in which messages with equal timestamps reach the pipeline.
enum class SensorOrder { kOdometry = 0, kStereo = 1, kLidar = 2 };

// The grid is recorded at a fifth of the lidar rate (2.5 Hz at 12.5 Hz): 400 x 400 cells a
// frame, enough to watch it in Foxglove without making the recording ten times larger.
inline constexpr std::size_t kRecordGridEvery = 5;

struct SensorStreams {
  std::span<const LidarScan> lidar;
  std::span<const StereoFrame> stereo;
  std::span<const EgoOdometry> odometry;
};

// One lidar cycle, as the after-cycle callback sees it.
struct LidarCycle {
  std::size_t index = 0;  // of the scan in SensorStreams::lidar
  const LidarScan* scan = nullptr;
  // This scan's lidar objects, or nullptr when their source had to skip the scan (no ego pose).
  const LidarObjectFrame* objects = nullptr;
};

struct MessageLoopOptions {
  io::Recorder* recorder = nullptr;  // none: nothing recorded; finished after the last message
  // After each lidar cycle and its recording: scoring, truth, snapshots, progress.
  std::function<void(const LidarCycle&)> after_cycle;
};

struct MessageLoopResult {
  std::vector<double> step_ms;  // wall time of the pipeline's step, one per lidar scan
  double after_cycle_s = 0.0;   // wall time spent in the callback
  std::map<std::string, std::uint64_t> messages_per_topic;  // as recorded; none without a recorder
};

MessageLoopResult RunMessageLoop(const SensorStreams& streams, Pipeline& pipeline,
                                 const MessageLoopOptions& options);

}  // namespace lookout::app
