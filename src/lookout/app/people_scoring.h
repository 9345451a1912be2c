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

#include <cstdint>
#include <map>
#include <string>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/io/replay_log.h"

namespace lookout::app {

struct PeopleScoringOptions {
  double match_distance_m = 0.5;
  // The bearing sector of the benchmark's evaluation, in the scan's frame.
  double sector_min_rad = DegToRad(-80.0);
  double sector_max_rad = DegToRad(12.0);
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

}  // namespace lookout::app
