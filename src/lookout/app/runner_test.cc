#include "lookout/app/runner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "lookout/io/scenario_loader.h"

namespace lookout::app {
namespace {

// Records what reaches it, in order.
class ProbeStage : public Stage {
 public:
  explicit ProbeStage(std::vector<std::pair<TimeNs, SensorOrder>>* seen) : seen_(seen) {}
  void OnOdometry(const EgoOdometry& o) override {
    seen_->push_back({o.stamp, SensorOrder::kOdometry});
  }
  void OnStereo(const StereoFrame& f) override {
    seen_->push_back({f.stamp, SensorOrder::kStereo});
  }
  void OnLidar(const LidarScan& s) override { seen_->push_back({s.stamp, SensorOrder::kLidar}); }

 private:
  std::vector<std::pair<TimeNs, SensorOrder>>* seen_;
};

TEST(RunnerTest, DeliversEveryMessageInTimestampOrderAtEachSensorsRate) {
  sim::Scenario scenario = io::LoadDefaultScenario();
  scenario.duration_s = 2.0;
  std::vector<std::pair<TimeNs, SensorOrder>> seen;
  Pipeline pipeline;
  pipeline.Add(std::make_unique<ProbeStage>(&seen));
  const RunResult result = RunScenario(scenario, pipeline, RunOptions{});

  // 2 s at 12.5, 20 and 50 Hz, both ends included.
  EXPECT_EQ(result.lidar_frames, 26);
  EXPECT_EQ(result.stereo_frames, 41);
  EXPECT_EQ(result.odometry_frames, 101);
  ASSERT_EQ(seen.size(), 26u + 41u + 101u);
  for (std::size_t i = 1; i < seen.size(); ++i) {
    ASSERT_LE(seen[i - 1], seen[i]) << "message " << i << " arrived out of order";
  }
  // At t = 0 all three sensors fire: odometry, then stereo, then the scan closing the cycle.
  EXPECT_EQ(seen[0], std::make_pair(TimeNs{0}, SensorOrder::kOdometry));
  EXPECT_EQ(seen[1], std::make_pair(TimeNs{0}, SensorOrder::kStereo));
  EXPECT_EQ(seen[2], std::make_pair(TimeNs{0}, SensorOrder::kLidar));
  EXPECT_EQ(result.metrics.values.at("timing.frames"), 26.0);
  EXPECT_GT(result.metrics.values.at("timing.realtime_factor"), 0.0);
}

}  // namespace
}  // namespace lookout::app

namespace lookout::app {
namespace {

// Fusion closes each cycle: every lidar object of the cycle is in the fused frame exactly once
// (seen by the lidar alone or with the camera: none is lost), and the run reports fusion.*.
TEST(RunnerTest, FusionKeepsEveryLidarObjectOfTheCycle) {
  // One literal joined by the preprocessor: std::string + literal here trips GCC 12's known
  // false positive -Warray-bounds at -O3.
  sim::Scenario scenario =
      io::LoadScenarioFile(LOOKOUT_SOURCE_DIR "/scenarios/pushchair-group.yaml");
  scenario.duration_s = 6.0;
  Pipeline pipeline(PipelineOptions{});
  const RunResult result = RunScenario(scenario, pipeline, RunOptions{});
  const LidarObjectFrame* lidar = pipeline.lidar_objects();
  const fusion::FusedObjectFrame* fused = pipeline.fused_objects();
  ASSERT_NE(lidar, nullptr);
  ASSERT_NE(fused, nullptr);
  EXPECT_EQ(fused->stamp, lidar->stamp);
  std::map<std::uint32_t, int> seen;  // lidar object id -> fused objects that carry it
  for (const LidarObject& o : lidar->objects) seen[o.id] = 0;
  for (const fusion::FusedObject& o : fused->objects) {
    EXPECT_TRUE(o.sensor_count == 1 || o.sensor_count == 2);
    if (o.lidar_id) {
      ASSERT_TRUE(seen.contains(*o.lidar_id)) << "unknown lidar id " << *o.lidar_id;
      ++seen[*o.lidar_id];
    }
  }
  const fusion::FusionEngine* engine = pipeline.fusion();
  ASSERT_NE(engine, nullptr);
  // Every lidar object is carried by one fused object, or was left out as a fragment or a piece
  // of another's body (docs/fusion.md), and then by none.
  const std::vector<std::uint32_t>& left_out = engine->last_left_out_lidar_ids();
  for (const auto& [id, count] : seen) {
    const bool out = std::find(left_out.begin(), left_out.end(), id) != left_out.end();
    EXPECT_EQ(count, out ? 0 : 1) << "lidar object " << id;
  }
  const std::int64_t pairs = engine->stats().pairs;
  EXPECT_LT(0, pairs) << "no object was seen by both sensors in 6 s of the crossing group";
  EXPECT_TRUE(result.metrics.values.contains("fusion.position_rmse_m"));
}

}  // namespace
}  // namespace lookout::app

