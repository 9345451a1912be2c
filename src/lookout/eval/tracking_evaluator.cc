#include "lookout/eval/tracking_evaluator.h"

namespace lookout::eval {

TrackingScores operator+(const TrackingScores& a, const TrackingScores& b) {
  return {a.clear + b.clear, a.identity + b.identity};
}

void TrackingEvaluator::AddFrame(const MotFrame& frame) {
  clear_.AddFrame(frame);
  identity_.AddFrame(frame);
}

TrackingScores TrackingEvaluator::Scores() const { return {clear_.Counts(), identity_.Counts()}; }

}  // namespace lookout::eval
