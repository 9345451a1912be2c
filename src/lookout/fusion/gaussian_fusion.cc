#include "lookout/fusion/gaussian_fusion.h"

#include <Eigen/LU>

namespace lookout::fusion {

using Eigen::Matrix2d;

Gaussian2 FuseGaussians(const Gaussian2& a, const Gaussian2& b) {
  const Matrix2d info_a = a.covariance.inverse();
  const Matrix2d info_b = b.covariance.inverse();
  Gaussian2 fused;
  fused.covariance = (info_a + info_b).inverse();
  // Exactly symmetric, so that downstream Cholesky factorisations see what they expect.
  fused.covariance = 0.5 * (fused.covariance + fused.covariance.transpose()).eval();
  fused.mean = fused.covariance * (info_a * a.mean + info_b * b.mean);
  return fused;
}

Gaussian2 FuseCorrelated(const Gaussian2& a, const Gaussian2& b, const Matrix2d& cross) {
  const Matrix2d a_less_cross = a.covariance - cross;
  const Matrix2d difference_covariance = a.covariance + b.covariance - cross - cross.transpose();
  const Matrix2d gain = a_less_cross * difference_covariance.inverse();
  Gaussian2 fused;
  fused.mean = a.mean + gain * (b.mean - a.mean);
  fused.covariance = a.covariance - gain * a_less_cross.transpose();
  fused.covariance = 0.5 * (fused.covariance + fused.covariance.transpose()).eval();
  return fused;
}

namespace {

// The squared Mahalanobis distance between two estimates with cross-covariance `cross`.
double DifferenceSquared(const Gaussian2& a, const Gaussian2& b, const Matrix2d& cross) {
  return MahalanobisSquared(a.mean - b.mean,
                            a.covariance + b.covariance - cross - cross.transpose());
}

}  // namespace

double DisagreementScale(const Gaussian2& a, const Gaussian2& b, double quantile,
                         const Matrix2d& cross) {
  const double d2 = DifferenceSquared(a, b, cross);
  return d2 > quantile ? d2 / quantile : 1.0;
}

Matrix2d SpreadAbout(const Eigen::Vector2d& about, const Gaussian2& g) {
  const Eigen::Vector2d offset = g.mean - about;
  return g.covariance + offset * offset.transpose();
}

Matrix2d DisagreementMixture(const Gaussian2& kept, const Gaussian2& other, double quantile) {
  const double d2 = DifferenceSquared(kept, other, Matrix2d::Zero());
  if (!(d2 > quantile)) return kept.covariance;
  const double w = quantile / d2;
  return w * kept.covariance + (1.0 - w) * SpreadAbout(kept.mean, other);
}

Matrix2d TwoBodiesMixture(const Gaussian2& fused, const Gaussian2& a, const Gaussian2& b,
                          double quantile, const Matrix2d& cross) {
  const double d2 = DifferenceSquared(a, b, cross);
  if (!(d2 > quantile)) return fused.covariance;
  const double w = quantile / d2;
  return w * fused.covariance +
         0.5 * (1.0 - w) * (SpreadAbout(fused.mean, a) + SpreadAbout(fused.mean, b));
}

double MahalanobisSquared(const Eigen::Vector2d& difference, const Matrix2d& covariance) {
  return difference.dot(covariance.inverse() * difference);
}

}  // namespace lookout::fusion
