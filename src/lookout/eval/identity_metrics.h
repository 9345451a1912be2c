#pragma once

// Identity metrics IDF1, IDP, IDR (Ristani, Solera, Zou, Cucchiara and Tomasi, "Performance
// measures and a data set for multi-target, multi-camera tracking", ECCV 2016 workshops).
// Each truth trajectory is matched to at most one hypothesis trajectory, once for the whole
// sequence, so as to maximise the identity true positives IDTP: the frames in which a matched
// pair is present together and within the match threshold. Unmatched presences are IDFN
// (truth) and IDFP (hypothesis). The global matching is the bipartite assignment of
// py-motmetrics' id_global_assignment, solved by assignment::SolveCompleteAssignment.

#include <cstdint>
#include <map>
#include <utility>

#include "lookout/eval/mot_frame.h"

namespace lookout::eval {

struct IdentityCounts {
  std::int64_t true_positives = 0;   // IDTP
  std::int64_t false_negatives = 0;  // IDFN
  std::int64_t false_positives = 0;  // IDFP

  double Idf1() const;  // 2 IDTP / (2 IDTP + IDFP + IDFN)
  double Idp() const;   // IDTP / (IDTP + IDFP)
  double Idr() const;   // IDTP / (IDTP + IDFN)
};

// Sums of counts: several sequences evaluated together (py-motmetrics' "overall").
IdentityCounts operator+(const IdentityCounts& a, const IdentityCounts& b);

// Feed it the frames of one sequence (any order); Counts() solves the global matching.
class IdentityAccumulator {
 public:
  void AddFrame(const MotFrame& frame);
  IdentityCounts Counts() const;

 private:
  // Ordered maps: the assignment matrix is built in id order, so equal-cost matchings are
  // broken the same way on every run.
  std::map<std::int64_t, std::int64_t> truth_presences_;
  std::map<std::int64_t, std::int64_t> hypothesis_presences_;
  std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t>
      pair_presences_;  // within threshold
};

}  // namespace lookout::eval
