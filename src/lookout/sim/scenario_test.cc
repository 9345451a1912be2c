#include "lookout/sim/scenario.h"

#include <gtest/gtest.h>

namespace lookout::sim {
namespace {

TEST(SpeedProfileTest, InterpolatesLinearlyAndHoldsAtEnds) {
  const SpeedProfile p{{{0.0, 11.1}, {4.0, 11.1}, {6.0, 0.0}}};
  EXPECT_DOUBLE_EQ(p.At(-1.0), 11.1);
  EXPECT_DOUBLE_EQ(p.At(2.0), 11.1);
  EXPECT_NEAR(p.At(5.0), 5.55, 1e-12);
  EXPECT_DOUBLE_EQ(p.At(6.0), 0.0);
  EXPECT_DOUBLE_EQ(p.At(100.0), 0.0);
}

TEST(SpeedProfileTest, ConstantIsOnePair) {
  EXPECT_DOUBLE_EQ(SpeedProfile::Constant(3.0).At(17.0), 3.0);
}

}  // namespace
}  // namespace lookout::sim
