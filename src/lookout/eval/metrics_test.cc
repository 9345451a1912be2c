#include "lookout/eval/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lookout/eval/statistics.h"

namespace lookout::eval {
namespace {

TEST(MedianTest, OddEvenAndEmpty) {
  EXPECT_DOUBLE_EQ(Median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(Median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_TRUE(std::isnan(Median({})));
}

TEST(SummariseTest, MeanMinMaxPerKeySkippingNonFinite) {
  const std::vector<ScenarioMetrics> s = {
      {"a", {{"x", 1.0}, {"y", 5.0}}},
      {"b", {{"x", 3.0}, {"y", std::numeric_limits<double>::quiet_NaN()}}},
      {"c", {{"x", 8.0}}}};
  const auto summary = Summarise(s);
  EXPECT_EQ(summary.at("x").count, 3);
  EXPECT_DOUBLE_EQ(summary.at("x").mean, 4.0);
  EXPECT_DOUBLE_EQ(summary.at("x").min, 1.0);
  EXPECT_DOUBLE_EQ(summary.at("x").max, 8.0);
  EXPECT_EQ(summary.at("y").count, 1);
  EXPECT_DOUBLE_EQ(summary.at("y").mean, 5.0);
}

}  // namespace
}  // namespace lookout::eval
