#include "lookout/fusion/gaussian_fusion.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <vector>

#include "lookout/core/random.h"
#include "lookout/fusion/sampled_moment_test_support.h"

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

// Correlated errors (Bar-Shalom and Campo): with no cross-covariance it is FuseGaussians; where
// b repeats a's error whole (B = C = A) the fused covariance is A, nothing averaged away; and
// against 200,000 draws of correlated errors, the fused error's covariance is the one it
// states (within 4 standard errors), where FuseGaussians' would state too little.
TEST(GaussianFusionTest, FuseCorrelatedStatesTheCovarianceOfItsError) {
  Gaussian2 a{Vector2d(3.0, -1.0), Matrix2d()};
  a.covariance << 0.04, 0.01, 0.01, 0.02;
  Gaussian2 b{Vector2d(3.2, -0.9), Matrix2d()};
  b.covariance << 0.09, -0.01, -0.01, 0.03;
  const Gaussian2 independent = FuseCorrelated(a, b, Matrix2d::Zero());
  const Gaussian2 plain = FuseGaussians(a, b);
  EXPECT_LT((independent.mean - plain.mean).norm(), 1e-12);
  EXPECT_LT((independent.covariance - plain.covariance).norm(), 1e-12);
  // B = C = A, a hair less for S = A + B - C - C^T to be invertible.
  const Matrix2d almost_a = a.covariance - 1e-9 * Matrix2d::Identity();
  const Gaussian2 repeated = FuseCorrelated(a, Gaussian2{b.mean, a.covariance}, almost_a);
  EXPECT_LT((repeated.covariance - a.covariance).norm(), 1e-6);

  Matrix2d cross;
  cross << 0.015, 0.002, 0.001, 0.008;  // correlation about 0.3
  const Gaussian2 fused = FuseCorrelated(a, b, cross);
  Eigen::Matrix4d joint;
  joint << a.covariance, cross, cross.transpose(), b.covariance;
  const Eigen::Matrix4d lower = joint.llt().matrixL();
  const std::uint64_t seed = 20261208;
  Rng rng(seed);
  const int samples = 200000;
  testing::SampledMoment errors;
  for (int k = 0; k < samples; ++k) {
    const Eigen::Vector4d e =
        lower * Eigen::Vector4d(rng.Normal(), rng.Normal(), rng.Normal(), rng.Normal());
    const Gaussian2 draw = FuseCorrelated(Gaussian2{a.mean + e.head<2>(), a.covariance},
                                          Gaussian2{b.mean + e.tail<2>(), b.covariance}, cross);
    const Vector2d error = draw.mean - fused.mean;  // both means' errors drawn about zero
    errors.Add(error * error.transpose());
  }
  errors.ExpectNear(fused.covariance, seed);
  EXPECT_GT(fused.covariance.trace(), 1.2 * plain.covariance.trace());
}

// The second moment about a point of samples drawn from a weighted set of Gaussians: the
// mixture the closed forms below stand for, drawn. `weights` sum to 1.
testing::SampledMoment SampleSecondMoment(const Vector2d& about,
                                          const std::vector<Gaussian2>& components,
                                          const std::vector<double>& weights, int samples,
                                          Rng& rng) {
  testing::SampledMoment out;
  for (int k = 0; k < samples; ++k) {
    double u = rng.Uniform(0.0, 1.0);
    std::size_t c = 0;
    while (c + 1 < components.size() && u >= weights[c]) u -= weights[c++];
    const Eigen::LLT<Matrix2d> chol(components[c].covariance);
    const Vector2d x = components[c].mean + chol.matrixL() * Vector2d(rng.Normal(), rng.Normal());
    out.Add((x - about) * (x - about).transpose());
  }
  return out;
}

