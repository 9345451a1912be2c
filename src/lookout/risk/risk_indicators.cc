#include "lookout/risk/risk_indicators.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "lookout/core/random.h"

namespace lookout::risk {
namespace {

// A square root L (L L^T = P) of a PSD 2 x 2 matrix; LDLT copes with singular P.
Eigen::Matrix2d SquareRoot(const Eigen::Matrix2d& p) {
  const Eigen::LDLT<Eigen::Matrix2d> ldlt(p);
  const Eigen::Vector2d d = ldlt.vectorD().cwiseMax(0.0).cwiseSqrt();
  Eigen::Matrix2d l = ldlt.matrixL();
  l = ldlt.transpositionsP().transpose() * l;
  return l * d.asDiagonal();
}

}  // namespace

double CollisionProbability(const CircleTrack& ego, const CircleTrack& object, double dt_s,
                            const SamplingInput& sampling) {
  if (sampling.samples <= 0) return 0.0;
  const std::size_t n = std::min({ego.centre_m.size(), ego.radius_m.size(),
                                  object.centre_m.size(), object.radius_m.size()});
  const Eigen::Matrix2d lp = SquareRoot(sampling.position_covariance);
  const Eigen::Matrix2d lv = SquareRoot(sampling.velocity_covariance);
  // The relative nominal positions and the radii's sums, once.
  std::vector<Eigen::Vector2d> relative(n);
  std::vector<double> reach2(n);
  for (std::size_t k = 0; k < n; ++k) {
    relative[k] = object.centre_m[k] - ego.centre_m[k];
    const double r = ego.radius_m[k] + object.radius_m[k];
    reach2[k] = r * r;
  }
  Rng rng(sampling.seed);
  int hits = 0;
  for (int s = 0; s < sampling.samples; ++s) {
    const Eigen::Vector2d dp = lp * Eigen::Vector2d(rng.Normal(), rng.Normal());
    const Eigen::Vector2d dv = lv * Eigen::Vector2d(rng.Normal(), rng.Normal());
    for (std::size_t k = 0; k < n; ++k) {
      const double t = static_cast<double>(k) * dt_s;
      if ((relative[k] + dp + t * dv).squaredNorm() <= reach2[k]) {
        ++hits;
        break;
      }
    }
  }
  return static_cast<double>(hits) / static_cast<double>(sampling.samples);
}

std::optional<double> PostEncroachmentTime(const CircleTrack& ego, const CircleTrack& object,
                                           double dt_s) {
  const std::size_t ne = std::min(ego.centre_m.size(), ego.radius_m.size());
  const std::size_t no = std::min(object.centre_m.size(), object.radius_m.size());
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < ne; ++i) {
    for (std::size_t j = 0; j < no; ++j) {
      const std::size_t gap = i > j ? i - j : j - i;
      if (best && gap >= *best) continue;
      const double r = ego.radius_m[i] + object.radius_m[j];
      if ((ego.centre_m[i] - object.centre_m[j]).squaredNorm() <= r * r) best = gap;
    }
  }
  if (!best) return std::nullopt;
  return static_cast<double>(*best) * dt_s;
}

}  // namespace lookout::risk
