#include "lookout/app/replay.h"

#include <chrono>
#include <optional>
#include <vector>

#include <tbb/task_arena.h>

#include "lookout/app/message_loop.h"
#include "lookout/app/people_scoring.h"
#include "lookout/eval/statistics.h"
#include "lookout/eval/trajectory_error.h"
#include "lookout/io/recorder.h"

namespace lookout::app {
namespace {

ReplayResult RunInArena(const io::ReplayLog& log, Pipeline& pipeline,
                        const ReplayOptions& options) {
  const WallClock::time_point run_start = WallClock::now();
  ReplayResult result;
  result.duration_s = log.duration_s;
  result.lidar_frames = static_cast<std::int64_t>(log.lidar.size());
  result.stereo_frames = static_cast<std::int64_t>(log.stereo.size());
  result.odometry_frames = static_cast<std::int64_t>(log.odometry.size());

  std::optional<io::Recorder> recorder;
  if (options.recording_path) {
    recorder.emplace(*options.recording_path);
    recorder->WriteTransform(0, io::frames::kVehicle, io::frames::kLidar, log.lidar.front().mount);
  }

  // The log's truth, by scan: the people annotated on it, its reference pose.
  std::vector<const io::PeopleFrame*> people_at(log.lidar.size(), nullptr);
  for (const io::PeopleFrame& f : log.people) people_at[f.scan_index] = &f;
  std::size_t next_reference = 0;
  // Each source of lidar objects is scored from its own stage, whichever the pipeline fuses.
  std::optional<PeopleScorer> grid_people, segmentation_people;
  if (!log.people.empty() && pipeline.grid()) grid_people.emplace("people.grid");
  if (!log.people.empty() && pipeline.lidar_chain()) {
    segmentation_people.emplace("people.segmentation");
  }
  // Tracks are scored over the annotated span, every scan of it a frame (people_scoring.h).
  std::optional<PeopleTrackingScorer> people_tracks, people_baseline_tracks;
  const std::size_t first_annotated = log.people.empty() ? 0 : log.people.front().scan_index;
  const std::size_t last_annotated = log.people.empty() ? 0 : log.people.back().scan_index;
  const TrackingStage* const tracking = pipeline.tracking();
  if (!log.people.empty() && tracking != nullptr) {
    people_tracks.emplace("people.tracking");
    if (tracking->baseline() != nullptr) people_baseline_tracks.emplace("people.tracking_baseline");
  }
  std::vector<Pose2> estimate, reference;

  const auto after_cycle = [&](const LidarCycle& cycle) {
    const LidarScan& scan = *cycle.scan;
    // The pipeline's ego pose at the scan, in the odometry frame (the grid's, for now).
    if (cycle.objects && recorder) {
      recorder->WriteTransform(scan.stamp, io::frames::kOdom, io::frames::kVehicle,
                               cycle.objects->ego_pose);
    }
    const io::PeopleFrame* people = people_at[cycle.index];
    if (people && recorder) recorder->Write(*people);
    // A stage that skipped this scan (no ego pose) holds an older frame: none for this scan.
    const auto at_scan = [&](const std::optional<LidarObjectFrame>& frame) {
      return frame && frame->stamp == scan.stamp ? &*frame : nullptr;
    };
    if (people && grid_people) {
      grid_people->Observe(*people, scan.mount, at_scan(pipeline.grid()->last_objects()));
    }
    if (people && segmentation_people) {
      segmentation_people->Observe(*people, scan.mount,
                                   at_scan(pipeline.lidar_chain()->last_objects()));
    }
    if (people_tracks && tracking && cycle.index >= first_annotated &&
        cycle.index <= last_annotated) {
      // A cycle the tracker did not run (no objects) shows no track.
      const bool ran = cycle.objects && tracking->last_stamp() == scan.stamp;
      static const std::vector<tracking::Track> kNone;
      const Pose2 ego = cycle.objects ? cycle.objects->ego_pose : Pose2();
      people_tracks->Observe(people, scan.mount, ego, ran ? tracking->tracks() : kNone);
      if (people_baseline_tracks) {
        people_baseline_tracks->Observe(people, scan.mount, ego,
                                        ran ? tracking->baseline_tracks() : kNone);
      }
    }
    while (next_reference < log.reference.size() &&
           log.reference[next_reference].stamp < scan.stamp) {
      ++next_reference;
    }
    if (cycle.objects && next_reference < log.reference.size() &&
        log.reference[next_reference].stamp == scan.stamp) {
      estimate.push_back(cycle.objects->ego_pose);
      reference.push_back(log.reference[next_reference].pose);
    }
    if (options.progress) options.progress(ToSeconds(scan.stamp), log.duration_s);
  };
  MessageLoopOptions loop_options;
  loop_options.recorder = recorder ? &*recorder : nullptr;
  loop_options.after_cycle = after_cycle;
  const MessageLoopResult loop =
      RunMessageLoop(SensorStreams{log.lidar, log.stereo, log.odometry}, pipeline, loop_options);

  result.messages_per_topic = loop.messages_per_topic;
  // Scoring, the people's and the poses' recording and progress are not the pipeline's time.
  result.wall_s = SecondsSince(run_start) - loop.after_cycle_s;
  std::map<std::string, double>& m = result.metrics.values;
  result.metrics.scenario = log.name;
  m["timing.frames"] = static_cast<double>(result.lidar_frames);
  m["timing.pipeline_ms_median"] = eval::Median(loop.step_ms);
  if (log.duration_s > 0.0) m["timing.realtime_factor"] = log.duration_s / result.wall_s;
  if (pipeline.grid()) {
    m["replay.scans_without_pose"] = static_cast<double>(pipeline.grid()->skipped_scans());
  }
  if (grid_people) grid_people->Report(m);
  if (segmentation_people) segmentation_people->Report(m);
  if (people_tracks) people_tracks->Report(m);
  if (people_baseline_tracks) people_baseline_tracks->Report(m);
  if (estimate.size() >= 2) {
    const eval::AbsoluteTrajectoryError ate = eval::AbsoluteErrorOfPairs(estimate, reference);
    m["localisation.ate_rmse_m"] = ate.ate_rmse_m;
    m["localisation.heading_rmse_deg"] = RadToDeg(ate.heading_rmse_rad);
  }
  return result;
}

}  // namespace

ReplayResult RunReplay(const io::ReplayLog& log, Pipeline& pipeline, const ReplayOptions& options) {
  tbb::task_arena arena(options.threads);
  ReplayResult result;
  arena.execute([&] { result = RunInArena(log, pipeline, options); });
  return result;
}

}  // namespace lookout::app