namespace lookout::app {
namespace {

// Tracking and risk close each cycle: the child who runs out from behind the parked car (in
// view from 1.35 s, contact at 5.02 s) is tracked as a pedestrian and warned of by the
// scenario's deadline (2.9 s), and the run reports the tracking.* and risk.* keys.
TEST(RunnerTest, TracksTheChildAndWarnsByTheDeadline) {
  // One literal joined by the preprocessor: std::string + literal here trips GCC 12's known
  // false positive -Warray-bounds at -O3.
  sim::Scenario scenario =
      io::LoadScenarioFile(LOOKOUT_SOURCE_DIR "/scenarios/child-behind-parked-car.yaml");
  scenario.duration_s = 3.0;
  Pipeline pipeline(PipelineOptions{});
  const RunResult result = RunScenario(scenario, pipeline, RunOptions{});
  ASSERT_NE(pipeline.tracking(), nullptr);
  ASSERT_NE(pipeline.risk(), nullptr);
  const auto& m = result.metrics.values;
  for (const char* key : {"tracking.mota", "tracking.motp_m", "tracking.idf1",
                          "tracking.id_switches", "tracking.gospa_m", "risk.warned",
                          "risk.ttc_mae_s", "timing.tracking_ms_median", "timing.risk_ms_median"}) {
    EXPECT_TRUE(m.contains(key)) << key;
  }
  EXPECT_EQ(m.at("risk.warned"), 1.0);
  EXPECT_LE(m.at("risk.first_warning_s"), 2.9);
  // Information may come first (a contact predicted inside the horizon); the warning names the
  // child.
  const auto warning =
      std::find_if(result.warnings.begin(), result.warnings.end(),
                   [](const risk::WarningEvent& e) {
                     return e.level == risk::WarningLevel::kWarning;
                   });
  ASSERT_NE(warning, result.warnings.end());
  EXPECT_EQ(result.warning_classes[static_cast<std::size_t>(warning - result.warnings.begin())],
            ObjectClass::kPedestrian);
  EXPECT_GT(m.at("tracking.recall"), 0.8) << "the child is tracked while in view";
}

TEST(RunnerTest, TheTrackingStageTakesTheCameraOfTheScenariosSensorBlock) {
  const sim::Scenario scenario = io::LoadScenarioText(R"(
format: 1
name: narrow-camera
duration: 1.0
ego: {path: [[0, 0], [10, 0]], speed_profile: [[0, 0.0]]}
sensors:
  stereo: {fov_deg: 50, max_depth: 20}
)",
                                                      "narrow-camera.yaml");
  const DetectionOptions defaults;
  const DetectionOptions d =
      ForSensors(PipelineOptions{}, scenario.sensors).tracking_options.detections;
  EXPECT_NEAR(d.camera_fov_rad, 50.0 * kPi / 180.0, 1e-12);
  EXPECT_DOUBLE_EQ(d.camera_max_depth_m, 20.0);
  EXPECT_NE(d.camera_fov_rad, defaults.camera_fov_rad);
  EXPECT_NE(d.camera_max_depth_m, defaults.camera_max_depth_m);
}

// The four_way preset's two roads as the ego's map, in a frame turned and moved from the
// world's: the ego's lane and the junction are on them, the sidewalks and the blocks are not;
// empty ground has no map.
TEST(RunnerTest, TheFourWayWorldGivesTheMapItsTwoCarriageways) {
  sim::World world;
  world.preset = "four_way";
  const Pose2 frame_from_world(3.0, -2.0, 0.7);
  const risk::Carriageways roads = CarriagewaysOf(world, frame_from_world);
  ASSERT_EQ(roads.size(), 2u);
  const auto on = [&](double x, double y) {
    return risk::OnCarriageway(roads, frame_from_world * Eigen::Vector2d(x, y));
  };
  EXPECT_TRUE(on(-40.0, -1.75)) << "the ego's lane on the east-west road";
  EXPECT_TRUE(on(1.75, 30.0)) << "the north-south road";
  EXPECT_TRUE(on(0.0, 0.0)) << "the junction";
  EXPECT_FALSE(on(-5.3, -7.0)) << "the south-west sidewalk";
  EXPECT_FALSE(on(-20.0, -4.0)) << "the south sidewalk of the east-west road";
  EXPECT_FALSE(on(10.0, 10.0)) << "the north-east block";
  EXPECT_TRUE(CarriagewaysOf(sim::World{}, frame_from_world).empty());
}

}  // namespace
}  // namespace lookout::app
