#include "lookout/tracking/imm.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "lookout/core/input_error.h"
#include "lookout/core/chi_square.h"
#include "lookout/tracking/simulation_test_support.h"

namespace lookout::tracking {
namespace {

const std::vector<int> kPosVel = {kX, kY, kVx, kVy};

Gaussian Prior(const Eigen::Vector4d& x) {
  return {x, Eigen::Vector4d(25.0, 25.0, 4.0, 4.0).asDiagonal()};
}

ImmOptions TestImm() { return FourModelImm(0.5, 0.05, 0.1, 0.5, 0.9); }

TEST(Imm, WithOneModelItIsThatModelsKalmanFilterExactly) {
  for (const MotionModel& model :
       {ConstantVelocity(0.7), ConstantAcceleration(0.2), CoordinatedTurnRate(0.5, 1e-3)}) {
    ImmOptions options;
    options.models = {model};
    options.transition = Eigen::MatrixXd::Ones(1, 1);
    options.initial_probabilities = Eigen::VectorXd::Ones(1);
    options.Validate("test", "imm");
    ImmState imm = InitImm(options, Prior({0.0, 0.0, 5.0, 1.0}), kPosVel, 1.0, 0);
    Gaussian kf = imm.modes[0];
    Rng rng(7);
    const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * 4.0;
    for (int k = 0; k < 30; ++k) {
      const Eigen::Vector2d z{5.0 * k + rng.Normal(), 1.0 * k + rng.Normal()};
      imm = Update(options, PredictTo(options, imm, imm.time + 500'000'000), z, R).state;
      kf = UpdateState(PredictState(model, kf, 0.5), z, R).posterior;
    }
    // Exactly: the same operations in the same order.
    EXPECT_EQ(imm.modes[0].mean, kf.mean);
    EXPECT_EQ(imm.modes[0].cov, kf.cov);
    EXPECT_EQ(imm.probabilities(0), 1.0);
  }
}

// Moment matching of equal-size members against the second-moment form
// sum_i w_i (P_i + x_i x_i') - m m', a different formula for the same quantity.
TEST(Imm, MomentMatchPreservesTheMixturesMeanAndCovariance) {
  Rng rng(11);
  std::vector<Gaussian> members;
  for (int i = 0; i < 4; ++i) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(4, 4);
    for (Eigen::Index r = 0; r < 4; ++r) {
      for (Eigen::Index c = 0; c < 4; ++c) a(r, c) = rng.Normal();
    }
    Eigen::VectorXd x(4);
    for (Eigen::Index r = 0; r < 4; ++r) x(r) = rng.Normal(0.0, 10.0);
    members.push_back({x, a * a.transpose() + Eigen::MatrixXd::Identity(4, 4)});
  }
  const Eigen::Vector4d w(0.1, 0.2, 0.3, 0.4);
  const Gaussian g = MomentMatch(std::vector<std::vector<int>>(4, kPosVel), members, w, kPosVel);
  Eigen::VectorXd m = Eigen::VectorXd::Zero(4);
  Eigen::MatrixXd second = Eigen::MatrixXd::Zero(4, 4);
  for (int i = 0; i < 4; ++i) {
    m += w(i) * members[static_cast<std::size_t>(i)].mean;
    second += w(i) * (members[static_cast<std::size_t>(i)].cov +
                      members[static_cast<std::size_t>(i)].mean *
                          members[static_cast<std::size_t>(i)].mean.transpose());
  }
  EXPECT_TRUE(g.mean.isApprox(m, 1e-12));
  EXPECT_TRUE(g.cov.isApprox(second - m * m.transpose(), 1e-10));
}

// Unequal sizes: CV (4) and CA (6). The common block is the mixture of the members' marginals;
// the acceleration is the CA member's own (the only carrier), not shrunk towards zero by CV's
// weight, and its cross-covariance with the common block shrinks by CA's weight.
TEST(Imm, MixingUnequalStatesIsUnbiasedInTheMissingComponents) {
  Gaussian cv{Eigen::Vector4d(1.0, 2.0, 3.0, 4.0), Eigen::Matrix4d::Identity() * 2.0};
  Eigen::VectorXd ca_mean(6);
  ca_mean << 3.0, 2.0, 1.0, 0.0, 0.5, -0.5;
  Eigen::MatrixXd ca_cov = Eigen::MatrixXd::Identity(6, 6);
  ca_cov(0, 4) = ca_cov(4, 0) = 0.3;
  const Gaussian ca{ca_mean, ca_cov};
  const Eigen::Vector2d w(0.75, 0.25);
  const std::vector<std::vector<int>> comps = {StateComponents(MotionKind::kConstantVelocity),
                                               StateComponents(MotionKind::kConstantAcceleration)};
  const Gaussian g = MomentMatch(comps, {cv, ca}, w, comps[1]);
  // Common block: direct moment matching of the 4-D marginals.
  const Gaussian common = MomentMatch(
      {kPosVel, kPosVel}, {cv, Gaussian{ca_mean.head(4), ca_cov.topLeftCorner(4, 4)}}, w, kPosVel);
  EXPECT_TRUE(g.mean.head(4).isApprox(common.mean, 1e-12));
  EXPECT_TRUE(g.cov.topLeftCorner(4, 4).isApprox(common.cov, 1e-12));
  EXPECT_DOUBLE_EQ(g.mean(4), 0.5);
  EXPECT_DOUBLE_EQ(g.mean(5), -0.5);
  EXPECT_DOUBLE_EQ(g.cov(4, 4), 1.0);
  EXPECT_DOUBLE_EQ(g.cov(0, 4), 0.25 * 0.3);
}

TEST(Imm, MixingWeightsAreTheBayesRuleOfTheMarkovChain) {
  const ImmOptions options = TestImm();
  ImmState state = InitImm(options, Prior({0, 0, 1, 0}), kPosVel, 1.0, 0);
  state.probabilities = Eigen::Vector4d(0.7, 0.1, 0.15, 0.05);
  const Mixing mixing = MixInto(options, state);
  for (Eigen::Index j = 0; j < 4; ++j) {
    double c = 0.0;
    for (Eigen::Index i = 0; i < 4; ++i) c += options.transition(i, j) * state.probabilities(i);
    EXPECT_NEAR(mixing.predicted_probabilities(j), c, 1e-15);
    EXPECT_NEAR(mixing.weights.col(j).sum(), 1.0, 1e-15);
    EXPECT_NEAR(mixing.weights(0, j), options.transition(0, j) * 0.7 / c, 1e-15);
  }
}

struct ModeRun {
  std::vector<Eigen::VectorXd> probabilities;  // after each update
};

ModeRun RunOnTruth(const ImmOptions& options, const std::vector<Eigen::VectorXd>& truth,
                   double sigma, std::uint64_t seed) {
  Rng rng(seed);
  ImmState state = InitImm(options, Prior(truth.front().head<4>()), kPosVel, 1.0, 0);
  const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * sigma * sigma;
  ModeRun run;
  for (std::size_t k = 1; k < truth.size(); ++k) {
    state = PredictTo(options, state, state.time + kNanosPerSecond);
    state = Update(options, state, testing::Measure(rng, truth[k], sigma), R).state;
    run.probabilities.push_back(state.probabilities);
  }
  return run;
}

TEST(Imm, AConstantVelocityTargetStaysWithConstantVelocityOrAcceleration) {
  for (const std::uint64_t seed : {1U, 2U, 3U}) {
    Rng truth_rng(seed);
    const auto truth = testing::SimulateTruth(truth_rng, ConstantVelocity(0.01),
                                              Eigen::Vector4d(0, 0, 10, 3), 60, 1.0, true);
    const ModeRun run = RunOnTruth(TestImm(), truth, 3.0, seed + 100);
    // After the start-up, CV + CA hold most of the probability on average and at 90 % of the
    // steps (the turn models win a scan now and then on noise alone).
    double sum = 0.0;
    int above = 0, count = 0;
    for (std::size_t k = 10; k < run.probabilities.size(); ++k, ++count) {
      const double straight = run.probabilities[k](0) + run.probabilities[k](1);
      sum += straight;
      above += straight > 0.5 ? 1 : 0;
    }
    EXPECT_GT(sum / count, 0.7) << "seed " << seed;
    EXPECT_GE(above, count * 9 / 10) << "seed " << seed;
  }
}

// 20 s straight at 10 m/s, then a left turn at 0.1 rad/s (a car's U-turn is ~0.3 rad/s), 1 Hz,
// 3 m measurement noise. The left-turn model passes 0.5 within 10 scans of the turn's start on
// every seed (4 to 10 on these seeds: the turn leaves the straight line by v w k^2 / 2, 0.5 k^2 m,
// against 3 m of noise), and from then on the right-turn model never leads.
TEST(Imm, OnASimulatedTurnTheTurnModelTakesOver) {
  constexpr int kWithinSteps = 10;
  for (const std::uint64_t seed : {1U, 2U, 3U, 4U, 5U}) {
    Rng truth_rng(seed);
    auto truth = testing::SimulateTruth(truth_rng, ConstantVelocity(1e-6),
                                        Eigen::Vector4d(0, 0, 10, 0), 21, 1.0, false);
    const auto turn = testing::SimulateTruth(truth_rng, CoordinatedTurn(0.1, 1e-6), truth.back(),
                                             25, 1.0, false);
    truth.insert(truth.end(), turn.begin(), turn.end());
    const ModeRun run = RunOnTruth(TestImm(), truth, 3.0, seed + 200);
    // run.probabilities[k] follows truth[k + 1]; the turn starts after truth[20].
    int first = -1;
    for (int s = 1; s <= 25; ++s) {
      if (run.probabilities[static_cast<std::size_t>(19 + s)](2) > 0.5) {
        first = s;
        break;
      }
    }
    EXPECT_GE(first, 1) << "seed " << seed;
    EXPECT_LE(first, kWithinSteps) << "seed " << seed;
    std::cout << "seed " << seed << ": left-turn model above 0.5 after " << first << " scans\n";
    for (int s = kWithinSteps; s <= 25; ++s) {
      const Eigen::VectorXd& p = run.probabilities[static_cast<std::size_t>(19 + s)];
      EXPECT_LT(p(3), p(2)) << "seed " << seed << " scan " << s;
    }
  }
}

// The IMM on data from one of its models: NEES of position and velocity, averaged over Monte
// Carlo runs, inside the 95 % band of chi-square(4 N) / N at most steps.
TEST(Imm, NeesOnSimulatedDataIsInsideTheChiSquareBand) {
  constexpr std::uint64_t kSeed = 9090;
  Rng rng(kSeed);
  ImmOptions options;
  options.models = {ConstantVelocity(0.5), ConstantAcceleration(0.02)};
  options.transition = Eigen::Matrix2d{{0.95, 0.05}, {0.05, 0.95}};
  options.initial_probabilities = Eigen::Vector2d(0.5, 0.5);
  const double sigma = 5.0;
  const int runs = 100, steps = 40;
  Eigen::VectorXd nees_sum = Eigen::VectorXd::Zero(steps);
  for (int run = 0; run < runs; ++run) {
    const Gaussian prior = Prior({0.0, 0.0, 10.0, 2.0});
    const Eigen::VectorXd start = prior.mean + testing::DrawNormal(rng, prior.cov);
    const auto truth = testing::SimulateTruth(rng, ConstantVelocity(0.5), start, steps, 1.0, true);
    ImmState state = InitImm(options, prior, kPosVel, 0.01, 0);
    for (int k = 0; k < steps; ++k) {
      const Eigen::VectorXd& x = truth[static_cast<std::size_t>(k)];
      state = PredictTo(options, state, state.time + kNanosPerSecond);
      state = Update(options, state, testing::Measure(rng, x, sigma),
                     Eigen::Matrix2d::Identity() * sigma * sigma)
                  .state;
      const Gaussian g = Combine(options, state);
      nees_sum(k) += NormalisedSquare(x - g.mean, g.cov);
    }
  }
  const double lo = ChiSquareQuantile(0.025, 4.0 * runs) / runs;
  const double hi = ChiSquareQuantile(0.975, 4.0 * runs) / runs;
  int outside = 0;
  for (int k = 0; k < steps; ++k) {
    const double nees = nees_sum(k) / runs;
    if (nees < lo || nees > hi) {
      ++outside;
      std::cout << "step " << k << " NEES " << nees << " outside [" << lo << ", " << hi << "]\n";
    }
  }
  EXPECT_LE(outside, 5) << "seed " << kSeed;
}

TEST(Imm, ValidateNamesTheWrongField) {
  ImmOptions options = TestImm();
  options.transition(1, 2) += 0.1;
  try {
    options.Validate("cfg.yaml", "tracking.imm");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "tracking.imm.transition[1]");
  }
  options = TestImm();
  options.initial_probabilities = Eigen::Vector3d(0.2, 0.3, 0.5);
  EXPECT_THROW(options.Validate("cfg.yaml", "imm"), InputError);
}

TEST(Imm, CombinedMeasurementPredictionIsTheMomentMatchOfTheModes) {
  const ImmOptions options = TestImm();
  ImmState state = InitImm(options, Prior({0, 0, 10, 0}), kPosVel, 1.0, 0);
  state = PredictTo(options, state, 2 * kNanosPerSecond);
  const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * 9.0;
  const ImmMeasurementPrediction p = PredictMeasurement(state, R);
  const Gaussian combined = Combine(options, state);
  // H is linear, so predicting the combined state equals combining the predicted measurements.
  EXPECT_TRUE(p.combined.z.isApprox(combined.mean.head<2>(), 1e-12));
  EXPECT_TRUE(p.combined.S.isApprox(combined.cov.topLeftCorner<2, 2>() + R, 1e-12));
}

}  // namespace
}  // namespace lookout::tracking
