#include "lookout/sim/simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "lookout/sim/stereo_sensor.h"

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

ActorSpec Actor(std::string id, ObjectClass c, std::vector<Vector2d> path, double speed_mps) {
  ActorSpec a;
  a.id = std::move(id);
  a.object_class = c;
  a.path = std::move(path);
  a.speed = SpeedProfile::Constant(speed_mps);
  a.stop_s = 12.0;
  return a;
}

// The built-in left-turn-across-path scenario (scenarios/left-turn-across-path.yaml), with a
// pedestrian and a cyclist added so every footprint kind and sensor path is exercised.
Scenario LeftTurnScenario() {
  Scenario s;
  s.name = "left-turn-across-path";
  s.duration_s = 12.0;
  s.seed = 7;
  s.world.preset = "four_way";
  s.ego.path = {{-60, -1.75}, {60, -1.75}};
  s.ego.speed = SpeedProfile::Constant(11.1);
  s.actors.push_back(Actor("car1", ObjectClass::kCar,
                           {{45, 1.75}, {5, 1.75}, {-1.75, -5}, {-1.75, -60}}, 8.0));
  s.actors.push_back(Actor("ped1", ObjectClass::kPedestrian, {{8, -8}, {8, 8}}, 1.4));
  ActorSpec cyclist = Actor("bike1", ObjectClass::kCyclist, {{30, -2.5}, {-30, -2.5}}, 5.0);
  cyclist.start_s = 2.0;
  cyclist.stop_s = 9.0;
  s.actors.push_back(cyclist);
  s.source = "<test>";
  return s;
}

// A still ego on the west approach, heading east into the junction.
Scenario StillEgo() {
  Scenario s;
  s.name = "still";
  s.duration_s = 2.0;
  s.seed = 11;
  s.world.preset = "four_way";
  s.ego.path = {{-25, -1.75}, {60, -1.75}};
  s.ego.speed = SpeedProfile::Constant(0.0);
  return s;
}

bool SameBytes(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void ExpectSamePose(const Pose2& a, const Pose2& b) {
  EXPECT_TRUE(SameBytes(a.x(), b.x()) && SameBytes(a.y(), b.y()) && SameBytes(a.yaw, b.yaw));
}

void ExpectSameState(const KinematicState& a, const KinematicState& b) {
  ExpectSamePose(a.pose, b.pose);
  EXPECT_TRUE(SameBytes(a.speed_mps, b.speed_mps));
  EXPECT_TRUE(SameBytes(a.yaw_rate_radps, b.yaw_rate_radps));
  EXPECT_TRUE(SameBytes(a.acceleration_mps2, b.acceleration_mps2));
}

void ExpectSameShape(const Shape& a, const Shape& b) {
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.center, b.center);
  EXPECT_TRUE(SameBytes(a.radius, b.radius));
  EXPECT_EQ(a.owner, b.owner);
}

