#include "lookout/risk/warning_levels.h"

#include <gtest/gtest.h>

#include "lookout/core/input_error.h"

namespace lookout::risk {
namespace {

constexpr TimeNs kStep = 80'000'000;  // 12.5 Hz

TEST(WarningLevelsTest, RisesAtOnceAndNamesTheObject) {
  WarningState s;
  EXPECT_FALSE(s.Update(0, 0.0, std::nullopt, std::nullopt).has_value());
  const auto info = s.Update(kStep, 0.2, 4u, 4.4);
  ASSERT_TRUE(info.has_value());
  EXPECT_EQ(info->level, WarningLevel::kInformation);
  const auto warn = s.Update(2 * kStep, 0.9, 4u, 2.3);
  ASSERT_TRUE(warn.has_value());
  EXPECT_EQ(warn->level, WarningLevel::kWarning);
  EXPECT_EQ(warn->object_id, 4u);
  EXPECT_EQ(warn->ttc_s, 2.3);
  EXPECT_EQ(s.events().size(), 2u);
}

// A risk that flickers around the warning threshold gives one warning, not one per flicker.
TEST(WarningLevelsTest, HysteresisHoldsTheLevelThroughFlicker) {
  WarningState s;
  int events = 0;
  for (int k = 0; k < 40; ++k) {
    const double risk = k % 2 == 0 ? 0.65 : 0.5;  // above enter, then between exit and enter
    if (s.Update(k * kStep, risk, 1u, 3.0)) ++events;
  }
  EXPECT_EQ(events, 1);
  EXPECT_EQ(s.level(), WarningLevel::kWarning);
}

// Below the exit for hold_s (0.5 s), then down.
TEST(WarningLevelsTest, FallsOnlyAfterTheHoldTime) {
  WarningState s;
  s.Update(0, 0.9, 1u, 1.0);
  TimeNs t = 0;
  int steps_below = 0;
  while (s.level() == WarningLevel::kWarning && steps_below < 100) {
    t += kStep;
    ++steps_below;
    s.Update(t, 0.0, std::nullopt, std::nullopt);
  }
  // Below from the first step (80 ms); the first step at least 0.5 s after it is the 8th (640 ms).
  EXPECT_EQ(steps_below, 8);
  EXPECT_EQ(s.level(), WarningLevel::kNone);
}

TEST(WarningLevelsTest, TimeGoingBackwardsIsIgnored) {
  WarningState s;
  s.Update(10 * kStep, 0.9, 1u, 1.0);
  EXPECT_FALSE(s.Update(5 * kStep, 0.0, std::nullopt, std::nullopt).has_value());
  EXPECT_EQ(s.level(), WarningLevel::kWarning);
}

TEST(WarningLevelsTest, ExitAboveEnterIsRefused) {
  WarningOptions o;
  o.warning_exit = 0.7;
  EXPECT_THROW(o.Validate(), InputError);
}

}  // namespace
}  // namespace lookout::risk
