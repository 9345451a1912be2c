#pragma once

// The tracking.* keys of docs/cli-contract.md over one run: CLEAR MOT with distance matching
// (2 m), IDF1, and GOSPA (c = 2 m, p = 2, alpha = 2) averaged over frames, from the true
// objects and the tracks of each frame as points in one frame of reference. Which truths count
// and which point of them is compared is the caller's (app/tracking_scoring.h).

#include <map>
#include <string>
#include <vector>

#include "lookout/eval/mot_frame.h"
#include "lookout/eval/ospa.h"
#include "lookout/eval/tracking_evaluator.h"

namespace lookout::eval {

struct TrackingMetricOptions {
  double match_distance_m = 2.0;
  GospaOptions gospa;  // c = 2 m, p = 2, alpha = 2
};

class TrackingMetricsAccumulator {
 public:
  explicit TrackingMetricsAccumulator(const TrackingMetricOptions& options = {});

  // One frame, in time order; ids distinct within the frame.
  void AddFrame(const std::vector<PointObject>& truths, const std::vector<PointObject>& tracks);

  // PREFIX.mota, .motp_m, .idf1, .id_switches, .gospa_m, and beside them .idp, .idr, .recall,
  // .precision, .false_positives, .misses, .fragmentations, .mostly_tracked, .mostly_lost,
  // .truths (distinct), .frames, and GOSPA's mean parts .gospa_localisation_m,
  // .gospa_missed_m, .gospa_false_m (each the root of the mean p-th power part, so that their
  // squares add up to the mean of GOSPA^2). Keys that need a truth or a match are absent
  // without one.
  std::map<std::string, double> Values(const std::string& prefix) const;

  TrackingScores Scores() const { return evaluator_.Scores(); }
  const TrackingMetricOptions& options() const { return options_; }
  double MeanGospa() const;

 private:
  TrackingMetricOptions options_;
  TrackingEvaluator evaluator_;
  std::int64_t frames_ = 0;
  double gospa_sum_ = 0.0;
  double localisation_sum_ = 0.0, missed_sum_ = 0.0, false_sum_ = 0.0;
};

}  // namespace lookout::eval