void ExpectSameLog(const SensorLog& a, const SensorLog& b) {
  ASSERT_EQ(a.lidar.size(), b.lidar.size());
  for (std::size_t k = 0; k < a.lidar.size(); ++k) {
    const LidarScan& x = a.lidar[k];
    const LidarScan& y = b.lidar[k];
    EXPECT_EQ(x.stamp, y.stamp);
    ExpectSamePose(x.mount, y.mount);
    EXPECT_TRUE(SameBytes(x.angle_min_rad, y.angle_min_rad));
    EXPECT_TRUE(SameBytes(x.angle_increment_rad, y.angle_increment_rad));
    EXPECT_TRUE(SameBytes(x.max_range_m, y.max_range_m));
    ASSERT_EQ(x.ranges_m.size(), y.ranges_m.size());
    EXPECT_EQ(std::memcmp(x.ranges_m.data(), y.ranges_m.data(),
                          x.ranges_m.size() * sizeof(float)), 0) << "lidar frame " << k;
  }
  ASSERT_EQ(a.stereo.size(), b.stereo.size());
  for (std::size_t k = 0; k < a.stereo.size(); ++k) {
    EXPECT_EQ(a.stereo[k].stamp, b.stereo[k].stamp);
    ExpectSamePose(a.stereo[k].mount, b.stereo[k].mount);
    ASSERT_EQ(a.stereo[k].objects.size(), b.stereo[k].objects.size()) << "stereo frame " << k;
    for (std::size_t j = 0; j < a.stereo[k].objects.size(); ++j) {
      const StereoObject& x = a.stereo[k].objects[j];
      const StereoObject& y = b.stereo[k].objects[j];
      EXPECT_EQ(x.id, y.id);
      EXPECT_EQ(x.object_class, y.object_class);
      EXPECT_EQ(x.center_m, y.center_m);
      EXPECT_TRUE(SameBytes(x.yaw_rad, y.yaw_rad));
      EXPECT_TRUE(SameBytes(x.length_m, y.length_m));
      EXPECT_TRUE(SameBytes(x.width_m, y.width_m));
      EXPECT_TRUE(SameBytes(x.speed_longitudinal_mps, y.speed_longitudinal_mps));
      EXPECT_TRUE(SameBytes(x.speed_lateral_mps, y.speed_lateral_mps));
      EXPECT_EQ(x.center_covariance, y.center_covariance);
      EXPECT_TRUE(SameBytes(x.yaw_variance, y.yaw_variance));
      EXPECT_TRUE(SameBytes(x.speed_variance, y.speed_variance));
      EXPECT_EQ(x.history, y.history);
    }
  }
  ASSERT_EQ(a.odometry.size(), b.odometry.size());
  for (std::size_t k = 0; k < a.odometry.size(); ++k) {
    EXPECT_EQ(a.odometry[k].stamp, b.odometry[k].stamp);
    EXPECT_TRUE(SameBytes(a.odometry[k].speed_mps, b.odometry[k].speed_mps));
    EXPECT_TRUE(SameBytes(a.odometry[k].yaw_rate_radps, b.odometry[k].yaw_rate_radps));
  }
  ASSERT_EQ(a.truth.size(), b.truth.size());
  for (std::size_t k = 0; k < a.truth.size(); ++k) {
    const TruthFrame& x = a.truth[k];
    const TruthFrame& y = b.truth[k];
    EXPECT_EQ(x.stamp, y.stamp);
    ExpectSameState(x.ego.state, y.ego.state);
    ExpectSameShape(x.ego.footprint, y.ego.footprint);
    ASSERT_EQ(x.actors.size(), y.actors.size());
    for (std::size_t j = 0; j < x.actors.size(); ++j) {
      EXPECT_EQ(x.actors[j].index, y.actors[j].index);
      EXPECT_EQ(x.actors[j].id, y.actors[j].id);
      EXPECT_EQ(x.actors[j].object_class, y.actors[j].object_class);
      ExpectSameState(x.actors[j].state, y.actors[j].state);
      ExpectSameShape(x.actors[j].footprint, y.actors[j].footprint);
      EXPECT_TRUE(
          SameBytes(x.actors[j].visible_fraction_lidar, y.actors[j].visible_fraction_lidar));
      EXPECT_TRUE(
          SameBytes(x.actors[j].visible_fraction_stereo, y.actors[j].visible_fraction_stereo));
      EXPECT_EQ(x.actors[j].contact_time_s, y.actors[j].contact_time_s);
    }
  }
}

TEST(SimulatorTest, SameBytesForAnyThreadCount) {
  const Simulator sim(LeftTurnScenario());
  const SensorLog one = sim.Run(1);
  const SensorLog two = sim.Run(2);
  ExpectSameLog(one, two);
  ExpectSameLog(one, sim.Run(3));  // more threads than cores, too
  // And the parallel run agrees with the frames simulated one by one.
  const std::size_t k = 40;
  const LidarScan lone = sim.SimulateLidar(static_cast<int>(k));
  EXPECT_EQ(std::memcmp(lone.ranges_m.data(), one.lidar[k].ranges_m.data(),
                        lone.ranges_m.size() * sizeof(float)), 0);
  const TruthFrame truth = sim.Truth(one.truth[k].stamp);
  ASSERT_EQ(truth.actors.size(), one.truth[k].actors.size());
  for (std::size_t j = 0; j < truth.actors.size(); ++j) {
    EXPECT_EQ(truth.actors[j].visible_fraction_lidar,
              one.truth[k].actors[j].visible_fraction_lidar);
  }
}

