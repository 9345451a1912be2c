#pragma once

// Scores lidar objects against people annotated by hand on a real log (the leg_tracker
// benchmark bag: io/replay_log.h's PeopleFrame): of the annotated person positions, the share
// with a lidar object within match_distance_m, counting dynamic objects only (what the lidar
// chain calls moving) and, beside it, any object (so that a miss of the detection and a miss of
// the moving/static call can be told apart). An object's point is its centroid, the middle of
// its cells or points, as the annotator clicked the middle of a person.
//
// Frames: both are in the vehicle frame at the scan's stamp (the annotations were brought there
// through the tf tree by the reader), so no ego pose enters the comparison.
//
// The benchmark's own evaluation (leg_tracker_benchmarks' clear_mot.py) counts only people
// between -80 and +12 deg of bearing in the laser frame, where its annotators marked everyone
// (their field of view); the `sector` figures repeat the shares over that sector.
//
// Tracks (PeopleTrackingScorer) are scored as that evaluation scores its trackers: CLEAR MOT
// with a match within 0.75 m, people and tracks in the sector only, every scan from the first
// annotated one to the last a frame (a scan without annotations has no person to match, so its
// tracks in the sector are false positives), so that MOTA and MOTP stand beside Leigh et al.'s
// published figures (ICRA 2015, Table III).

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/eval/tracking_metrics.h"
#include "lookout/io/replay_log.h"
#include "lookout/tracking/tracker.h"

namespace lookout::app {

struct PeopleScoringOptions {
  double match_distance_m = 0.5;
  // The bearing sector of the benchmark's evaluation, in the scan's frame.
  double sector_min_rad = DegToRad(-80.0);
  double sector_max_rad = DegToRad(12.0);
  double track_match_distance_m = 0.75;  // clear_mot.py's max_match_threshold
};

class PeopleScorer {
 public:
  // `prefix` names the objects' source in the metric keys ("people.grid").
  explicit PeopleScorer(std::string prefix, const PeopleScoringOptions& options = {});

  // The annotations of one scan and that scan's objects (nullptr when the pipeline had none for
  // it: every person of the frame is then missed).
  void Observe(const io::PeopleFrame& people, const Pose2& lidar_mount,
               const LidarObjectFrame* objects);

  // PREFIX.positions (annotated positions scored), PREFIX.dynamic_share and PREFIX.any_share,
  // and the same over the sector: PREFIX.sector_positions, .sector_dynamic_share,
  // .sector_any_share. Absent without any annotated position.
  void Report(std::map<std::string, double>& metrics) const;

 private:
  struct Counts {
    std::int64_t positions = 0;
    std::int64_t near_dynamic = 0;
    std::int64_t near_any = 0;
  };
  std::string prefix_;
  PeopleScoringOptions options_;
  Counts all_;
  Counts sector_;
};

class PeopleTrackingScorer {
 public:
  // `prefix` names the tracker in the metric keys ("people.tracking").
  explicit PeopleTrackingScorer(std::string prefix, const PeopleScoringOptions& options = {});

  // One frame: the scan's annotations (nullptr: none), the lidar's mount, the ego pose at the
  // scan (the vehicle frame in the odometry frame) and the confirmed tracks (odometry frame).
  void Observe(const io::PeopleFrame* people, const Pose2& lidar_mount, const Pose2& ego_pose,
               const std::vector<tracking::Track>& tracks);

  // PREFIX.mota, .motp_m, .id_switches, .false_positives, .misses, ... as
  // eval::TrackingMetricsAccumulator names them; absent without a frame.
  void Report(std::map<std::string, double>& metrics) const;

 private:
  bool InSector(const Pose2& lidar_from_vehicle, const Eigen::Vector2d& vehicle_point) const;

  std::string prefix_;
  PeopleScoringOptions options_;
  eval::TrackingMetricsAccumulator accumulator_;
  std::int64_t frames_ = 0;
};

}  // namespace lookout::app
