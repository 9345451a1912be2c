#include "lookout/eval/ospa.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "lookout/assignment/linear_assignment.h"

namespace lookout::eval {
namespace {

using Points = std::vector<Eigen::Vector2d>;

// Cut-off distances, rows the smaller set.
Eigen::MatrixXd CutOffDistances(const Points& fewer, const Points& more, double cutoff) {
  Eigen::MatrixXd d(static_cast<Eigen::Index>(fewer.size()),
                    static_cast<Eigen::Index>(more.size()));
  for (std::size_t i = 0; i < fewer.size(); ++i) {
    for (std::size_t j = 0; j < more.size(); ++j) {
      d(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          std::min((fewer[i] - more[j]).norm(), cutoff);
    }
  }
  return d;
}

// min over complete assignments of the largest entry: the smallest threshold under which the
// entries at most that threshold still admit a complete assignment (binary search over the
// distinct entries).
double BottleneckAssignment(const Eigen::MatrixXd& d) {
  std::vector<double> values(d.data(), d.data() + d.size());
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  std::size_t lo = 0, hi = values.size() - 1;  // values[hi] always admits one
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    const Eigen::MatrixXd allowed = (d.array() <= values[mid]).select(d, assignment::kForbidden);
    if (assignment::SolveCompleteAssignment(allowed)) {
      hi = mid;
    } else {
      lo = mid + 1;
    }
  }
  return values[lo];
}

}  // namespace

double Ospa(const Points& truths, const Points& estimates, const OspaOptions& options) {
  const double c = options.cutoff_m;
  const double p = options.order_p;
  assert(c > 0.0 && p >= 1.0);
  const bool truths_fewer = truths.size() <= estimates.size();
  const Points& fewer = truths_fewer ? truths : estimates;
  const Points& more = truths_fewer ? estimates : truths;
  const auto m = static_cast<double>(fewer.size());
  const auto n = static_cast<double>(more.size());
  if (more.empty()) return 0.0;
  if (fewer.empty()) return c;
  const Eigen::MatrixXd d = CutOffDistances(fewer, more, c);
  if (std::isinf(p)) return fewer.size() == more.size() ? BottleneckAssignment(d) : c;
  const Eigen::MatrixXd d_p = d.array().pow(p);
  const double localisation = assignment::SolveCompleteAssignment(d_p)->cost;
  return std::pow((localisation + std::pow(c, p) * (n - m)) / n, 1.0 / p);
}

GospaResult Gospa(const Points& truths, const Points& estimates, const GospaOptions& options) {
  const double c = options.cutoff_m;
  const double p = options.order_p;
  const double alpha = options.alpha;
  assert(c > 0.0 && p >= 1.0 && std::isfinite(p) && alpha > 0.0 && alpha <= 2.0);
  const bool truths_fewer = truths.size() <= estimates.size();
  const Points& fewer = truths_fewer ? truths : estimates;
  const Points& more = truths_fewer ? estimates : truths;
  const double c_p = std::pow(c, p);

  std::vector<int> column_of_row(fewer.size(), assignment::kUnassigned);
  double cut_sum = 0.0;  // sum of min(d, c)^p over the optimal complete assignment
  if (!fewer.empty()) {
    const Eigen::MatrixXd d_p = CutOffDistances(fewer, more, c).array().pow(p);
    const assignment::Assignment best = *assignment::SolveCompleteAssignment(d_p);
    column_of_row = best.column_of_row;
    cut_sum = best.cost;
  }
  GospaResult r;
  const double unassigned = static_cast<double>(more.size() - fewer.size());
  r.distance = std::pow(cut_sum + c_p / alpha * unassigned, 1.0 / p);
  if (alpha != 2.0) {
    r.localisation_pth = r.missed_pth = r.false_pth = std::numeric_limits<double>::quiet_NaN();
    return r;
  }
  // alpha = 2: a pair at the cut-off is no assignment but one missed and one false target
  // (c^p = c^p / 2 + c^p / 2), which leaves the distance unchanged.
  int cut_pairs = 0;
  for (std::size_t i = 0; i < fewer.size(); ++i) {
    const double d = (fewer[i] - more[static_cast<std::size_t>(column_of_row[i])]).norm();
    if (d < c) {
      ++r.assigned;
      r.localisation_pth += std::pow(d, p);
    } else {
      ++cut_pairs;
    }
  }
  const int extra = static_cast<int>(more.size() - fewer.size());
  r.missed = cut_pairs + (truths_fewer ? 0 : extra);
  r.false_targets = cut_pairs + (truths_fewer ? extra : 0);
  r.missed_pth = c_p / 2.0 * r.missed;
  r.false_pth = c_p / 2.0 * r.false_targets;
  return r;
}

}  // namespace lookout::eval
