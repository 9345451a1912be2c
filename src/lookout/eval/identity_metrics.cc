#include "lookout/eval/identity_metrics.h"

#include <cassert>
#include <cmath>
#include <limits>

#include "lookout/assignment/linear_assignment.h"
#include "lookout/eval/statistics.h"

namespace lookout::eval {

double IdentityCounts::Idf1() const {
  return Ratio(2.0 * static_cast<double>(true_positives),
               static_cast<double>(2 * true_positives + false_positives + false_negatives));
}
double IdentityCounts::Idp() const {
  return Ratio(static_cast<double>(true_positives),
               static_cast<double>(true_positives + false_positives));
}
double IdentityCounts::Idr() const {
  return Ratio(static_cast<double>(true_positives),
               static_cast<double>(true_positives + false_negatives));
}

IdentityCounts operator+(const IdentityCounts& a, const IdentityCounts& b) {
  return {a.true_positives + b.true_positives, a.false_negatives + b.false_negatives,
          a.false_positives + b.false_positives};
}

void IdentityAccumulator::AddFrame(const MotFrame& frame) {
  assert(frame.distance.rows() == static_cast<Eigen::Index>(frame.truth_ids.size()));
  assert(frame.distance.cols() == static_cast<Eigen::Index>(frame.hypothesis_ids.size()));
  for (const std::int64_t id : frame.truth_ids) ++truth_presences_[id];
  for (const std::int64_t id : frame.hypothesis_ids) ++hypothesis_presences_[id];
  for (Eigen::Index i = 0; i < frame.distance.rows(); ++i) {
    for (Eigen::Index j = 0; j < frame.distance.cols(); ++j) {
      if (std::isfinite(frame.distance(i, j))) {
        ++pair_presences_[{frame.truth_ids[static_cast<std::size_t>(i)],
                           frame.hypothesis_ids[static_cast<std::size_t>(j)]}];
      }
    }
  }
}

IdentityCounts IdentityAccumulator::Counts() const {
  std::int64_t truth_total = 0, hypothesis_total = 0;
  std::map<std::int64_t, Eigen::Index> truth_row, hypothesis_column;
  for (const auto& [id, n] : truth_presences_) {
    truth_row.emplace(id, static_cast<Eigen::Index>(truth_row.size()));
    truth_total += n;
  }
  for (const auto& [id, n] : hypothesis_presences_) {
    hypothesis_column.emplace(id, static_cast<Eigen::Index>(hypothesis_column.size()));
    hypothesis_total += n;
  }

  // Matching truth i to hypothesis j costs IDFN + IDFP = n_i + n_j - 2 tp_ij, leaving either
  // unmatched costs n_i or n_j: minimising the total is maximising the sum of tp_ij over the
  // matched pairs. Rows: truths; columns: hypotheses, then one "unmatched" column per truth
  // (cost 0, its own only), so every truth is assigned and any subset can stay unmatched.
  const auto n_truth = static_cast<Eigen::Index>(truth_row.size());
  const auto n_hyp = static_cast<Eigen::Index>(hypothesis_column.size());
  Eigen::MatrixXd cost =
      Eigen::MatrixXd::Constant(n_truth, n_hyp + n_truth, assignment::kForbidden);
  for (Eigen::Index i = 0; i < n_truth; ++i) cost(i, n_hyp + i) = 0.0;
  for (const auto& [pair, tp] : pair_presences_) {
    cost(truth_row.at(pair.first), hypothesis_column.at(pair.second)) = -static_cast<double>(tp);
  }
  const std::optional<assignment::Assignment> best = assignment::SolveCompleteAssignment(cost);
  assert(best.has_value());  // the "unmatched" columns always allow one

  IdentityCounts counts;
  // Costs are small integers, so the (negated) sum is exact.
  counts.true_positives = static_cast<std::int64_t>(std::llround(-best->cost));
  counts.false_negatives = truth_total - counts.true_positives;
  counts.false_positives = hypothesis_total - counts.true_positives;
  return counts;
}

}  // namespace lookout::eval
