#include "lookout/app/localisation_scoring.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lookout::app {
namespace {

TEST(LocalisationScorer, ErrorsInTheOdometryFrameWithoutAnyFit) {
  // The odometry frame sits at (10, 5), turned by 90 degrees, in the world.
  const Pose2 world_from_odom(10.0, 5.0, 0.5 * kPi);
  LocalisationScorer scorer(world_from_odom, "localisation.");
  // Truth 3 m ahead along the odometry frame's x: world (10, 8), heading 90 degrees.
  const Pose2 truth_world = world_from_odom * Pose2(3.0, 0.0, 0.0);
  EgoState e;
  e.pose = Pose2(3.0, 0.4, 0.01);  // 0.4 m to the side, 0.01 rad
  scorer.Observe(e, truth_world);
  e.pose = Pose2(3.0, 0.0, -0.03);  // on the spot, -0.03 rad
  scorer.Observe(e, truth_world);
  scorer.Observe(std::nullopt, truth_world);
  std::map<std::string, double> m;
  scorer.Report(m);
  EXPECT_NEAR(m.at("localisation.ate_rmse_m"), std::sqrt(0.16 / 2.0), 1e-12);
  EXPECT_NEAR(m.at("localisation.heading_rmse_deg"),
              std::sqrt((0.01 * 0.01 + 0.03 * 0.03) / 2.0) * 180.0 / kPi, 1e-9);
  EXPECT_NEAR(m.at("localisation.max_error_m"), 0.4, 1e-12);
  EXPECT_EQ(m.at("localisation.missing_frames"), 1.0);
  // One step between the two estimates: moved (0, -0.4) where the truth stood still.
  EXPECT_NEAR(m.at("localisation.step_rmse_m"), 0.4, 1e-12);
}

TEST(LocalisationScorer, OnlyTheMissingCountWithoutAnEstimate) {
  LocalisationScorer scorer(Pose2(), "localisation.dead_reckoning_");
  scorer.Observe(std::nullopt, Pose2());
  std::map<std::string, double> m;
  scorer.Report(m);
  EXPECT_EQ(m.size(), 1u);
  EXPECT_EQ(m.at("localisation.dead_reckoning_missing_frames"), 1.0);
}

}  // namespace
}  // namespace lookout::app
