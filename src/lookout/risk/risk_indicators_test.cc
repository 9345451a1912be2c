#include "lookout/risk/risk_indicators.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lookout::risk {
namespace {

constexpr double kDt = 0.1;

CircleTrack Straight(const Eigen::Vector2d& start, const Eigen::Vector2d& velocity, double radius) {
  CircleTrack t;
  for (int k = 0; k <= 50; ++k) {
    t.centre_m.push_back(start + velocity * (k * kDt));
    t.radius_m.push_back(radius);
  }
  return t;
}

// Head-on with only the lateral position uncertain (sigma): the circles meet iff |dy| <= the
// radii's sum r, so P = erf(r / (sigma sqrt 2)). 20000 samples: within 4 standard errors.
TEST(RiskIndicatorsTest, CollisionProbabilityMatchesTheAnalyticCase) {
  const CircleTrack ego = Straight({0.0, 0.0}, {10.0, 0.0}, 1.0);
  const CircleTrack car = Straight({60.0, 0.0}, {-10.0, 0.0}, 1.0);
  for (const double sigma : {0.5, 1.5, 3.0}) {
    SamplingInput s;
    s.position_covariance << 1e-12, 0.0, 0.0, sigma * sigma;
    s.samples = 20000;
    s.seed = 20261122;
    const double p = CollisionProbability(ego, car, kDt, s);
    const double expected = std::erf(2.0 / (sigma * std::sqrt(2.0)));
    const double tolerance = 4.0 * std::sqrt(expected * (1.0 - expected) / s.samples) + 1e-3;
    EXPECT_NEAR(p, expected, tolerance) << "sigma " << sigma << ", seed " << s.seed;
  }
}

TEST(RiskIndicatorsTest, CollisionProbabilityIsDeterministicPerSeed) {
  const CircleTrack ego = Straight({0.0, 0.0}, {10.0, 0.0}, 1.0);
  const CircleTrack car = Straight({60.0, 1.0}, {-10.0, 0.0}, 1.0);
  SamplingInput s;
  s.position_covariance = Eigen::Matrix2d::Identity() * 2.0;
  s.velocity_covariance = Eigen::Matrix2d::Identity() * 0.5;
  s.seed = 5;
  EXPECT_EQ(CollisionProbability(ego, car, kDt, s), CollisionProbability(ego, car, kDt, s));
}

// Crossing paths that miss by a known time: the ego (east at 10 m/s from x = -30) occupies the
// crossing around t = 3 s, the other (north at 8 m/s from y = -32) around t = 4 s. With point
// circles of radius 0.05 m, the places coincide only at the crossing: PET = 1 s.
TEST(RiskIndicatorsTest, PostEncroachmentTimeOfCrossingPaths) {
  const CircleTrack ego = Straight({-30.0, 0.0}, {10.0, 0.0}, 0.05);
  const CircleTrack other = Straight({0.0, -32.0}, {0.0, 8.0}, 0.05);
  const auto pet = PostEncroachmentTime(ego, other, kDt);
  ASSERT_TRUE(pet.has_value());
  EXPECT_NEAR(*pet, 1.0, 1e-9);
  EXPECT_FALSE(PostEncroachmentTime(ego, Straight({0.0, 5.0}, {0.0, 8.0}, 0.05), kDt));
}

}  // namespace
}  // namespace lookout::risk
