#include "lookout/eval/statistics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lookout::eval {
namespace {

// Median has its test in metrics_test.cc.
TEST(Statistics, RatioIsNanForNoDenominator) {
  EXPECT_DOUBLE_EQ(Ratio(3.0, 4.0), 0.75);
  EXPECT_TRUE(std::isnan(Ratio(0.0, 0.0)));
  EXPECT_TRUE(std::isnan(Ratio(1.0, -2.0)));
}

}  // namespace
}  // namespace lookout::eval
