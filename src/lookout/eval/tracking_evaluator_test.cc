// The tracking metrics against published reference values: py-motmetrics' own expectations on
// the MOTChallenge TUD files, and TrackEval's unit-test sequences (../shared/data/README.md
// lists both).

#include "lookout/eval/tracking_evaluator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "lookout/io/mot_challenge.h"

namespace lookout::eval {
namespace {

// Frames of a MOTChallenge ground truth and tracker output, as py-motmetrics'
// compare_to_groundtruth feeds them: every frame in either file, in increasing order, objects
// in file order, IoU distance with a match when 1 - IoU <= 0.5. The TUD ground truth has
// confidence 1 everywhere and no class column, so no row is filtered out.
TrackingScores EvaluateMotChallenge(const std::string& sequence) {
  const std::string dir = std::string(LOOKOUT_SOURCE_DIR) + "/../shared/data/mot/" + sequence;
  std::map<std::int64_t, std::pair<std::vector<BoxObject>, std::vector<BoxObject>>> frames;
  for (const io::MotChallengeRow& r : io::ReadMotChallengeFile(dir + "/gt.txt")) {
    frames[r.frame].first.push_back({r.id, {r.bb_left, r.bb_top, r.bb_width, r.bb_height}});
  }
  for (const io::MotChallengeRow& r : io::ReadMotChallengeFile(dir + "/test.txt")) {
    frames[r.frame].second.push_back({r.id, {r.bb_left, r.bb_top, r.bb_width, r.bb_height}});
  }
  TrackingEvaluator evaluator;
  for (const auto& [frame, objects] : frames) {
    evaluator.AddFrame(IouFrame(objects.first, objects.second, 0.5));
  }
  return evaluator.Scores();
}

struct Reference {
  double idf1, idp, idr, recall, precision;
  int gt, mt, pt, ml, fp, fn, ids, fm;
  double mota, motp;
};

void ExpectReference(const std::string& name, const TrackingScores& s, const Reference& r) {
  // The row as computed, in the reference table's column order (docs/tracking-metrics.md
  // quotes it).
  std::printf(
      "%-15s IDF1 %.6f IDP %.6f IDR %.6f Rcll %.6f Prcn %.6f GT %lld MT %lld PT %lld "
      "ML %lld FP %lld FN %lld IDs %lld FM %lld MOTA %.6f MOTP %.6f\n",
      name.c_str(), s.identity.Idf1(), s.identity.Idp(), s.identity.Idr(), s.clear.Recall(),
      s.clear.Precision(), static_cast<long long>(s.clear.unique_truths),
      static_cast<long long>(s.clear.mostly_tracked),
      static_cast<long long>(s.clear.partially_tracked),
      static_cast<long long>(s.clear.mostly_lost), static_cast<long long>(s.clear.false_positives),
      static_cast<long long>(s.clear.misses), static_cast<long long>(s.clear.switches),
      static_cast<long long>(s.clear.fragmentations), s.clear.Mota(), s.clear.Motp());
  constexpr double kTolerance = 1e-4;  // the reference is printed to six digits
  EXPECT_NEAR(s.identity.Idf1(), r.idf1, kTolerance);
  EXPECT_NEAR(s.identity.Idp(), r.idp, kTolerance);
  EXPECT_NEAR(s.identity.Idr(), r.idr, kTolerance);
  EXPECT_NEAR(s.clear.Recall(), r.recall, kTolerance);
  EXPECT_NEAR(s.clear.Precision(), r.precision, kTolerance);
  EXPECT_EQ(s.clear.unique_truths, r.gt);
  EXPECT_EQ(s.clear.mostly_tracked, r.mt);
  EXPECT_EQ(s.clear.partially_tracked, r.pt);
  EXPECT_EQ(s.clear.mostly_lost, r.ml);
  EXPECT_EQ(s.clear.false_positives, r.fp);
  EXPECT_EQ(s.clear.misses, r.fn);
  EXPECT_EQ(s.clear.switches, r.ids);
  EXPECT_EQ(s.clear.fragmentations, r.fm);
  EXPECT_NEAR(s.clear.Mota(), r.mota, kTolerance);
  EXPECT_NEAR(s.clear.Motp(), r.motp, kTolerance);
}

// py-motmetrics, test_metrics.py::test_motchallenge_files (../shared/data/README.md).
TEST(TrackingEvaluatorReference, TudCampus) {
  ExpectReference("TUD-Campus", EvaluateMotChallenge("TUD-Campus"),
                  {0.557659, 0.729730, 0.451253, 0.582173, 0.941441, 8, 1, 6, 1, 13, 150, 7, 7,
                   0.526462, 0.277201});
}

TEST(TrackingEvaluatorReference, TudStadtmitte) {
  ExpectReference("TUD-Stadtmitte", EvaluateMotChallenge("TUD-Stadtmitte"),
                  {0.644619, 0.819760, 0.531142, 0.608997, 0.939920, 10, 5, 4, 1, 45, 452, 7, 6,
                   0.564014, 0.345904});
}

TEST(TrackingEvaluatorReference, BothTudSequencesTogether) {
  ExpectReference("both together",
                  EvaluateMotChallenge("TUD-Campus") + EvaluateMotChallenge("TUD-Stadtmitte"),
                  {0.624296, 0.799176, 0.512211, 0.602640, 0.940268, 18, 6, 10, 2, 58, 602, 14, 13,
                   0.555116, 0.330177});
}

// TrackEval's tests/test_metrics.py sequences, rebuilt: per frame the truths and trackers
// present and the pairs whose similarity is 1 (all others 0). TrackEval matches at
// similarity >= 0.5, i.e. distance 1 - similarity <= 0.5.
struct DenseSequence {
  std::vector<std::vector<int>> truth_present;         // [frame][truth] in {0, 1}
  std::vector<std::vector<int>> tracker_present;       // [frame][tracker]
  std::vector<std::vector<std::vector<int>>> similar;  // [frame][truth][tracker]
};

TrackingScores EvaluateDense(const DenseSequence& s) {
  TrackingEvaluator evaluator;
  for (std::size_t t = 0; t < s.truth_present.size(); ++t) {
    MotFrame frame;
    std::vector<std::size_t> truths, trackers;
    for (std::size_t i = 0; i < s.truth_present[t].size(); ++i) {
      if (s.truth_present[t][i]) truths.push_back(i);
    }
    for (std::size_t j = 0; j < s.tracker_present[t].size(); ++j) {
      if (s.tracker_present[t][j]) trackers.push_back(j);
    }
    frame.distance.resize(static_cast<Eigen::Index>(truths.size()),
                          static_cast<Eigen::Index>(trackers.size()));
    for (std::size_t a = 0; a < truths.size(); ++a) {
      frame.truth_ids.push_back(static_cast<std::int64_t>(truths[a]));
      for (std::size_t b = 0; b < trackers.size(); ++b) {
        const double distance = 1.0 - s.similar[t][truths[a]][trackers[b]];
        frame.distance(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) =
            distance <= 0.5 ? distance : std::numeric_limits<double>::infinity();
      }
    }
    for (const std::size_t j : trackers) {
      frame.hypothesis_ids.push_back(static_cast<std::int64_t>(j));
    }
    evaluator.AddFrame(frame);
  }
  return evaluator.Scores();
}

// Columns as TrackEval writes them: similarity[:, i, j] = per-frame values.
DenseSequence MakeDense(
    std::size_t frames, std::vector<std::vector<int>> truth_columns,
    std::vector<std::vector<int>> tracker_columns,
    const std::vector<std::tuple<std::size_t, std::size_t, std::vector<int>>>& similarity_columns) {
  DenseSequence s;
  s.truth_present.assign(frames, std::vector<int>(truth_columns.size()));
  s.tracker_present.assign(frames, std::vector<int>(tracker_columns.size()));
  s.similar.assign(frames, std::vector<std::vector<int>>(truth_columns.size(),
                                                         std::vector<int>(tracker_columns.size())));
  for (std::size_t t = 0; t < frames; ++t) {
    for (std::size_t i = 0; i < truth_columns.size(); ++i) {
      s.truth_present[t][i] = truth_columns[i][t];
    }
    for (std::size_t j = 0; j < tracker_columns.size(); ++j) {
      s.tracker_present[t][j] = tracker_columns[j][t];
    }
    for (const auto& [i, j, values] : similarity_columns) s.similar[t][i][j] = values[t];
  }
  return s;
}

TEST(TrackingEvaluatorReference, TrackEvalNoConfusion) {
  const TrackingScores s = EvaluateDense(
      MakeDense(5, {{1, 1, 1, 1, 1}, {1, 1, 1, 0, 0}}, {{1, 1, 1, 1, 0}, {1, 1, 1, 1, 1}},
                {{0, 1, {0, 0, 0, 1, 1}}, {1, 0, {1, 1, 0, 0, 0}}}));
  EXPECT_EQ(s.clear.matches, 4);
  EXPECT_EQ(s.clear.misses, 4);
  EXPECT_EQ(s.clear.false_positives, 5);
  EXPECT_EQ(s.clear.switches, 0);
  EXPECT_DOUBLE_EQ(s.clear.Mota(), 1.0 - 9.0 / 8.0);
  EXPECT_EQ(s.identity.true_positives, 4);
  EXPECT_EQ(s.identity.false_negatives, 4);
  EXPECT_EQ(s.identity.false_positives, 5);
  EXPECT_DOUBLE_EQ(s.identity.Idr(), 4.0 / 8.0);
  EXPECT_DOUBLE_EQ(s.identity.Idp(), 4.0 / 9.0);
  EXPECT_DOUBLE_EQ(s.identity.Idf1(), 8.0 / 17.0);
}

TEST(TrackingEvaluatorReference, TrackEvalWithConfusion) {
  const TrackingScores s = EvaluateDense(MakeDense(5, {{1, 1, 1, 1, 1}, {1, 1, 1, 0, 0}},
                                                   {{1, 1, 1, 1, 0}, {1, 1, 1, 1, 1}},
                                                   {{0, 1, {0, 0, 0, 1, 1}},
                                                    {1, 0, {1, 1, 0, 0, 0}},
                                                    {0, 0, {0, 0, 1, 0, 0}},
                                                    {1, 1, {0, 1, 0, 0, 0}}}));
  EXPECT_EQ(s.clear.matches, 5);
  EXPECT_EQ(s.clear.misses, 3);
  EXPECT_EQ(s.clear.false_positives, 4);
  EXPECT_EQ(s.clear.switches, 1);
  EXPECT_DOUBLE_EQ(s.clear.Mota(), 0.0);
  EXPECT_EQ(s.identity.true_positives, 4);
  EXPECT_EQ(s.identity.false_negatives, 4);
  EXPECT_EQ(s.identity.false_positives, 5);
  EXPECT_DOUBLE_EQ(s.identity.Idf1(), 8.0 / 17.0);
}

TEST(TrackingEvaluatorReference, TrackEvalSplitTracks) {
  const TrackingScores s = EvaluateDense(MakeDense(
      5, {{1, 1, 0, 1, 1}, {1, 1, 1, 1, 1}},
      {{1, 1, 0, 0, 0}, {0, 0, 1, 1, 1}, {0, 0, 0, 0, 1}, {0, 0, 1, 1, 1}, {1, 1, 0, 0, 0}},
      {{0, 0, {1, 1, 0, 0, 0}},
       {0, 3, {0, 0, 0, 1, 1}},
       {1, 1, {0, 0, 1, 1, 0}},
       {1, 2, {0, 0, 0, 0, 1}},
       {1, 4, {1, 1, 0, 0, 0}}}));
  EXPECT_EQ(s.clear.matches, 9);
  EXPECT_EQ(s.clear.misses, 0);
  EXPECT_EQ(s.clear.false_positives, 2);
  EXPECT_EQ(s.clear.switches, 3);
  EXPECT_DOUBLE_EQ(s.clear.Mota(), 1.0 - 5.0 / 9.0);
  EXPECT_EQ(s.identity.true_positives, 4);
  EXPECT_EQ(s.identity.false_negatives, 5);
  EXPECT_EQ(s.identity.false_positives, 7);
  EXPECT_DOUBLE_EQ(s.identity.Idr(), 4.0 / 9.0);
  EXPECT_DOUBLE_EQ(s.identity.Idp(), 4.0 / 11.0);
  EXPECT_DOUBLE_EQ(s.identity.Idf1(), 8.0 / 20.0);
}

TEST(TrackingEvaluator, EmptySequenceGivesNaNRatesAndZeroCounts) {
  TrackingEvaluator evaluator;
  evaluator.AddFrame(MotFrame{});
  const TrackingScores s = evaluator.Scores();
  EXPECT_EQ(s.clear.frames, 1);
  EXPECT_EQ(s.clear.matches, 0);
  EXPECT_TRUE(std::isnan(s.clear.Mota()));
  EXPECT_TRUE(std::isnan(s.clear.Motp()));
  EXPECT_TRUE(std::isnan(s.identity.Idf1()));
}

}  // namespace
}  // namespace lookout::eval
