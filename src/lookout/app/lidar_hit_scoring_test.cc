#include "lookout/app/lidar_hit_scoring.h"

#include <gtest/gtest.h>

#include "lookout/core/time.h"
#include "lookout/sim/raycast.h"

namespace lookout::app {
namespace {

using lidar::HitClass;

sim::ActorTruth Actor(int index, double speed_mps) {
  sim::ActorTruth a;
  a.index = index;
  a.state.speed_mps = speed_mps;
  return a;
}

TEST(LidarHitScorer, CountsEachBeamByItsTrueOwnerAndItsClass) {
  // Actor 0 walks (1.2 m/s), actor 2 stands (0.1 m/s); ten beams.
  sim::TruthFrame truth;
  truth.actors = {Actor(0, 1.2), Actor(2, 0.1)};
  const int s = sim::kStaticOwner;
  truth.lidar_beam_owner = {0, 0, 0, 0, s, s, s, 2, sim::kNoHit, 0};
  lidar::ScanHitClasses c;
  c.beam = {HitClass::kDynamic, HitClass::kDynamic, HitClass::kStatic, HitClass::kUnknown,
            HitClass::kStatic,  HitClass::kDynamic, HitClass::kStatic, HitClass::kDynamic,
            HitClass::kNoReturn, HitClass::kNoReturn};
  LidarHitScorer scorer;
  scorer.Observe(c, truth);
  std::map<std::string, double> m;
  scorer.Report(m);
  // Moving returns: beams 0-3 (beam 9 is no return). Dynamic on them: 0, 1. Dynamic on the
  // static world: beam 5; on the standing actor: beam 7, counted neither way.
  EXPECT_DOUBLE_EQ(m.at("lidar_hits.moving_recall"), 2.0 / 4.0);
  EXPECT_DOUBLE_EQ(m.at("lidar_hits.moving_precision"), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(m.at("lidar_hits.moving_as_static"), 1.0 / 4.0);
  EXPECT_DOUBLE_EQ(m.at("lidar_hits.moving_as_unknown"), 1.0 / 4.0);
  EXPECT_DOUBLE_EQ(m.at("lidar_hits.static_false_dynamic"), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(m.at("lidar_hits.unknown_share"), 1.0 / 8.0);
  EXPECT_DOUBLE_EQ(m.at("lidar_hits.no_returns_per_frame"), 2.0);
  EXPECT_EQ(scorer.counts().slow_actor_dynamic, 1);
}

// The first second of scans (the map still empty) counts in the whole-run figures only.
TEST(LidarHitScorer, AfterOneSecondLeavesOutTheFirstSecondOfScans) {
  sim::TruthFrame truth;
  truth.actors = {Actor(0, 1.2)};
  truth.lidar_beam_owner = {0, 0, sim::kStaticOwner};
  lidar::ScanHitClasses unknown;
  unknown.beam = {HitClass::kUnknown, HitClass::kUnknown, HitClass::kUnknown};
  lidar::ScanHitClasses seen;
  seen.beam = {HitClass::kDynamic, HitClass::kStatic, HitClass::kDynamic};
  LidarHitScorer scorer;
  for (const double t : {2.0, 2.5, 3.0}) {  // the first scan fixes the start
    truth.stamp = FromSeconds(t);
    scorer.Observe(t < 3.0 ? unknown : seen, truth);
  }
  std::map<std::string, double> m;
  scorer.Report(m);
  EXPECT_DOUBLE_EQ(m.at("lidar_hits.moving_recall"), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(m.at("lidar_hits.moving_recall_after_1s"), 1.0 / 2.0);
  EXPECT_DOUBLE_EQ(m.at("lidar_hits.moving_precision_after_1s"), 1.0 / 2.0);
  EXPECT_EQ(scorer.counts_after_warm_up().moving, 2);
}

TEST(LidarHitScorer, NoKeyWithoutAnythingToCount) {
  LidarHitScorer scorer;
  std::map<std::string, double> m;
  scorer.Report(m);
  EXPECT_TRUE(m.empty());
}

}  // namespace
}  // namespace lookout::app
