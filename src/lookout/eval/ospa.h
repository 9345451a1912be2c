#pragma once

// Set distances between the true objects and the estimates of one frame, for point targets.
//
// OSPA (Schuhmacher, Vo and Vo, "A consistent metric for performance evaluation of multi-object
// filters", IEEE TSP 56(8), 2008): with |X| = m <= |Y| = n, distances cut off at c,
//   d_p^(c)(X, Y) = ( (1/n) (min_pi sum_i min(d(x_i, y_pi(i)), c)^p + c^p (n - m)) )^(1/p),
// and for p = infinity: max_i min(d, c) of the bottleneck assignment when m = n, c otherwise.
// 0 when both sets are empty.
//
// GOSPA (Rahmathullah, Garcia-Fernandez and Svensson, "Generalized optimal sub-pattern
// assignment metric", FUSION 2017, eq. 1): not normalised by n, and with alpha in (0, 2]
//   d_p^(c,alpha)(X, Y) = ( min_pi sum_i min(d, c)^p + c^p / alpha (n - m) )^(1/p).
// With alpha = 2 it splits (their eq. 2) into localisation (the assigned pairs closer than c),
// missed targets and false targets, each missed or false one costing c^p / 2.

#include <Eigen/Core>
#include <limits>
#include <vector>

namespace lookout::eval {

struct OspaOptions {
  double cutoff_m = 2.0;  // c > 0
  double order_p = 2.0;   // p >= 1, or infinity
};

struct GospaOptions {
  double cutoff_m = 2.0;  // c > 0
  double order_p = 2.0;   // 1 <= p < infinity
  double alpha = 2.0;     // (0, 2]
};

struct GospaResult {
  double distance = 0.0;  // d_p^(c, alpha)(X, Y), metres
  // The alpha = 2 decomposition of distance^p (NaN for other alpha): the sum of d^p over
  // the assigned pairs, and c^p / 2 for each missed truth and each false estimate.
  double localisation_pth = 0.0;
  double missed_pth = 0.0;
  double false_pth = 0.0;
  int assigned = 0;
  int missed = 0;
  int false_targets = 0;
};

double Ospa(const std::vector<Eigen::Vector2d>& truths,
            const std::vector<Eigen::Vector2d>& estimates, const OspaOptions& options);

GospaResult Gospa(const std::vector<Eigen::Vector2d>& truths,
                  const std::vector<Eigen::Vector2d>& estimates, const GospaOptions& options);

}  // namespace lookout::eval
