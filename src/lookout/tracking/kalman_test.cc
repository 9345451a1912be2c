#include "lookout/tracking/kalman.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "lookout/core/chi_square.h"
#include "lookout/tracking/simulation_test_support.h"

namespace lookout::tracking {
namespace {

// The Joseph form equals the textbook P - K S K' for the optimal gain.
TEST(Kalman, JosephUpdateEqualsTheStandardFormForTheOptimalGain) {
  Gaussian prior{Eigen::Vector4d(1.0, 2.0, 3.0, 4.0), Eigen::MatrixXd::Zero(4, 4)};
  Eigen::Matrix4d a;
  a << 4, 1, 0.5, 0, 1, 3, 0, 0.2, 0.5, 0, 2, 0.1, 0, 0.2, 0.1, 1;
  prior.cov = a * a.transpose();
  const Eigen::Matrix2d R = Eigen::Vector2d(2.0, 3.0).asDiagonal();
  const Eigen::Vector2d z(2.0, 0.5);
  const UpdateResult u = UpdateState(prior, z, R);

  Eigen::Matrix<double, 2, 4> H = Eigen::Matrix<double, 2, 4>::Zero();
  H(0, 0) = H(1, 1) = 1.0;
  const Eigen::Matrix2d S = H * prior.cov * H.transpose() + R;
  const Eigen::MatrixXd K = prior.cov * H.transpose() * S.inverse();
  EXPECT_TRUE(u.S.isApprox(S));
  EXPECT_TRUE(u.posterior.mean.isApprox(prior.mean + K * (z - H * prior.mean)));
  EXPECT_TRUE(u.posterior.cov.isApprox(prior.cov - K * S * K.transpose(), 1e-12));
  const Eigen::Vector2d nu = z - H * prior.mean;
  EXPECT_NEAR(u.nis, nu.dot(S.inverse() * nu), 1e-12);
  EXPECT_NEAR(
      u.log_likelihood,
      std::log(std::exp(-0.5 * u.nis) / (2.0 * std::numbers::pi * std::sqrt(S.determinant()))),
      1e-12);
}

// Scalar case per axis: prior variance p, noise r: posterior variance p r / (p + r).
TEST(Kalman, PositionOnlyCaseIsTheScalarFormula) {
  Gaussian prior{Eigen::Vector4d::Zero(), Eigen::Matrix4d::Identity() * 4.0};
  const UpdateResult u =
      UpdateState(prior, Eigen::Vector2d(1.0, -1.0), Eigen::Matrix2d::Identity());
  EXPECT_NEAR(u.posterior.cov(0, 0), 0.8, 1e-12);
  EXPECT_NEAR(u.posterior.mean(0), 0.8, 1e-12);
  EXPECT_NEAR(u.posterior.mean(1), -0.8, 1e-12);
  EXPECT_NEAR(u.posterior.cov(2, 2), 4.0, 1e-12);  // velocity uncorrelated: unchanged
}

// A Kalman filter with the truth's model is consistent: the NEES averaged over Monte Carlo runs
// lies in the two-sided 95 % band of chi-square(4 N) / N (Bar-Shalom et al. 2001, section 5.4.2).
TEST(Kalman, NeesOnSimulatedDataIsInsideTheChiSquareBand) {
  constexpr std::uint64_t kSeed = 4004;
  Rng rng(kSeed);
  const MotionModel model = ConstantVelocity(0.5);
  const double sigma = 5.0, dt = 1.0;
  const int runs = 100, steps = 40;
  Eigen::VectorXd nees_sum = Eigen::VectorXd::Zero(steps);
  for (int run = 0; run < runs; ++run) {
    const Eigen::Vector4d x0(0.0, 0.0, 10.0, 2.0);
    Gaussian g{x0, Eigen::Vector4d(25.0, 25.0, 4.0, 4.0).asDiagonal()};
    // The truth starts from a draw of the prior, so the prior is consistent too.
    const Eigen::VectorXd start = x0 + testing::DrawNormal(rng, g.cov);
    const auto truth = testing::SimulateTruth(rng, model, start, steps, dt, true);
    for (int k = 0; k < steps; ++k) {
      g = PredictState(model, g, dt);
      g = UpdateState(g, testing::Measure(rng, truth[static_cast<std::size_t>(k)], sigma),
                      Eigen::Matrix2d::Identity() * sigma * sigma)
              .posterior;
      nees_sum(k) += NormalisedSquare(truth[static_cast<std::size_t>(k)] - g.mean, g.cov);
    }
  }
  const double lo = ChiSquareQuantile(0.025, 4.0 * runs) / runs;
  const double hi = ChiSquareQuantile(0.975, 4.0 * runs) / runs;
  int outside = 0;
  for (int k = 0; k < steps; ++k) {
    const double nees = nees_sum(k) / runs;
    if (nees < lo || nees > hi) ++outside;
  }
  // 95 % bands: about 2 of 40 steps fall outside by chance; 6 or more would be a fault.
  EXPECT_LE(outside, 5) << "seed " << kSeed << ", band [" << lo << ", " << hi << "]";
}

}  // namespace
}  // namespace lookout::tracking
