#include "lookout/eval/tracking_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lookout::eval {
namespace {

// Two truths tracked 0.3 m off for four frames, then one lost and a false track: every key
// from the counts by hand.
TEST(TrackingMetricsAccumulatorTest, KeysFromCountsByHand) {
  TrackingMetricsAccumulator a;
  for (int k = 0; k < 4; ++k) {
    const double x = static_cast<double>(k);
    a.AddFrame({{1, {x, 0.0}}, {2, {x, 5.0}}}, {{10, {x + 0.3, 0.0}}, {11, {x, 5.3}}});
  }
  a.AddFrame({{1, {4.0, 0.0}}, {2, {4.0, 5.0}}}, {{10, {4.3, 0.0}}, {12, {20.0, 20.0}}});
  const auto v = a.Values("tracking");
  // GT 10, FN 1, FP 1, IDs 0.
  EXPECT_NEAR(v.at("tracking.mota"), 1.0 - 2.0 / 10.0, 1e-12);
  EXPECT_NEAR(v.at("tracking.motp_m"), 0.3, 1e-12);
  EXPECT_EQ(v.at("tracking.id_switches"), 0.0);
  EXPECT_EQ(v.at("tracking.false_positives"), 1.0);
  EXPECT_EQ(v.at("tracking.misses"), 1.0);
  // IDTP 9 of 10 truth and 10 track presences.
  EXPECT_NEAR(v.at("tracking.idf1"), 18.0 / 20.0, 1e-12);
  // GOSPA (c = 2, p = 2, alpha = 2): sqrt(2 * 0.09) in the first four frames, then
  // sqrt(0.09 + 2 + 2) in the last (one missed, one false: c^2 / 2 each).
  const double expected = (4.0 * std::sqrt(0.18) + std::sqrt(4.09)) / 5.0;
  EXPECT_NEAR(v.at("tracking.gospa_m"), expected, 1e-12);
  EXPECT_NEAR(std::pow(v.at("tracking.gospa_missed_m"), 2.0), 2.0 / 5.0, 1e-12);
  EXPECT_EQ(v.at("tracking.frames"), 5.0);
}

TEST(TrackingMetricsAccumulatorTest, WithoutTruthOnlyFalseTracksAreScored) {
  TrackingMetricsAccumulator a;
  a.AddFrame({}, {{3, {1.0, 1.0}}});
  a.AddFrame({}, {});
  const auto v = a.Values("t");
  EXPECT_FALSE(v.contains("t.mota"));
  EXPECT_NEAR(v.at("t.gospa_m"), std::sqrt(2.0) / 2.0, 1e-12);
  EXPECT_EQ(v.at("t.false_positives"), 1.0);
}

}  // namespace
}  // namespace lookout::eval
