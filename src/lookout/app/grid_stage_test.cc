#include "lookout/app/grid_stage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

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
  const Pose2 truth = simulator.ego_trajectory().At(ToSeconds(log.lidar.back().stamp)).pose *
                      log.lidar.back().mount;
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

// A standing ego before a small object 10 m ahead of the lidar: `cycles` scans at 12.5 Hz, each
// after a stereo frame 30 ms older (when `stereo` holds any object) and the odometry up to it.
// Returns the stage after the last cycle.
void RunStandingScene(GridStage& stage, const std::vector<StereoObject>& stereo, int cycles) {
  const Pose2 lidar_mount(1.0, 0.0, 0.0);
  TimeNs odometry_stamp = 0;
  for (int k = 0; k < cycles; ++k) {
    const TimeNs scan_stamp = 80'000'000LL * (k + 1);
    while (odometry_stamp <= scan_stamp) {
      stage.OnOdometry(EgoOdometry{odometry_stamp, 0.0, 0.0});
      odometry_stamp += 10'000'000;
    }
    StereoFrame frame;
    frame.stamp = scan_stamp - 30'000'000;
    frame.mount = Pose2(1.5, 0.2, 0.1);  // the camera frame in the vehicle frame
    frame.objects = stereo;
    stage.OnStereo(frame);
    LidarScan scan;
    scan.stamp = scan_stamp;
    scan.mount = lidar_mount;
    scan.angle_min_rad = -0.5;
    scan.angle_increment_rad = 0.005;
    scan.max_range_m = 50.0;
    scan.ranges_m.assign(201, std::numeric_limits<float>::infinity());
    // Beams within +-0.03 rad of straight ahead hit the object's near side 10 m out.
    for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
      if (std::abs(scan.BeamAngle(i)) <= 0.03) scan.ranges_m[i] = 10.0f;
    }
    stage.OnLidar(scan);
  }
}

// The pedestrian probability of the grid's occupied cells within 0.3 m of `point_m` (odometry
// frame), averaged; and how many there are.
std::pair<double, int> PedestrianProbabilityAround(const GridStage& stage,
                                                   const Eigen::Vector2d& point_m) {
  const grid::ExtendedGrid& g = stage.grid();
  const auto& pmf = g.layers().Values(g.ids().class_pmf[static_cast<std::size_t>(
      grid::GridClass::kPedestrian)]);
  const auto& occupancy = g.layers().Values(g.ids().occupancy);
  double sum = 0.0;
  int n = 0;
  const grid::ScrollingGridGeometry& geometry = g.geometry();
  const CellIndex centre = geometry.GlobalCellAt(point_m);
  for (int dy = -3; dy <= 3; ++dy) {
    for (int dx = -3; dx <= 3; ++dx) {
      const CellIndex c{centre.ix + dx, centre.iy + dy};
      if (!geometry.Contains(c) || (geometry.CellCenterM(c) - point_m).norm() > 0.3) continue;
      const std::size_t i = geometry.StorageIndex(c);
      if (occupancy[i] < 0.6f) continue;
      sum += static_cast<double>(pmf[i]);
      ++n;
    }
  }
  return {n > 0 ? sum / n : 0.0, n};
}

TEST(GridStageTest, AStereoPedestrianRaisesThePedestrianProbabilityOfTheCellsItCovers) {
  // The object's hits lie 11 m ahead of the vehicle (lidar at x = 1 m, range 10 m). The camera
  // (at (1.5, 0.2), turned 0.1 rad) reports a pedestrian whose footprint covers them: its centre
  // in the camera frame is the vehicle frame's (11.2, 0) brought into the camera's axes.
  const Pose2 camera_mount(1.5, 0.2, 0.1);
  StereoObject pedestrian;
  pedestrian.id = 7;
  pedestrian.object_class = ObjectClass::kPedestrian;
  pedestrian.center_m = camera_mount.Inverse() * Eigen::Vector2d(11.2, 0.0);
  pedestrian.length_m = 0.8;
  pedestrian.width_m = 0.8;
  pedestrian.center_covariance = 0.01 * Eigen::Matrix2d::Identity();
  pedestrian.yaw_variance = 0.0025;
  pedestrian.speed_variance = 0.09;
  pedestrian.history = 5;
  // The same object reported 4 m to the side: it covers none of the hits.
  StereoObject aside = pedestrian;
  aside.center_m = camera_mount.Inverse() * Eigen::Vector2d(11.2, 4.0);

  GridStage with_camera, elsewhere, without_camera;
  RunStandingScene(with_camera, {pedestrian}, 12);
  RunStandingScene(elsewhere, {aside}, 12);
  RunStandingScene(without_camera, {}, 12);
  // The ego stands at the odometry frame's origin: the hits are at (11, 0) there.
  const Eigen::Vector2d hits(11.0, 0.0);
  const auto [p_with, n_with] = PedestrianProbabilityAround(with_camera, hits);
  const auto [p_aside, n_aside] = PedestrianProbabilityAround(elsewhere, hits);
  const auto [p_without, n_without] = PedestrianProbabilityAround(without_camera, hits);
  ASSERT_GT(n_without, 0) << "the scene's hits must make occupied cells";
  EXPECT_EQ(n_with, n_without);
  EXPECT_EQ(with_camera.stereo_class_stats().frames_used, 12);
  EXPECT_EQ(with_camera.stereo_class_stats().regions, 12);
  EXPECT_EQ(with_camera.last_stereo_regions().size(), 1u);
  // The grid's own cues (a small cluster that does not move) already lean to pedestrian; the
  // camera's reports (likelihood ratio 45 against each other class, tempered by the
  // footprint's share of the grown region) make it near certain.
  EXPECT_GT(p_with, 0.9) << "without the camera: " << p_without;
  EXPECT_GT(p_with, p_without + 0.2);
  // A report elsewhere changes nothing here.
  EXPECT_NEAR(p_aside, p_without, 1e-6);
}

TEST(GridStageTest, UnknownAndUnusableStereoObjectsGiveNoEvidence) {
  StereoObject unknown;
  unknown.object_class = ObjectClass::kUnknown;
  unknown.center_m = Eigen::Vector2d(10.0, 0.0);
  unknown.length_m = unknown.width_m = 0.8;
  unknown.center_covariance = 0.01 * Eigen::Matrix2d::Identity();
  unknown.speed_variance = 0.09;
  StereoObject broken = unknown;
  broken.object_class = ObjectClass::kPedestrian;
  broken.center_covariance(0, 0) = std::numeric_limits<double>::quiet_NaN();
  GridStage stage;
  RunStandingScene(stage, {unknown, broken}, 3);
  EXPECT_EQ(stage.stereo_class_stats().frames_used, 3);
  EXPECT_EQ(stage.stereo_class_stats().regions, 0);
  EXPECT_EQ(stage.stereo_class_stats().objects_dropped, 3);
}

}  // namespace
}  // namespace lookout::app
