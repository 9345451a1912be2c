#include "lookout/fusion/gaussian_fusion.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "lookout/core/random.h"

namespace lookout::fusion {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

// The paper's scalar formulas: 1/R = 1/R_L + 1/R_V, P = (P_L/R_L + P_V/R_V) R.
TEST(GaussianFusionTest, ScalarCaseIsThePapersFormula) {
  const Gaussian2 laser{Vector2d(10.0, 0.0), Vector2d(0.04, 0.01).asDiagonal()};
  const Gaussian2 vision{Vector2d(11.0, 0.2), Vector2d(0.36, 0.01).asDiagonal()};
  const Gaussian2 f = FuseGaussians(laser, vision);
  const double r = 1.0 / (1.0 / 0.04 + 1.0 / 0.36);
  EXPECT_NEAR(f.covariance(0, 0), r, 1e-15);
  EXPECT_NEAR(f.mean.x(), (10.0 / 0.04 + 11.0 / 0.36) * r, 1e-12);  // 10.1
  EXPECT_NEAR(f.mean.x(), 10.1, 1e-12);
  EXPECT_NEAR(f.mean.y(), 0.1, 1e-15);  // equal weights
  EXPECT_NEAR(f.covariance(1, 1), 0.005, 1e-15);
  EXPECT_NEAR(f.covariance(0, 1), 0.0, 1e-15);
}

// The information form against the Kalman-gain form of the same product of Gaussians:
// K = A (A + B)^-1, mean = a + K (b - a), covariance = (I - K) A.
TEST(GaussianFusionTest, EqualsTheClosedFormOnCorrelatedCovariances) {
  Gaussian2 a{Vector2d(3.0, -1.0), Matrix2d()};
  a.covariance << 0.5, 0.2, 0.2, 0.3;
  Gaussian2 b{Vector2d(2.5, -0.4), Matrix2d()};
  b.covariance << 0.1, -0.05, -0.05, 0.9;
  const Matrix2d gain = a.covariance * (a.covariance + b.covariance).inverse();
  const Vector2d mean = a.mean + gain * (b.mean - a.mean);
  const Matrix2d covariance = (Matrix2d::Identity() - gain) * a.covariance;
  const Gaussian2 f = FuseGaussians(a, b);
  EXPECT_LT((f.mean - mean).norm(), 1e-12);
  EXPECT_LT((f.covariance - covariance).norm(), 1e-12);
  // Symmetric in its arguments.
  const Gaussian2 g = FuseGaussians(b, a);
  EXPECT_LT((g.mean - f.mean).norm(), 1e-12);
  EXPECT_LT((g.covariance - f.covariance).norm(), 1e-12);
}

Matrix2d RandomCovariance(Rng& rng) {
  // A random rotation of random variances over six orders of magnitude (1e-4 .. 1e2 m^2).
  const double angle = rng.Uniform(-3.2, 3.2);
  const Eigen::Rotation2Dd rotation(angle);
  const Vector2d variances{std::pow(10.0, rng.Uniform(-4.0, 2.0)),
                           std::pow(10.0, rng.Uniform(-4.0, 2.0))};
  return rotation.toRotationMatrix() * variances.asDiagonal() *
         rotation.toRotationMatrix().transpose();
}

// Loewner order: the fused covariance is no larger than either input, A - F and B - F are
// positive semidefinite. Checked by their eigenvalues on 10,000 random pairs, with a tolerance
// relative to the inputs' size for rounding.
TEST(GaussianFusionTest, FusedCovarianceIsNoLargerThanEitherInput) {
  const std::uint64_t seed = 4242;
  Rng rng(seed);
  for (int trial = 0; trial < 10000; ++trial) {
    const Gaussian2 a{Vector2d{rng.Normal(), rng.Normal()}, RandomCovariance(rng)};
    const Gaussian2 b{Vector2d{rng.Normal(), rng.Normal()}, RandomCovariance(rng)};
    const Gaussian2 f = FuseGaussians(a, b);
    for (const Matrix2d* input : {&a.covariance, &b.covariance}) {
      const Matrix2d difference = *input - f.covariance;
      const Eigen::SelfAdjointEigenSolver<Matrix2d> eigen(difference);
      const double tolerance = 1e-9 * input->norm();
      ASSERT_GE(eigen.eigenvalues().minCoeff(), -tolerance)
          << "seed " << seed << ", trial " << trial << "\ninput\n"
          << *input << "\nfused\n"
          << f.covariance;
    }
    // And it is still a covariance.
    ASSERT_GT(Eigen::SelfAdjointEigenSolver<Matrix2d>(f.covariance).eigenvalues().minCoeff(),
              0.0)
        << "seed " << seed << ", trial " << trial;
  }
}

TEST(GaussianFusionTest, MahalanobisOfAnAxisAlignedCovariance) {
  EXPECT_NEAR(MahalanobisSquared(Vector2d(2.0, 3.0), Vector2d(4.0, 9.0).asDiagonal()), 2.0,
              1e-15);
}

// Two points 0.5 m apart along x, each with variance 0.01 there: d^2 = 0.25 / 0.02 = 12.5,
// beyond the 99 % quantile (9.21): the scale is 12.5 / 9.21, and with it both covariances put
// the difference on the quantile. Moved within it (0.4 m: d^2 = 8), the scale is 1.
TEST(GaussianFusionTest, ADisagreementBeyondTheQuantileScalesTheCovariance) {
  const double quantile = 9.2103403719761836;  // chi-square, 2 dof, 0.99
  const Gaussian2 lidar{Vector2d(10.0, 0.0), Vector2d(0.01, 0.04).asDiagonal()};
  const Gaussian2 stereo{Vector2d(10.5, 0.0), Vector2d(0.01, 0.09).asDiagonal()};
  const double scale = DisagreementScale(lidar, stereo, quantile);
  EXPECT_NEAR(scale, 12.5 / quantile, 1e-12);
  EXPECT_NEAR(
      MahalanobisSquared(lidar.mean - stereo.mean, scale * (lidar.covariance + stereo.covariance)),
      quantile, 1e-9);
  // Scaling both inputs leaves the fused mean and scales the fused covariance.
  const Gaussian2 fused = FuseGaussians(lidar, stereo);
  const Gaussian2 scaled = FuseGaussians({lidar.mean, scale * lidar.covariance},
                                         {stereo.mean, scale * stereo.covariance});
  EXPECT_LT((scaled.mean - fused.mean).norm(), 1e-12);
  EXPECT_LT((scaled.covariance - scale * fused.covariance).norm(), 1e-12);
  const Gaussian2 near{Vector2d(10.4, 0.0), stereo.covariance};
  EXPECT_EQ(DisagreementScale(lidar, near, quantile), 1.0);
}

}  // namespace
}  // namespace lookout::fusion
