#include "lookout/risk/risk_indicators.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

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

std::vector<Eigen::Vector4d> DrawStandardNormals(int samples, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Eigen::Vector4d> out(static_cast<std::size_t>(std::max(0, samples)));
  for (Eigen::Vector4d& v : out) {
    const double a = rng.Normal(), b = rng.Normal(), c = rng.Normal(), d = rng.Normal();
    v = Eigen::Vector4d(a, b, c, d);
  }
  return out;
}

double CollisionProbability(const CircleTrack& ego, const CircleTrack& object, double dt_s,
                            const SamplingInput& sampling,
                            const std::vector<Eigen::Vector4d>& normals) {
  if (normals.empty()) return 0.0;
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
  // Most objects pass far from the ego: if even a 6-sigma offset of the position and of the
  // velocity (over the whole horizon) cannot close the nominal gap, the probability is below
  // 2 exp(-18) ~ 3e-8 and no sample is drawn.
  double closest_gap = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; ++k) {
    closest_gap = std::min(closest_gap, relative[k].norm() - std::sqrt(reach2[k]));
  }
  const double horizon_s = n > 0 ? static_cast<double>(n - 1) * dt_s : 0.0;
  const auto largest_sigma = [](const Eigen::Matrix2d& p) {
    return std::sqrt(std::max(0.0, 0.5 * (p.trace() + std::sqrt(std::max(
        0.0, (p(0, 0) - p(1, 1)) * (p(0, 0) - p(1, 1)) + 4.0 * p(0, 1) * p(1, 0))))));
  };
  constexpr double kSigmas = 6.0;
  if (closest_gap > kSigmas * (largest_sigma(sampling.position_covariance) +
                               horizon_s * largest_sigma(sampling.velocity_covariance))) {
    return 0.0;
  }
  int hits = 0;
  for (const Eigen::Vector4d& z : normals) {
    const Eigen::Vector2d dp = lp * z.head<2>();
    const Eigen::Vector2d dv = lv * z.tail<2>();
    for (std::size_t k = 0; k < n; ++k) {
      const double t = static_cast<double>(k) * dt_s;
      if ((relative[k] + dp + t * dv).squaredNorm() <= reach2[k]) {
        ++hits;
        break;
      }
    }
  }
  return static_cast<double>(hits) / static_cast<double>(normals.size());
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
