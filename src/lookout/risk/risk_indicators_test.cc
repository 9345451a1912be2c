#include "lookout/risk/risk_indicators.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "lookout/risk/risk_test_support.h"

namespace lookout::risk {
namespace {

using testing::kDt;
using testing::Straight;

// Head-on with only the lateral position uncertain (sigma): the circles meet iff |dy| <= the
// radii's sum r, so P = erf(r / (sigma sqrt 2)). 20000 samples: within 4 standard errors.
TEST(RiskIndicatorsTest, CollisionProbabilityMatchesTheAnalyticCase) {
  const FootprintTrack ego = Straight({0.0, 0.0}, {10.0, 0.0}, 1.0);
  const FootprintTrack car = Straight({60.0, 0.0}, {-10.0, 0.0}, 1.0);
  for (const double sigma : {0.5, 1.5, 3.0}) {
    SamplingInput s;
    s.position_covariance << 1e-12, 0.0, 0.0, sigma * sigma;
    constexpr int kSamples = 20000;
    constexpr std::uint64_t kSeed = 20261122;
    const double p = CollisionProbability(ego, car, kDt, s, DrawStandardNormals(kSamples, kSeed));
    const double expected = std::erf(2.0 / (sigma * std::sqrt(2.0)));
    const double tolerance = 4.0 * std::sqrt(expected * (1.0 - expected) / kSamples) + 1e-3;
    EXPECT_NEAR(p, expected, tolerance) << "sigma " << sigma << ", seed " << kSeed;
  }
}

// The same with boxes (the ego 4.6 x 1.9 m, the car 4.5 x 1.8 m, head-on): they meet iff
// |dy| <= the half-widths' sum, 1.85 m.
TEST(RiskIndicatorsTest, CollisionProbabilityOfBoxesMatchesTheAnalyticCase) {
  FootprintTrack ego, car;
  for (int k = 0; k <= 50; ++k) {
    ego.push_back(Footprint::Box({10.0 * k * kDt, 0.0}, 0.0, 4.6, 1.9));
    car.push_back(Footprint::Box({60.0 - 10.0 * k * kDt, 0.0}, std::numbers::pi, 4.5, 1.8));
  }
  for (const double sigma : {0.5, 1.5, 3.0}) {
    SamplingInput s;
    s.position_covariance << 1e-12, 0.0, 0.0, sigma * sigma;
    constexpr int kSamples = 20000;
    constexpr std::uint64_t kSeed = 20261202;
    const double p = CollisionProbability(ego, car, kDt, s, DrawStandardNormals(kSamples, kSeed));
    const double expected = std::erf(1.85 / (sigma * std::sqrt(2.0)));
    const double tolerance = 4.0 * std::sqrt(expected * (1.0 - expected) / kSamples) + 1e-3;
    EXPECT_NEAR(p, expected, tolerance) << "sigma " << sigma << ", seed " << kSeed;
  }
}

TEST(RiskIndicatorsTest, CollisionProbabilityIsDeterministicPerSeed) {
  const FootprintTrack ego = Straight({0.0, 0.0}, {10.0, 0.0}, 1.0);
  const FootprintTrack car = Straight({60.0, 1.0}, {-10.0, 0.0}, 1.0);
  SamplingInput s;
  s.position_covariance = Eigen::Matrix2d::Identity() * 2.0;
  s.velocity_covariance = Eigen::Matrix2d::Identity() * 0.5;
  EXPECT_EQ(CollisionProbability(ego, car, kDt, s, DrawStandardNormals(1000, 5)),
            CollisionProbability(ego, car, kDt, s, DrawStandardNormals(1000, 5)));
}

// Crossing paths that miss by a known time: the ego (east at 10 m/s from x = -30) occupies the
// crossing around t = 3 s, the other (north at 8 m/s from y = -32) around t = 4 s. With point
// circles of radius 0.05 m, the places coincide only at the crossing: PET = 1 s.
TEST(RiskIndicatorsTest, PostEncroachmentTimeOfCrossingPaths) {
  const FootprintTrack ego = Straight({-30.0, 0.0}, {10.0, 0.0}, 0.05);
  const FootprintTrack other = Straight({0.0, -32.0}, {0.0, 8.0}, 0.05);
  const auto pet = PostEncroachmentTime(ego, other, kDt);
  ASSERT_TRUE(pet.has_value());
  EXPECT_NEAR(*pet, 1.0, 1e-9);
  EXPECT_FALSE(PostEncroachmentTime(ego, Straight({0.0, 5.0}, {0.0, 8.0}, 0.05), kDt));
}

}  // namespace
}  // namespace lookout::risk

namespace lookout::risk {
namespace {

// The shortcut for far objects (no sample drawn beyond 6 sigma) must not change a probability
// that sampling would find: an object 6.5 sigma away still reads 0, one at 3 sigma does not.
TEST(RiskIndicatorsTest, FarObjectsAreZeroWithoutSampling) {
  const FootprintTrack ego = Straight({0.0, 0.0}, {10.0, 0.0}, 1.0);
  SamplingInput s;
  s.position_covariance = Eigen::Matrix2d::Identity();  // sigma 1 m
  const auto normals = DrawStandardNormals(20000, 9);
  // Nominal gap: lateral offset minus the reach of 2 m.
  EXPECT_EQ(CollisionProbability(ego, Straight({60.0, 8.5}, {-10.0, 0.0}, 1.0), kDt, s, normals),
            0.0);
  const double p3 =
      CollisionProbability(ego, Straight({60.0, 5.0}, {-10.0, 0.0}, 1.0), kDt, s, normals);
  EXPECT_NEAR(p3, 0.5 * std::erfc(3.0 / std::sqrt(2.0)), 0.002);
}

}  // namespace
}  // namespace lookout::risk
