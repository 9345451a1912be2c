#include "lookout/app/runner.h"

#include <gtest/gtest.h>

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
  void OnOdometry(const EgoOdometry& o) override { seen_->push_back({o.stamp, SensorOrder::kOdometry}); }
  void OnStereo(const StereoFrame& f) override { seen_->push_back({f.stamp, SensorOrder::kStereo}); }
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
  sim::Scenario scenario = io::LoadScenarioFile(std::string(LOOKOUT_SOURCE_DIR) +
                                                "/scenarios/pushchair-group.yaml");
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
  for (const auto& [id, count] : seen) EXPECT_EQ(count, 1) << "lidar object " << id;
  const fusion::FusionEngine* engine = pipeline.fusion();
  ASSERT_NE(engine, nullptr);
  const std::int64_t pairs = engine->stats().pairs;
  EXPECT_LT(0, pairs) << "no object was seen by both sensors in 6 s of the crossing group";
  EXPECT_TRUE(result.metrics.values.contains("fusion.position_rmse_m"));
}

}  // namespace
}  // namespace lookout::app
