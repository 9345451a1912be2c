#pragma once

// CLEAR MOT (Bernardin and Stiefelhagen, "Evaluating multiple object tracking performance:
// the CLEAR MOT metrics", EURASIP JIVP 2008) with the mostly tracked / lost and fragmentation
// counts of Li et al. (CVPR 2009), following py-motmetrics' conventions exactly, so that its
// published values on the MOTChallenge test files are reproduced (docs/tracking-metrics.md):
//
// Per frame, in this order:
//  1. a truth matched before (at any earlier frame) keeps its last hypothesis when that
//     hypothesis is present and the pair is within the threshold;
//  2. the remaining truths and hypotheses are matched by a minimum-cost assignment with the
//     most pairs (assignment::SolveLinearAssignment); a match whose truth was last matched to
//     another hypothesis is an ID switch;
//  3. unmatched truths are misses (FN), unmatched hypotheses false positives (FP).
// Over the sequence: MT / PT / ML from the share of a truth's frames in which it was matched
// (>= 0.8, [0.2, 0.8), < 0.2); a fragmentation each time a matched truth becomes missed and is
// matched again later (py-motmetrics counts the misses between the first and the last match).

#include <cstdint>
#include <unordered_map>

#include "lookout/eval/mot_frame.h"

namespace lookout::eval {

// Counts over one sequence, or summed over several (operator+: the "overall" of
// py-motmetrics, which merges sequences by adding their counts).
struct ClearMotCounts {
  std::int64_t frames = 0;
  std::int64_t truth_objects = 0;      // truth presences summed over frames (GT)
  std::int64_t hypotheses = 0;         // hypothesis presences summed over frames
  std::int64_t matches = 0;            // matched pairs, switches included (TP)
  std::int64_t switches = 0;           // ID switches (IDs)
  std::int64_t false_positives = 0;    // FP
  std::int64_t misses = 0;             // FN
  std::int64_t fragmentations = 0;     // FM
  std::int64_t unique_truths = 0;      // distinct truth ids
  std::int64_t mostly_tracked = 0;     // MT
  std::int64_t partially_tracked = 0;  // PT
  std::int64_t mostly_lost = 0;        // ML
  double distance_sum = 0.0;           // of the matched pairs' distances

  // 1 - (FN + FP + IDs) / GT; NaN without truth.
  double Mota() const;
  // Mean distance over matched pairs; NaN without a match.
  double Motp() const;
  double Recall() const;     // TP / GT
  double Precision() const;  // TP / (TP + FP)
};

ClearMotCounts operator+(const ClearMotCounts& a, const ClearMotCounts& b);

// Feed it the frames of one sequence in time order.
class ClearMotAccumulator {
 public:
  void AddFrame(const MotFrame& frame);
  ClearMotCounts Counts() const;

 private:
  struct TruthHistory {
    std::int64_t frames_present = 0;
    std::int64_t frames_matched = 0;
    std::int64_t last_hypothesis = 0;
    bool ever_matched = false;
    bool matched_last_present = false;  // its latest presence was a match
    bool miss_after_match = false;      // missed since its last match: a fragment if matched again
  };

  ClearMotCounts counts_;
  // Unordered maps for speed; nothing here depends on their iteration order.
  std::unordered_map<std::int64_t, TruthHistory> truths_;
};

}  // namespace lookout::eval
