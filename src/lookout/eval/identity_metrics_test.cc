#include "lookout/eval/identity_metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>

#include "lookout/core/random.h"

namespace lookout::eval {
namespace {

constexpr double kNoMatch = std::numeric_limits<double>::infinity();

TEST(IdentityMetrics, OneTruthSplitBetweenTwoTracks) {
  // Truth 1 for 10 frames: track 5 covers frames 0-5, track 6 frames 6-9. The best single
  // identity is track 5: IDTP 6, IDFN 4, IDFP 4.
  IdentityAccumulator acc;
  for (int t = 0; t < 10; ++t) {
    const std::int64_t track = t < 6 ? 5 : 6;
    acc.AddFrame(MotFrame{{1}, {track}, Eigen::MatrixXd::Constant(1, 1, 0.1)});
  }
  const IdentityCounts c = acc.Counts();
  EXPECT_EQ(c.true_positives, 6);
  EXPECT_EQ(c.false_negatives, 4);
  EXPECT_EQ(c.false_positives, 4);
  EXPECT_DOUBLE_EQ(c.Idp(), 0.6);
  EXPECT_DOUBLE_EQ(c.Idr(), 0.6);
  EXPECT_DOUBLE_EQ(c.Idf1(), 0.6);
}

// Literal reference: the best one-to-one matching of truth ids to hypothesis ids by trying
// every injective map (small id counts only).
std::int64_t BruteForceIdtp(const std::map<std::pair<int, int>, std::int64_t>& together, int truths,
                            int hypotheses) {
  std::int64_t best = 0;
  std::vector<char> used(static_cast<std::size_t>(hypotheses), 0);
  std::function<void(int, std::int64_t)> visit = [&](int i, std::int64_t sum) {
    if (i == truths) {
      best = std::max(best, sum);
      return;
    }
    visit(i + 1, sum);
    for (int j = 0; j < hypotheses; ++j) {
      if (used[static_cast<std::size_t>(j)]) continue;
      used[static_cast<std::size_t>(j)] = 1;
      const auto it = together.find({i, j});
      visit(i + 1, sum + (it == together.end() ? 0 : it->second));
      used[static_cast<std::size_t>(j)] = 0;
    }
  };
  visit(0, 0);
  return best;
}

TEST(IdentityMetrics, MatchesBruteForceOnRandomSequences) {
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    Rng rng(seed);
    const int truths = 1 + static_cast<int>(rng.UniformIndex(4));
    const int hypotheses = 1 + static_cast<int>(rng.UniformIndex(5));
    IdentityAccumulator acc;
    std::map<std::pair<int, int>, std::int64_t> together;
    std::int64_t truth_total = 0, hypothesis_total = 0;
    for (int t = 0; t < 12; ++t) {
      MotFrame f;
      for (int i = 0; i < truths; ++i) {
        if (rng.Bernoulli(0.8)) f.truth_ids.push_back(i);
      }
      for (int j = 0; j < hypotheses; ++j) {
        if (rng.Bernoulli(0.7)) f.hypothesis_ids.push_back(j);
      }
      f.distance.resize(static_cast<Eigen::Index>(f.truth_ids.size()),
                        static_cast<Eigen::Index>(f.hypothesis_ids.size()));
      for (std::size_t a = 0; a < f.truth_ids.size(); ++a) {
        for (std::size_t b = 0; b < f.hypothesis_ids.size(); ++b) {
          const bool close = rng.Bernoulli(0.4);
          f.distance(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) =
              close ? rng.Uniform() : kNoMatch;
          if (close) {
            ++together[{static_cast<int>(f.truth_ids[a]), static_cast<int>(f.hypothesis_ids[b])}];
          }
        }
      }
      truth_total += static_cast<std::int64_t>(f.truth_ids.size());
      hypothesis_total += static_cast<std::int64_t>(f.hypothesis_ids.size());
      acc.AddFrame(f);
    }
    const IdentityCounts c = acc.Counts();
    const std::int64_t idtp = BruteForceIdtp(together, truths, hypotheses);
    ASSERT_EQ(c.true_positives, idtp) << "seed " << seed;
    ASSERT_EQ(c.false_negatives, truth_total - idtp) << "seed " << seed;
    ASSERT_EQ(c.false_positives, hypothesis_total - idtp) << "seed " << seed;
  }
}

TEST(IdentityMetrics, NoHypothesesAtAll) {
  IdentityAccumulator acc;
  acc.AddFrame(MotFrame{{1, 2}, {}, Eigen::MatrixXd(2, 0)});
  const IdentityCounts c = acc.Counts();
  EXPECT_EQ(c.true_positives, 0);
  EXPECT_EQ(c.false_negatives, 2);
  EXPECT_EQ(c.false_positives, 0);
  EXPECT_DOUBLE_EQ(c.Idf1(), 0.0);
  EXPECT_TRUE(std::isnan(c.Idp()));
}

}  // namespace
}  // namespace lookout::eval
