#include "lookout/app/grid_stage.h"

#include <gtest/gtest.h>

#include "lookout/io/scenario_loader.h"
#include "lookout/sim/simulator.h"

namespace lookout::app {
namespace {

TEST(GridStageTest, ScansWithoutAnEgoPoseAreSkippedAndCounted) {
  GridStage stage;
  LidarScan scan;
  scan.stamp = 0;
  scan.angle_min_rad = -0.5;
  scan.angle_increment_rad = 0.01;
  scan.max_range_m = 50.0;
  scan.ranges_m.assign(101, 10.0f);
  stage.OnLidar(scan);  // no odometry yet: no pose
  EXPECT_EQ(stage.skipped_scans(), 1);
  EXPECT_FALSE(stage.last_sensor_pose().has_value());
  EXPECT_TRUE(stage.cycle_ms().empty());
}

TEST(GridStageTest, SensorPoseFollowsTheEgoInTheOdometryFrame) {
  // The default scenario's first second without actors: the grid's lidar pose, in the odometry
  // frame (the ego's pose at t = 0), must be the true one, or the static world would smear.
  sim::Scenario scenario = io::LoadDefaultScenario();
  scenario.duration_s = 1.0;
  scenario.actors.clear();
  const sim::Simulator simulator(scenario);
  const sim::SensorLog log = simulator.Run(1);
  GridStage stage;
  std::size_t o = 0;
  for (const LidarScan& scan : log.lidar) {
    while (o < log.odometry.size() && log.odometry[o].stamp <= scan.stamp) {
      stage.OnOdometry(log.odometry[o++]);
    }
    stage.OnLidar(scan);
  }
  ASSERT_EQ(stage.skipped_scans(), 0);
  ASSERT_EQ(stage.cycle_ms().size(), log.lidar.size());
  // The lidar's estimated pose at the last scan (0.96 s) is the true one within dead-reckoning
  // drift.
  const Pose2 world_from_odom = simulator.ego_trajectory().At(0.0).pose;
  const Pose2 truth =
      simulator.ego_trajectory().At(ToSeconds(log.lidar.back().stamp)).pose * log.lidar.back().mount;
  const Pose2 estimate = world_from_odom * *stage.last_sensor_pose();
  EXPECT_LT((truth.translation - estimate.translation).norm(), 0.05);
  EXPECT_LT(std::abs(WrapAngle(truth.yaw - estimate.yaw)), 0.01);
}

}  // namespace
}  // namespace lookout::app
