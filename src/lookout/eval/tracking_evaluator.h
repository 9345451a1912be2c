#pragma once

// The tracking metrics of one sequence, fed frame by frame: CLEAR MOT and the identity
// metrics from the same frames. Build each frame with DistanceFrame (points, metres) or
// IouFrame (image boxes); GOSPA (ospa.h) is per frame and needs no history.

#include "lookout/eval/clear_mot.h"
#include "lookout/eval/identity_metrics.h"
#include "lookout/eval/mot_frame.h"

namespace lookout::eval {

struct TrackingScores {
  ClearMotCounts clear;
  IdentityCounts identity;
};

// Several sequences together: the sums of their counts.
TrackingScores operator+(const TrackingScores& a, const TrackingScores& b);

class TrackingEvaluator {
 public:
  // Frames in time order; a frame with nobody in it still counts as a frame.
  void AddFrame(const MotFrame& frame);
  TrackingScores Scores() const;

 private:
  ClearMotAccumulator clear_;
  IdentityAccumulator identity_;
};

}  // namespace lookout::eval
