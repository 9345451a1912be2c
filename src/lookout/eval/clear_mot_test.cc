#include "lookout/eval/clear_mot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace lookout::eval {
namespace {

constexpr double kNo = std::numeric_limits<double>::infinity();

MotFrame Frame(std::vector<std::int64_t> truths, std::vector<std::int64_t> hypotheses,
               std::vector<std::vector<double>> distance) {
  MotFrame f{std::move(truths), std::move(hypotheses), {}};
  f.distance.resize(static_cast<Eigen::Index>(f.truth_ids.size()),
                    static_cast<Eigen::Index>(f.hypothesis_ids.size()));
  for (std::size_t i = 0; i < distance.size(); ++i) {
    for (std::size_t j = 0; j < distance[i].size(); ++j) {
      f.distance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = distance[i][j];
    }
  }
  return f;
}

// py-motmetrics' README walk-through (truths a = 1, b = 2).
TEST(ClearMot, PyMotmetricsReadmeExample) {
  ClearMotAccumulator acc;
  // Frame 0: a-1 (0.1) and b-2 (0.2) match, 3 is a false positive.
  acc.AddFrame(Frame({1, 2}, {1, 2, 3}, {{0.1, kNo, 0.3}, {0.5, 0.2, 0.3}}));
  // Frame 1: a keeps 1, b is missed.
  acc.AddFrame(Frame({1, 2}, {1}, {{0.2}, {0.4}}));
  // Frame 2: a keeps 1 although a-3 (0.2) would be cheaper: earlier correspondences come
  // first. b takes 3, a switch from 2.
  acc.AddFrame(Frame({1, 2}, {1, 3}, {{0.6, 0.2}, {0.1, 0.6}}));
  const ClearMotCounts c = acc.Counts();
  EXPECT_EQ(c.frames, 3);
  EXPECT_EQ(c.truth_objects, 6);
  EXPECT_EQ(c.matches, 5);
  EXPECT_EQ(c.switches, 1);
  EXPECT_EQ(c.false_positives, 1);
  EXPECT_EQ(c.misses, 1);
  EXPECT_NEAR(c.distance_sum, 0.1 + 0.2 + 0.2 + 0.6 + 0.6, 1e-12);
  EXPECT_NEAR(c.Motp(), 1.7 / 5.0, 1e-12);
  EXPECT_NEAR(c.Mota(), 1.0 - 3.0 / 6.0, 1e-12);
  EXPECT_NEAR(c.Recall(), 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(c.Precision(), 5.0 / 6.0, 1e-12);
  EXPECT_EQ(c.fragmentations, 1);  // b: matched, missed, matched
}

TEST(ClearMot, CorrespondenceSurvivesAGapButNotTheThreshold) {
  ClearMotAccumulator acc;
  acc.AddFrame(Frame({7}, {1}, {{0.5}}));
  acc.AddFrame(Frame({}, {}, {}));                 // 7 absent: not a miss
  acc.AddFrame(Frame({7}, {1, 2}, {{0.9, 0.1}}));  // back: keeps 1, no switch
  acc.AddFrame(Frame({7}, {1, 2}, {{kNo, 0.1}}));  // 1 out of reach: 2, a switch
  const ClearMotCounts c = acc.Counts();
  EXPECT_EQ(c.frames, 4);
  EXPECT_EQ(c.matches, 3);
  EXPECT_EQ(c.switches, 1);
  EXPECT_EQ(c.misses, 0);
  EXPECT_EQ(c.false_positives, 2);
  EXPECT_EQ(c.fragmentations, 0);
}

TEST(ClearMot, FragmentationsCountInteriorMissRunsOnly) {
  ClearMotAccumulator acc;
  const auto seen = [&] { acc.AddFrame(Frame({1}, {5}, {{0.0}})); };
  const auto missed = [&] { acc.AddFrame(Frame({1}, {}, {})); };
  const auto absent = [&] { acc.AddFrame(Frame({}, {}, {})); };
  missed();  // before the first match: no fragment
  seen();
  missed();
  missed();
  seen();  // fragment 1
  missed();
  absent();  // absence neither ends nor starts a run
  seen();    // fragment 2
  missed();  // after the last match: no fragment
  const ClearMotCounts c = acc.Counts();
  EXPECT_EQ(c.fragmentations, 2);
  EXPECT_EQ(c.misses, 5);
  EXPECT_EQ(c.matches, 3);
}

TEST(ClearMot, MostlyTrackedPartlyTrackedMostlyLostAtTheirThresholds) {
  ClearMotAccumulator acc;
  // Truth 1 matched 4 of 5 frames (0.8: MT), truth 2 1 of 5 (0.2: PT), truth 3 0 of 5 (ML),
  // truth 4 3 of 5 (PT).
  const std::vector<std::vector<int>> matched = {
      {1, 1, 1, 1, 0}, {1, 0, 0, 0, 0}, {0, 0, 0, 0, 0}, {1, 1, 1, 0, 0}};
  for (std::size_t t = 0; t < 5; ++t) {
    std::vector<std::int64_t> truths, hyps;
    for (std::size_t k = 0; k < matched.size(); ++k) {
      truths.push_back(static_cast<std::int64_t>(k + 1));
      if (matched[k][t]) hyps.push_back(static_cast<std::int64_t>(10 + k));
    }
    MotFrame f{truths, hyps,
               Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(truths.size()),
                                         static_cast<Eigen::Index>(hyps.size()), kNo)};
    for (std::size_t j = 0; j < hyps.size(); ++j) {
      f.distance(hyps[j] - 10, static_cast<Eigen::Index>(j)) = 0.0;
    }
    acc.AddFrame(f);
  }
  const ClearMotCounts c = acc.Counts();
  EXPECT_EQ(c.unique_truths, 4);
  EXPECT_EQ(c.mostly_tracked, 1);
  EXPECT_EQ(c.partially_tracked, 2);
  EXPECT_EQ(c.mostly_lost, 1);
}

TEST(ClearMot, MatchingPrefersMorePairsToSmallerDistances) {
  // Truth 1 could take hypothesis 1 at 0.1, but then truth 2 would go unmatched: CLEAR MOT
  // counts a match before it weighs distances.
  ClearMotAccumulator acc;
  acc.AddFrame(Frame({1, 2}, {1, 2}, {{0.1, 0.4}, {0.3, kNo}}));
  const ClearMotCounts c = acc.Counts();
  EXPECT_EQ(c.matches, 2);
  EXPECT_NEAR(c.distance_sum, 0.7, 1e-12);
}

TEST(ClearMot, SumOfSequencesAddsCounts) {
  ClearMotAccumulator a, b;
  a.AddFrame(Frame({1}, {1}, {{0.5}}));
  b.AddFrame(Frame({1, 2}, {3}, {{kNo}, {0.25}}));
  const ClearMotCounts s = a.Counts() + b.Counts();
  EXPECT_EQ(s.frames, 2);
  EXPECT_EQ(s.unique_truths, 3);  // ids are per sequence
  EXPECT_EQ(s.matches, 2);
  EXPECT_EQ(s.misses, 1);
  EXPECT_NEAR(s.Motp(), 0.375, 1e-12);
  EXPECT_NEAR(s.Mota(), 1.0 - 1.0 / 3.0, 1e-12);
}

}  // namespace
}  // namespace lookout::eval
