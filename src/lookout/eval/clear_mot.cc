#include "lookout/eval/clear_mot.h"

#include <cassert>
#include <cmath>
#include <limits>
#include <vector>

#include "lookout/assignment/linear_assignment.h"
#include "lookout/eval/statistics.h"

namespace lookout::eval {

double ClearMotCounts::Mota() const {
  return 1.0 - Ratio(static_cast<double>(misses + false_positives + switches),
                     static_cast<double>(truth_objects));
}
double ClearMotCounts::Motp() const { return Ratio(distance_sum, static_cast<double>(matches)); }
double ClearMotCounts::Recall() const {
  return Ratio(static_cast<double>(matches), static_cast<double>(truth_objects));
}
double ClearMotCounts::Precision() const {
  return Ratio(static_cast<double>(matches), static_cast<double>(matches + false_positives));
}

ClearMotCounts operator+(const ClearMotCounts& a, const ClearMotCounts& b) {
  ClearMotCounts s;
  s.frames = a.frames + b.frames;
  s.truth_objects = a.truth_objects + b.truth_objects;
  s.hypotheses = a.hypotheses + b.hypotheses;
  s.matches = a.matches + b.matches;
  s.switches = a.switches + b.switches;
  s.false_positives = a.false_positives + b.false_positives;
  s.misses = a.misses + b.misses;
  s.fragmentations = a.fragmentations + b.fragmentations;
  s.unique_truths = a.unique_truths + b.unique_truths;
  s.mostly_tracked = a.mostly_tracked + b.mostly_tracked;
  s.partially_tracked = a.partially_tracked + b.partially_tracked;
  s.mostly_lost = a.mostly_lost + b.mostly_lost;
  s.distance_sum = a.distance_sum + b.distance_sum;
  return s;
}

void ClearMotAccumulator::AddFrame(const MotFrame& frame) {
  const std::size_t n_truth = frame.truth_ids.size();
  const std::size_t n_hyp = frame.hypothesis_ids.size();
  assert(frame.distance.rows() == static_cast<Eigen::Index>(n_truth));
  assert(frame.distance.cols() == static_cast<Eigen::Index>(n_hyp));
  ++counts_.frames;
  counts_.truth_objects += static_cast<std::int64_t>(n_truth);
  counts_.hypotheses += static_cast<std::int64_t>(n_hyp);

  std::vector<char> truth_done(n_truth, 0), hypothesis_done(n_hyp, 0);
  const auto record_match = [&](std::size_t i, std::size_t j, bool is_switch) {
    truth_done[i] = 1;
    hypothesis_done[j] = 1;
    ++counts_.matches;
    counts_.switches += is_switch ? 1 : 0;
    counts_.distance_sum +=
        frame.distance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
    TruthHistory& h = truths_[frame.truth_ids[i]];
    h.last_hypothesis = frame.hypothesis_ids[j];
    h.ever_matched = true;
  };

  // 1. Keep last correspondences that are still possible (py-motmetrics step 1: any earlier
  //    match, not only the previous frame's).
  for (std::size_t i = 0; i < n_truth; ++i) {
    const auto it = truths_.find(frame.truth_ids[i]);
    if (it == truths_.end() || !it->second.ever_matched) continue;
    for (std::size_t j = 0; j < n_hyp; ++j) {
      if (hypothesis_done[j] || frame.hypothesis_ids[j] != it->second.last_hypothesis) continue;
      if (std::isfinite(
              frame.distance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)))) {
        record_match(i, j, false);
      }
      break;
    }
  }

  // 2. Minimum-cost matching of the rest.
  Eigen::MatrixXd rest = frame.distance;
  for (std::size_t i = 0; i < n_truth; ++i) {
    if (truth_done[i]) rest.row(static_cast<Eigen::Index>(i)).setConstant(assignment::kForbidden);
  }
  for (std::size_t j = 0; j < n_hyp; ++j) {
    if (hypothesis_done[j]) {
      rest.col(static_cast<Eigen::Index>(j)).setConstant(assignment::kForbidden);
    }
  }
  const assignment::Assignment matched = assignment::SolveLinearAssignment(rest);
  for (std::size_t i = 0; i < n_truth; ++i) {
    const int j = matched.column_of_row[i];
    if (j == assignment::kUnassigned) continue;
    const auto uj = static_cast<std::size_t>(j);
    const auto it = truths_.find(frame.truth_ids[i]);
    const bool is_switch = it != truths_.end() && it->second.ever_matched &&
                           it->second.last_hypothesis != frame.hypothesis_ids[uj];
    record_match(i, uj, is_switch);
  }

  // 3. Misses and false positives; per-truth history for MT/PT/ML and fragmentations.
  for (std::size_t i = 0; i < n_truth; ++i) {
    TruthHistory& h = truths_[frame.truth_ids[i]];
    ++h.frames_present;
    if (truth_done[i]) {
      ++h.frames_matched;
      if (h.miss_after_match) ++counts_.fragmentations;
      h.miss_after_match = false;
      h.matched_last_present = true;
    } else {
      ++counts_.misses;
      if (h.matched_last_present) h.miss_after_match = true;
      h.matched_last_present = false;
    }
  }
  for (std::size_t j = 0; j < n_hyp; ++j) counts_.false_positives += hypothesis_done[j] ? 0 : 1;
}

ClearMotCounts ClearMotAccumulator::Counts() const {
  ClearMotCounts c = counts_;
  c.unique_truths = static_cast<std::int64_t>(truths_.size());
  for (const auto& [id, h] : truths_) {
    // Integer comparisons of matched / present against 0.8 and 0.2, free of rounding.
    const std::int64_t m = h.frames_matched, p = h.frames_present;
    if (5 * m >= 4 * p) {
      ++c.mostly_tracked;
    } else if (5 * m >= p) {
      ++c.partially_tracked;
    } else {
      ++c.mostly_lost;
    }
  }
  return c;
}

}  // namespace lookout::eval