TEST(SimulatorTest, FrameCountsAndStampsAreExact) {
  const Simulator sim(LeftTurnScenario());
  const SensorLog log = sim.Run(2);
  ASSERT_EQ(log.lidar.size(), 151u);  // 12 s at 12.5 Hz: 0, 80 ms, ..., 12 s
  ASSERT_EQ(log.truth.size(), 151u);
  ASSERT_EQ(log.stereo.size(), 241u);
  ASSERT_EQ(log.odometry.size(), 601u);
  for (std::size_t k = 0; k < log.lidar.size(); ++k) {
    EXPECT_EQ(log.lidar[k].stamp, static_cast<TimeNs>(k) * 80'000'000);
    EXPECT_EQ(log.truth[k].stamp, log.lidar[k].stamp);
    ASSERT_EQ(log.lidar[k].ranges_m.size(), 641u);
  }
  for (std::size_t k = 0; k < log.stereo.size(); ++k) {
    EXPECT_EQ(log.stereo[k].stamp, static_cast<TimeNs>(k) * 50'000'000);
  }
  for (std::size_t k = 0; k < log.odometry.size(); ++k) {
    EXPECT_EQ(log.odometry[k].stamp, static_cast<TimeNs>(k) * 20'000'000);
  }
  EXPECT_EQ(log.lidar.back().stamp, 12 * kNanosPerSecond);

  Scenario odd = LeftTurnScenario();
  odd.duration_s = 1.0;  // 12.5 frames fit: 0 .. 960 ms
  const SensorLog short_log = Simulator(odd).Run(1);
  ASSERT_EQ(short_log.lidar.size(), 13u);
  EXPECT_EQ(short_log.lidar.back().stamp, 960'000'000);
}

TEST(SimulatorTest, LidarScanLayoutAndMount) {
  const Simulator sim(LeftTurnScenario());
  const LidarScan scan = sim.SimulateLidar(10);
  EXPECT_EQ(scan.ranges_m.size(), 641u);
  EXPECT_NEAR(scan.angle_min_rad, -DegToRad(80.0), 1e-12);
  EXPECT_NEAR(scan.BeamAngle(640), DegToRad(80.0), 1e-12);
  EXPECT_DOUBLE_EQ(scan.mount.x(), 2.2);
  EXPECT_DOUBLE_EQ(scan.max_range_m, 150.0);
  for (const float r : scan.ranges_m) {
    EXPECT_TRUE(std::isinf(r) || (r >= 0.0f && r <= 150.0f));
  }
}

TEST(SimulatorTest, LidarSeesAWallAtItsDistance) {
  // A still ego 20 m west of a long wall: the straight-ahead beam reads 20 - 2.2 m, with
  // the range noise.
  Scenario s = StillEgo();
  s.world.preset.reset();
  s.ego.path = {{-20, 0}, {10, 0}};
  Obstacle wall;
  wall.polygon = {{0, -50}, {1, -50}, {1, 50}, {0, 50}};
  s.world.obstacles.push_back(wall);
  const Simulator sim(s);
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (int k = 0; k < 20; ++k) {
    const LidarScan scan = sim.SimulateLidar(k);
    for (std::size_t i = 300; i <= 340; ++i) {
      const double r = static_cast<double>(scan.ranges_m[i]);
      if (!std::isfinite(r)) continue;  // a dropout
      const double expected = 17.8 / std::cos(scan.BeamAngle(i));
      sum += r - expected;
      sum2 += (r - expected) * (r - expected);
      ++n;
    }
  }
  ASSERT_GT(n, 780);
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.03, 0.004);
}

TEST(SimulatorTest, ActorBehindABuildingIsInvisible) {
  // A car standing on the south road, 24 m ahead and 13 m right of the still ego: inside the
  // camera's field and depth, but the south-west block stands in between.
  Scenario hidden = StillEgo();
  hidden.actors.push_back(Actor("hidden", ObjectClass::kCar, {{0, -15}, {0, -60}}, 0.0));
  hidden.actors.back().stop_s = hidden.duration_s;
  // The same car in the open, in the junction ahead (29 m deep), as a control.
  Scenario open = StillEgo();
  open.actors.push_back(Actor("open", ObjectClass::kCar, {{5, 1.75}, {60, 1.75}}, 0.0));
  open.actors.back().stop_s = open.duration_s;

  const SensorLog hidden_log = Simulator(hidden).Run(2);
  for (const TruthFrame& f : hidden_log.truth) {
    ASSERT_EQ(f.actors.size(), 1u);
    // In the camera's field and depth, so only the building can hide it.
    const Pose2 camera = f.ego.state.pose * Pose2(0.8, 0.0, 0.0);
    const Vector2d seen = camera.Inverse() * f.actors[0].state.pose.translation;
    ASSERT_GT(seen.x(), 0.0);
    ASSERT_LT(seen.x(), 35.0);
    ASSERT_LT(std::abs(std::atan2(seen.y(), seen.x())), DegToRad(35.0));
    EXPECT_EQ(f.actors[0].visible_fraction_lidar, 0.0);
    EXPECT_EQ(f.actors[0].visible_fraction_stereo, 0.0);
  }
  for (const StereoFrame& f : hidden_log.stereo) {
    for (const StereoObject& o : f.objects) EXPECT_GE(o.id, kFalseObjectIdBase);
  }

  const SensorLog open_log = Simulator(open).Run(2);
  for (const TruthFrame& f : open_log.truth) {
    ASSERT_EQ(f.actors.size(), 1u);
    EXPECT_GT(f.actors[0].visible_fraction_lidar, 0.9);
    EXPECT_GT(f.actors[0].visible_fraction_stereo, 0.9);
  }
  int detections = 0;
  for (const StereoFrame& f : open_log.stereo) {
    for (const StereoObject& o : f.objects) detections += o.id == 1u ? 1 : 0;
  }
  EXPECT_GT(detections, 30);  // of 41 frames, at a 5 % miss rate
}

