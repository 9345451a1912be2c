#include "lookout/risk/warning_levels.h"

#include <gtest/gtest.h>

#include "lookout/core/input_error.h"

namespace lookout::risk {
namespace {

constexpr TimeNs kStep = 80'000'000;  // 12.5 Hz

// One object's assessment: its risk indicator and collision probability (sampled).
RiskAssessment One(double risk, double probability = 1.0, std::uint32_t id = 1,
                   std::optional<double> ttc = 2.0) {
  RiskAssessment a;
  a.sampled = true;
  if (risk <= 0.0) ttc.reset();
  a.objects.push_back({id, ttc, risk, probability, std::nullopt});
  if (ttc) a.earliest = 0;
  a.risk = risk;
  return a;
}

TEST(WarningLevelsTest, RisesAtOnceAndNamesTheObject) {
  WarningState s;
  EXPECT_FALSE(s.Update(0, One(0.0)).has_value());
  const auto info = s.Update(kStep, One(0.2, 1.0, 4, 4.4));
  ASSERT_TRUE(info.has_value());
  EXPECT_EQ(info->level, WarningLevel::kInformation);
  const auto warn = s.Update(2 * kStep, One(0.9, 1.0, 4, 2.3));
  ASSERT_TRUE(warn.has_value());
  EXPECT_EQ(warn->level, WarningLevel::kWarning);
  EXPECT_EQ(warn->object_id, 4u);
  EXPECT_EQ(warn->ttc_s, 2.3);
  EXPECT_EQ(s.events().size(), 2u);
}

// A TTC under the warning threshold with an improbable collision (an uncertain track, a walker
// whose likeliest path grazes the ego) is information only; a probable one warns.
TEST(WarningLevelsTest, AWarningNeedsTheTtcAndTheProbability) {
  const WarningOptions o;
  EXPECT_EQ(LevelsOf(One(0.9, 0.2), o).entered, WarningLevel::kInformation);
  EXPECT_EQ(LevelsOf(One(0.9, 0.5), o).entered, WarningLevel::kWarning);
  EXPECT_EQ(LevelsOf(One(0.5, 1.0), o).entered, WarningLevel::kInformation);
  // Without sampling, the TTC decides alone.
  RiskAssessment unsampled = One(0.9, 0.0);
  unsampled.sampled = false;
  EXPECT_EQ(LevelsOf(unsampled, o).entered, WarningLevel::kWarning);
  // Raised, the warning holds while the probability stays above its exit (0.3), and falls
  // after the hold time once it does not.
  WarningState s(o);
  s.Update(0, One(0.9, 0.6));
  s.Update(kStep, One(0.9, 0.35));
  EXPECT_EQ(s.level(), WarningLevel::kWarning);
  TimeNs t = kStep;
  while (s.level() == WarningLevel::kWarning && t < 100 * kStep) {
    t += kStep;
    s.Update(t, One(0.9, 0.1));
  }
  EXPECT_EQ(s.level(), WarningLevel::kInformation);
  EXPECT_EQ(t, 9 * kStep);  // below from 2 steps, the first 0.5 s later is the 9th
}

// Of several objects, the earliest potential collision among those at the highest level names
// the event.
TEST(WarningLevelsTest, TheEarliestObjectAtTheLevelIsNamed) {
  RiskAssessment a;
  a.sampled = true;
  a.objects.push_back({1, 1.5, 1.0, 0.1, std::nullopt});  // earliest, improbable
  a.objects.push_back({2, 3.0, 0.67, 0.9, std::nullopt});
  a.objects.push_back({3, 2.5, 0.83, 0.8, std::nullopt});
  a.earliest = 0;
  const LevelInput in = LevelsOf(a, WarningOptions{});
  EXPECT_EQ(in.entered, WarningLevel::kWarning);
  EXPECT_EQ(in.object_id, 3u);
  EXPECT_EQ(in.ttc_s, 2.5);
}

// A risk that flickers around the warning threshold gives one warning, not one per flicker.
TEST(WarningLevelsTest, HysteresisHoldsTheLevelThroughFlicker) {
  WarningState s;
  int events = 0;
  for (int k = 0; k < 40; ++k) {
    const double risk = k % 2 == 0 ? 0.65 : 0.5;  // above enter, then between exit and enter
    if (s.Update(k * kStep, One(risk, 1.0, 1, 3.0))) ++events;
  }
  EXPECT_EQ(events, 1);
  EXPECT_EQ(s.level(), WarningLevel::kWarning);
}

// Below the exit for hold_s (0.5 s), then down.
TEST(WarningLevelsTest, FallsOnlyAfterTheHoldTime) {
  WarningState s;
  s.Update(0, One(0.9, 1.0, 1, 1.0));
  TimeNs t = 0;
  int steps_below = 0;
  while (s.level() == WarningLevel::kWarning && steps_below < 100) {
    t += kStep;
    ++steps_below;
    s.Update(t, One(0.0));
  }
  // Below from the first step (80 ms); the first step at least 0.5 s after it is the 8th (640 ms).
  EXPECT_EQ(steps_below, 8);
  EXPECT_EQ(s.level(), WarningLevel::kNone);
}

TEST(WarningLevelsTest, TimeGoingBackwardsIsIgnored) {
  WarningState s;
  s.Update(10 * kStep, One(0.9, 1.0, 1, 1.0));
  EXPECT_FALSE(s.Update(5 * kStep, One(0.0)).has_value());
  EXPECT_EQ(s.level(), WarningLevel::kWarning);
}

TEST(WarningLevelsTest, ExitAboveEnterIsRefused) {
  WarningOptions o;
  o.warning_exit = 0.7;
  EXPECT_THROW(o.Validate(), InputError);
  o = WarningOptions{};
  o.warning_probability_exit = 0.6;
  EXPECT_THROW(o.Validate(), InputError);
}

}  // namespace
}  // namespace lookout::risk