// The kept estimate right with weight q / d^2, the other with 1 - q / d^2: DisagreementMixture
// is that mixture's second moment about the kept mean, here against 200,000 draws of it (the
// tolerance is 4 standard errors of the sample moment). Within the quantile it is the kept
// covariance, exactly; just past it, nearly; far past it, nearly the other's plus the offset.
TEST(GaussianFusionTest, DisagreementMixtureIsTheTwoHypothesesSecondMoment) {
  const double quantile = 9.2103403719761836;  // chi-square, 2 dof, 0.99
  const Gaussian2 kept{Vector2d(10.0, 0.0), Vector2d(0.0025, 0.01).asDiagonal()};
  Gaussian2 other{Vector2d(10.5, 0.2), Matrix2d()};
  other.covariance << 0.01, 0.002, 0.002, 0.004;
  const double d2 = MahalanobisSquared(kept.mean - other.mean, kept.covariance + other.covariance);
  ASSERT_GT(d2, 2.0 * quantile);
  const double w = quantile / d2;
  const Matrix2d mixture = DisagreementMixture(kept, other, quantile);
  const std::uint64_t seed = 20261206;
  Rng rng(seed);
  const int samples = 200000;
  SampleSecondMoment(kept.mean, {kept, other}, {w, 1.0 - w}, samples, rng)
      .ExpectNear(mixture, seed);
  // Within the quantile: the kept covariance as it was.
  const Gaussian2 agreeing{Vector2d(10.1, 0.0), other.covariance};
  EXPECT_EQ(DisagreementMixture(kept, agreeing, quantile), kept.covariance);
  // Continuous at the quantile: an offset that puts d^2 just past it changes next to nothing.
  const Vector2d direction = (other.mean - kept.mean).normalized();
  const double on_quantile =
      std::sqrt(quantile / MahalanobisSquared(direction, kept.covariance + other.covariance));
  const Gaussian2 just_past{kept.mean + (1.0 + 1e-9) * on_quantile * direction, other.covariance};
  EXPECT_LT((DisagreementMixture(kept, just_past, quantile) - kept.covariance).norm(), 1e-8);
  // Far past it (10 m against centimetres: q / d^2 = 0.0012): the other's covariance and the
  // offset, all but that share of the weight.
  const Gaussian2 far{Vector2d(20.0, 0.0), other.covariance};
  const Matrix2d far_mixture = DisagreementMixture(kept, far, quantile);
  const Matrix2d far_limit = SpreadAbout(kept.mean, far);
  EXPECT_NEAR(far_limit(0, 0), 100.0 + other.covariance(0, 0), 1e-12);
  EXPECT_LT((far_mixture - far_limit).norm(), 2e-3 * far_limit.norm());
}

// The fusion right with weight q / d^2, each of the pair's two points with half the rest:
// TwoBodiesMixture is that mixture's second moment about the fused mean, against 200,000
// draws. Within the quantile it is the fused covariance, exactly.
TEST(GaussianFusionTest, TwoBodiesMixtureIsTheThreeHypothesesSecondMoment) {
  const double quantile = 13.815510557964274;  // chi-square, 2 dof, 0.999
  const Gaussian2 lidar{Vector2d(10.0, 0.0), Vector2d(0.0025, 0.01).asDiagonal()};
  Gaussian2 stereo{Vector2d(11.4, 0.1), Matrix2d()};
  stereo.covariance << 0.04, 0.003, 0.003, 0.0025;
  const double d2 =
      MahalanobisSquared(lidar.mean - stereo.mean, lidar.covariance + stereo.covariance);
  ASSERT_GT(d2, 2.0 * quantile);
  const Gaussian2 fused = FuseGaussians(lidar, stereo);
  const double w = quantile / d2;
  const Matrix2d mixture = TwoBodiesMixture(fused, lidar, stereo, quantile);
  const std::uint64_t seed = 20261207;
  Rng rng(seed);
  const int samples = 200000;
  SampleSecondMoment(fused.mean, {fused, lidar, stereo}, {w, 0.5 * (1.0 - w), 0.5 * (1.0 - w)},
                     samples, rng)
      .ExpectNear(mixture, seed);
  const Gaussian2 near{Vector2d(10.2, 0.0), stereo.covariance};
  EXPECT_EQ(TwoBodiesMixture(fused, lidar, near, quantile), fused.covariance);
}

}  // namespace
}  // namespace lookout::fusion