TEST(SimulatorTest, StereoHistoryCountsConsecutiveDetections) {
  const Simulator sim(LeftTurnScenario());
  const SensorLog log = sim.Run(2);
  std::vector<std::uint32_t> previous(sim.scenario().actors.size() + 1, 0);
  int longest = 0;
  for (const StereoFrame& f : log.stereo) {
    std::vector<std::uint32_t> current(previous.size(), 0);
    for (const StereoObject& o : f.objects) {
      if (o.id >= kFalseObjectIdBase) {
        EXPECT_EQ(o.history, 1u);
        continue;
      }
      ASSERT_LT(o.id, previous.size());
      EXPECT_EQ(o.history, previous[o.id] + 1u) << "stamp " << f.stamp << " id " << o.id;
      current[o.id] = o.history;
      longest = std::max(longest, static_cast<int>(o.history));
    }
    previous = current;
  }
  EXPECT_GT(longest, 10);
  // A frame simulated alone does not know the past.
  for (const StereoObject& o : sim.SimulateStereo(60).objects) EXPECT_EQ(o.history, 1u);
}

TEST(SimulatorTest, TruthHasPresentActorsAndContactTimes) {
  // Head-on in the ego's lane at 10 m/s each from 60 m apart: the boxes (4.6 and 4.5 m long)
  // touch when the centres are 4.55 m apart, at (60 - 4.55) / 20 s.
  Scenario s = StillEgo();
  s.world.preset.reset();
  s.duration_s = 5.0;
  s.ego.path = {{-30, 0}, {60, 0}};
  s.ego.speed = SpeedProfile::Constant(10.0);
  s.actors.push_back(Actor("oncoming", ObjectClass::kCar, {{30, 0}, {-60, 0}}, 10.0));
  s.actors.back().stop_s = 5.0;
  ActorSpec late = Actor("late", ObjectClass::kPedestrian, {{10, 10}, {10, 20}}, 1.0);
  late.start_s = 1.0;
  late.stop_s = 2.0;
  s.actors.push_back(late);
  const Simulator sim(s);
  const TruthFrame early = sim.Truth(500'000'000);
  ASSERT_EQ(early.actors.size(), 1u);  // the pedestrian is not there yet
  EXPECT_EQ(early.actors[0].id, "oncoming");
  ASSERT_TRUE(early.actors[0].contact_time_s.has_value());
  EXPECT_NEAR(*early.actors[0].contact_time_s, (60.0 - 4.55) / 20.0, 2e-3);
  EXPECT_NEAR(early.ego.state.pose.x(), -25.0, 1e-6);
  const TruthFrame mid = sim.Truth(1'500'000'000);
  ASSERT_EQ(mid.actors.size(), 2u);
  EXPECT_EQ(mid.actors[1].id, "late");
  EXPECT_FALSE(mid.actors[1].contact_time_s.has_value());
  EXPECT_EQ(mid.actors[1].footprint.kind, Shape::Kind::kCircle);
}

TEST(SimulatorTest, OdometryIsTruthPlusNoise) {
  Scenario s = LeftTurnScenario();
  const Simulator sim(s);
  double sum = 0.0, sum2 = 0.0;
  const SensorLog log = sim.Run(1);
  for (const EgoOdometry& o : log.odometry) {
    const double e = o.speed_mps - sim.ego_trajectory().At(ToSeconds(o.stamp)).speed_mps;
    sum += e;
    sum2 += e * e;
  }
  const double n = static_cast<double>(log.odometry.size());
  EXPECT_NEAR(sum / n, 0.0, 4.0 * 0.05 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.05, 0.006);
}

}  // namespace
}  // namespace lookout::sim
