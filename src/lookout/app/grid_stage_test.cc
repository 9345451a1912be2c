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
  EXPECT_FALSE(stage.last_objects().has_value());
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

TEST(GridStageTest, EachCycleGivesTheObjectsOfItsScanInTheVehicleFrame) {
  // The default scenario's first 3 s: every cycle leaves its own LidarObjectFrame, stamped with
  // the scan, carrying the scan's mount and the ego pose the grid used.
  sim::Scenario scenario = io::LoadDefaultScenario();
  scenario.duration_s = 3.0;
  const sim::Simulator simulator(scenario);
  const sim::SensorLog log = simulator.Run(1);
  GridStage stage;
  std::size_t o = 0;
  for (const LidarScan& scan : log.lidar) {
    while (o < log.odometry.size() && log.odometry[o].stamp <= scan.stamp) {
      stage.OnOdometry(log.odometry[o++]);
    }
    stage.OnLidar(scan);
    ASSERT_TRUE(stage.last_objects().has_value());
    const LidarObjectFrame& frame = *stage.last_objects();
    EXPECT_EQ(frame.stamp, scan.stamp);
    EXPECT_EQ(frame.mount.translation, scan.mount.translation);
    // The ego pose is the one the grid's lidar pose was built from.
    const Pose2 sensor = frame.ego_pose * frame.mount;
    EXPECT_NEAR((sensor.translation - stage.last_sensor_pose()->translation).norm(), 0.0, 1e-12);
    for (std::size_t i = 0; i < frame.objects.size(); ++i) {
      const LidarObject& obj = frame.objects[i];
      EXPECT_EQ(obj.id, i);
      EXPECT_GE(obj.cell_count, 3u);
      // Inside the 60 m window around the ego, in the vehicle frame.
      EXPECT_LT(obj.centroid_m.cwiseAbs().maxCoeff(), 31.0);
    }
  }
  EXPECT_EQ(stage.objects_ms().size(), log.lidar.size());
}

}  // namespace
}  // namespace lookout::app
