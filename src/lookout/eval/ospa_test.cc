#include "lookout/eval/ospa.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

#include "lookout/core/random.h"

namespace lookout::eval {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<Eigen::Vector2d> OnLine(std::vector<double> xs) {
  std::vector<Eigen::Vector2d> points;
  for (const double x : xs) points.emplace_back(x, 0.0);
  return points;
}

// ../shared/data/README.md: OSPA with c = 10 and p in {1, 2, inf}.
TEST(Ospa, ReferenceCases) {
  for (const double p : {1.0, 2.0, kInf}) {
    const OspaOptions o{10.0, p};
    EXPECT_NEAR(Ospa(OnLine({0, 1, 2, 3, 4}), OnLine({0.5, 1.5, 2.5, 3.5, 4.5}), o), 0.5, 1e-12)
        << "p " << p;
    EXPECT_NEAR(Ospa(OnLine({1, 2, 3, 4, 5}), OnLine({1.2, 2.2, 3.2, 4.2, 5.2}), o), 0.2, 1e-12)
        << "p " << p;
  }
}

TEST(Ospa, CardinalityAndEmptySets) {
  const OspaOptions o{10.0, 2.0};
  EXPECT_EQ(Ospa({}, {}, o), 0.0);
  EXPECT_EQ(Ospa(OnLine({1}), {}, o), 10.0);
  EXPECT_EQ(Ospa({}, OnLine({1, 2}), o), 10.0);
  // One exact pair and one extra estimate: sqrt((0 + 10^2) / 2).
  EXPECT_NEAR(Ospa(OnLine({0}), OnLine({0, 50}), o), std::sqrt(50.0), 1e-12);
  // Symmetric in its arguments.
  EXPECT_NEAR(Ospa(OnLine({0, 50}), OnLine({0}), o), std::sqrt(50.0), 1e-12);
  // Distances beyond c are cut off.
  EXPECT_NEAR(Ospa(OnLine({0}), OnLine({1000}), o), 10.0, 1e-12);
  EXPECT_EQ(Ospa(OnLine({0}), OnLine({0, 1}), OspaOptions{10.0, kInf}), 10.0);
}

// Literal reference: every injection of the smaller set into the larger.
double BruteForceOspa(const std::vector<Eigen::Vector2d>& x, const std::vector<Eigen::Vector2d>& y,
                      double c, double p) {
  const auto& fewer = x.size() <= y.size() ? x : y;
  const auto& more = x.size() <= y.size() ? y : x;
  if (more.empty()) return 0.0;
  std::vector<std::size_t> perm(more.size());
  std::iota(perm.begin(), perm.end(), 0);
  double best = kInf;
  do {
    double sum = 0.0, worst = 0.0;
    for (std::size_t i = 0; i < fewer.size(); ++i) {
      const double d = std::min((fewer[i] - more[perm[i]]).norm(), c);
      sum += std::pow(d, std::isinf(p) ? 1.0 : p);
      worst = std::max(worst, d);
    }
    if (std::isinf(p)) {
      best = std::min(best, fewer.size() == more.size() ? worst : c);
    } else {
      const double extra = static_cast<double>(more.size() - fewer.size());
      best = std::min(
          best,
          std::pow((sum + std::pow(c, p) * extra) / static_cast<double>(more.size()), 1.0 / p));
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

TEST(Ospa, MatchesBruteForceOnRandomSets) {
  for (std::uint64_t seed = 1; seed <= 400; ++seed) {
    Rng rng(seed);
    std::vector<Eigen::Vector2d> x, y;
    const std::size_t nx = rng.UniformIndex(5), ny = rng.UniformIndex(5);
    for (std::size_t i = 0; i < nx; ++i) x.push_back({rng.Uniform(0, 8), rng.Uniform(0, 8)});
    for (std::size_t i = 0; i < ny; ++i) y.push_back({rng.Uniform(0, 8), rng.Uniform(0, 8)});
    for (const double p : {1.0, 2.0, 3.0, kInf}) {
      const double c = 4.0;
      ASSERT_NEAR(Ospa(x, y, {c, p}), BruteForceOspa(x, y, c, p), 1e-9)
          << "seed " << seed << " p " << p;
    }
  }
}

// ../shared/data/README.md: GOSPA with c = 10, p = 1, alpha = 2, five pairs off by 0.5.
TEST(Gospa, ReferenceCase) {
  const GospaResult r =
      Gospa(OnLine({0, 1, 2, 3, 4}), OnLine({0.5, 1.5, 2.5, 3.5, 4.5}), {10.0, 1.0, 2.0});
  EXPECT_NEAR(r.distance, 2.5, 1e-12);
  EXPECT_NEAR(r.localisation_pth, 2.5, 1e-12);
  EXPECT_EQ(r.assigned, 5);
  EXPECT_EQ(r.missed, 0);
  EXPECT_EQ(r.false_targets, 0);
}

TEST(Gospa, DecompositionIntoLocalisationMissedAndFalse) {
  // c = 2, p = 2: truths at 0 and 100, estimates at 0.5, 3 and 50. Truth 0 pairs with 0.5
  // (0.25); truth 100 is missed; estimates 3 and 50 are false: 0.25 + 3 * 4 / 2 = 6.25.
  const GospaResult r = Gospa(OnLine({0, 100}), OnLine({0.5, 3, 50}), {2.0, 2.0, 2.0});
  EXPECT_NEAR(r.distance, 2.5, 1e-12);
  EXPECT_NEAR(r.localisation_pth, 0.25, 1e-12);
  EXPECT_NEAR(r.missed_pth, 2.0, 1e-12);
  EXPECT_NEAR(r.false_pth, 4.0, 1e-12);
  EXPECT_EQ(r.assigned, 1);
  EXPECT_EQ(r.missed, 1);
  EXPECT_EQ(r.false_targets, 2);
  EXPECT_NEAR(r.localisation_pth + r.missed_pth + r.false_pth, std::pow(r.distance, 2.0), 1e-12);
  // Swapping the sets swaps missed and false.
  const GospaResult s = Gospa(OnLine({0.5, 3, 50}), OnLine({0, 100}), {2.0, 2.0, 2.0});
  EXPECT_NEAR(s.distance, r.distance, 1e-12);
  EXPECT_EQ(s.missed, 2);
  EXPECT_EQ(s.false_targets, 1);
}

TEST(Gospa, EmptySetsAndOtherAlpha) {
  EXPECT_EQ(Gospa({}, {}, {}).distance, 0.0);
  // Three misses at c = 2, p = 2, alpha = 2: sqrt(3 * 4 / 2).
  EXPECT_NEAR(Gospa(OnLine({0, 5, 9}), {}, {2.0, 2.0, 2.0}).distance, std::sqrt(6.0), 1e-12);
  const GospaResult r = Gospa(OnLine({0}), OnLine({0, 5}), {2.0, 1.0, 1.0});
  EXPECT_NEAR(r.distance, 2.0, 1e-12);  // c^p / alpha for the extra estimate
  EXPECT_TRUE(std::isnan(r.localisation_pth));
}

TEST(Gospa, MatchesBruteForceOnRandomSets) {
  for (std::uint64_t seed = 1; seed <= 400; ++seed) {
    Rng rng(seed);
    std::vector<Eigen::Vector2d> x, y;
    const std::size_t nx = rng.UniformIndex(5), ny = rng.UniformIndex(5);
    for (std::size_t i = 0; i < nx; ++i) x.push_back({rng.Uniform(0, 8), rng.Uniform(0, 8)});
    for (std::size_t i = 0; i < ny; ++i) y.push_back({rng.Uniform(0, 8), rng.Uniform(0, 8)});
    const double c = 3.0, p = 2.0;
    // Both minimise the same sum over the same assignments; OSPA charges c^p for each
    // unassigned element and divides by n, GOSPA (alpha = 2) charges c^p / 2:
    // GOSPA^p = n OSPA^p - c^p / 2 (n - m).
    const double n = static_cast<double>(std::max(nx, ny));
    const double m = static_cast<double>(std::min(nx, ny));
    const double expected =
        n > 0
            ? std::pow(n * std::pow(BruteForceOspa(x, y, c, p), p) - std::pow(c, p) / 2.0 * (n - m),
                       1.0 / p)
            : 0.0;
    const GospaResult r = Gospa(x, y, {c, p, 2.0});
    ASSERT_NEAR(r.distance, expected, 1e-9) << "seed " << seed;
    ASSERT_NEAR(r.localisation_pth + r.missed_pth + r.false_pth, std::pow(r.distance, p), 1e-9)
        << "seed " << seed;
    ASSERT_EQ(r.assigned + r.missed, static_cast<int>(nx)) << "seed " << seed;
    ASSERT_EQ(r.assigned + r.false_targets, static_cast<int>(ny)) << "seed " << seed;
  }
}

}  // namespace
}  // namespace lookout::eval
