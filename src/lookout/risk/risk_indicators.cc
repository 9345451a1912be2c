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

double CollisionProbability(const FootprintTrack& ego, const FootprintTrack& object, double dt_s,
                            const SamplingInput& sampling,
                            const std::vector<Eigen::Vector4d>& normals) {
  if (normals.empty()) return 0.0;
  const std::size_t n = std::min(ego.size(), object.size());
  const Eigen::Matrix2d lp = SquareRoot(sampling.position_covariance);
  const Eigen::Matrix2d lv = SquareRoot(sampling.velocity_covariance);
  // Most objects pass far from the ego, and most steps of the others are out of every sample's
  // reach: a step is a candidate only where the largest offset among the samples (of the
  // position, and of the velocity over the step's time) could close the gap between the
  // bounding circles. Without a candidate step no sample is tested. Exact: no sample is
  // skipped that could hit.
  const auto largest_sigma = [](const Eigen::Matrix2d& p) {
    return std::sqrt(std::max(0.0, 0.5 * (p.trace() + std::sqrt(std::max(
        0.0, (p(0, 0) - p(1, 1)) * (p(0, 0) - p(1, 1)) + 4.0 * p(0, 1) * p(1, 0))))));
  };
  double zp = 0.0, zv = 0.0;
  for (const Eigen::Vector4d& z : normals) {
    zp = std::max(zp, z.head<2>().squaredNorm());
    zv = std::max(zv, z.tail<2>().squaredNorm());
  }
  // |L z| <= sigma_max |z|, with a hair of slack for rounding.
  const double sp = 1.000001 * std::sqrt(zp) * largest_sigma(sampling.position_covariance);
  const double sv = 1.000001 * std::sqrt(zv) * largest_sigma(sampling.velocity_covariance);
  struct Candidate {
    std::size_t step;
    double t_s;
    Eigen::Vector2d relative;  // the object's centre from the ego's
    double reach2;             // (sum of the bounding radii)^2
  };
  std::vector<Candidate> candidates;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * dt_s;
    const Eigen::Vector2d relative = object[k].centre_m - ego[k].centre_m;
    const double reach = ego[k].BoundingRadius() + object[k].BoundingRadius();
    if (relative.norm() - reach <= sp + t * sv) {
      candidates.push_back({k, t, relative, reach * reach});
    }
  }
  if (candidates.empty()) return 0.0;
  // Each sample: the cheap bounding-circle test at the candidate steps, the exact test of the
  // footprints where it passes, until its first hit.
  int hits = 0;
  for (const Eigen::Vector4d& z : normals) {
    const Eigen::Vector2d dp = lp * z.head<2>();
    const Eigen::Vector2d dv = lv * z.tail<2>();
    for (const Candidate& c : candidates) {
      const Eigen::Vector2d offset = dp + c.t_s * dv;
      if ((c.relative + offset).squaredNorm() > c.reach2) continue;
      if (Overlap(ego[c.step], object[c.step], offset)) {
        ++hits;
        break;
      }
    }
  }
  return static_cast<double>(hits) / static_cast<double>(normals.size());
}

std::optional<double> PostEncroachmentTime(const FootprintTrack& ego,
                                           const FootprintTrack& object, double dt_s) {
  // Only the object's steps that come near the box about the ego's whole path can share a
  // place with it; most objects have none.
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  for (const Footprint& f : ego) {
    low = low.cwiseMin(f.centre_m - Eigen::Vector2d::Constant(f.BoundingRadius()));
    high = high.cwiseMax(f.centre_m + Eigen::Vector2d::Constant(f.BoundingRadius()));
  }
  std::optional<std::size_t> best;
  for (std::size_t j = 0; j < object.size(); ++j) {
    const Footprint& o = object[j];
    const Eigen::Vector2d r = Eigen::Vector2d::Constant(o.BoundingRadius());
    if (((o.centre_m + r).array() < low.array()).any() ||
        ((o.centre_m - r).array() > high.array()).any()) {
      continue;
    }
    for (std::size_t i = 0; i < ego.size(); ++i) {
      const std::size_t gap = i > j ? i - j : j - i;
      if (best && gap >= *best) continue;
      if (Overlap(ego[i], o, Eigen::Vector2d::Zero())) best = gap;
    }
  }
  if (!best) return std::nullopt;
  return static_cast<double>(*best) * dt_s;
}

}  // namespace lookout::risk
