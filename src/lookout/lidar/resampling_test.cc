#include "lookout/lidar/resampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "lookout/core/random.h"

namespace lookout::lidar {
namespace {

TEST(Resampling, EffectiveSampleSizeBounds) {
  const std::vector<double> uniform(10, 0.1);
  EXPECT_NEAR(EffectiveSampleSize(uniform), 10.0, 1e-12);
  std::vector<double> one_hot(10, 0.0);
  one_hot[3] = 1.0;
  EXPECT_DOUBLE_EQ(EffectiveSampleSize(one_hot), 1.0);
  // Two equal halves: 2.
  EXPECT_NEAR(EffectiveSampleSize(std::vector<double>{0.5, 0.0, 0.5}), 2.0, 1e-12);
}

TEST(Resampling, NormalisesInTheLogDomain) {
  // exp(-1000) underflows; the normalisation must not.
  const std::vector<double> w =
      NormaliseLogWeights(std::vector<double>{-1000.0, -1000.0 + std::log(3.0)});
  EXPECT_NEAR(w[0], 0.25, 1e-12);
  EXPECT_NEAR(w[1], 0.75, 1e-12);
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> all_impossible = NormaliseLogWeights(std::vector<double>{-inf, -inf});
  EXPECT_DOUBLE_EQ(all_impossible[0], 0.5);
  const std::vector<double> with_nan =
      NormaliseLogWeights(std::vector<double>{0.0, std::numeric_limits<double>::quiet_NaN()});
  EXPECT_DOUBLE_EQ(with_nan[0], 1.0);
  EXPECT_DOUBLE_EQ(with_nan[1], 0.0);
}

TEST(Resampling, LowVarianceKeepsFloorOrCeilOfExpectedCopies) {
  const std::uint64_t seed = 99;
  Rng rng(seed);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t n = 1 + rng.UniformIndex(50);
    std::vector<double> w(n);
    double sum = 0.0;
    for (double& x : w) {
      x = rng.Uniform() < 0.3 ? 0.0 : rng.Uniform();
      sum += x;
    }
    if (sum == 0.0) continue;
    for (double& x : w) x /= sum;
    const std::vector<std::size_t> kept = LowVarianceResample(w, rng.Uniform());
    ASSERT_EQ(kept.size(), n);
    ASSERT_TRUE(std::is_sorted(kept.begin(), kept.end()));
    std::vector<int> copies(n, 0);
    for (std::size_t k : kept) ++copies[k];
    for (std::size_t i = 0; i < n; ++i) {
      const double expected = static_cast<double>(n) * w[i];
      ASSERT_GE(copies[i], static_cast<int>(std::floor(expected - 1e-9)))
          << "seed " << seed << " trial " << trial << " particle " << i;
      ASSERT_LE(copies[i], static_cast<int>(std::ceil(expected + 1e-9)))
          << "seed " << seed << " trial " << trial << " particle " << i;
      if (w[i] == 0.0) {
        ASSERT_EQ(copies[i], 0);
      }
    }
  }
}

TEST(Resampling, UniformWeightsKeepEveryParticleOnce) {
  const std::vector<double> w(7, 1.0 / 7.0);
  for (double u0 : {0.001, 0.3, 0.999}) {
    const std::vector<std::size_t> kept = LowVarianceResample(w, u0);
    for (std::size_t i = 0; i < kept.size(); ++i) EXPECT_EQ(kept[i], i) << "u0 " << u0;
  }
}

}  // namespace
}  // namespace lookout::lidar
