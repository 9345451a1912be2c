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

double DisagreementScale(const Gaussian2& a, const Gaussian2& b, double quantile) {
  const double d2 = MahalanobisSquared(a.mean - b.mean, a.covariance + b.covariance);
  return d2 > quantile ? d2 / quantile : 1.0;
}

double MahalanobisSquared(const Eigen::Vector2d& difference, const Matrix2d& covariance) {
  return difference.dot(covariance.inverse() * difference);
}

}  // namespace lookout::fusion
