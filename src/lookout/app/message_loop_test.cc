#include "lookout/app/message_loop.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lookout/io/mcap_reader.h"
#include "lookout/io/recorder.h"

namespace lookout::app {
namespace {

using Seen = std::vector<std::pair<TimeNs, SensorOrder>>;

class ProbeStage : public Stage {
 public:
  explicit ProbeStage(Seen* seen) : seen_(seen) {}
  void OnOdometry(const EgoOdometry& o) override {
    seen_->push_back({o.stamp, SensorOrder::kOdometry});
  }
  void OnStereo(const StereoFrame& f) override {
    seen_->push_back({f.stamp, SensorOrder::kStereo});
  }
  void OnLidar(const LidarScan& s) override { seen_->push_back({s.stamp, SensorOrder::kLidar}); }

 private:
  Seen* seen_;
};

template <typename Message>
std::vector<Message> At(std::vector<TimeNs> stamps) {
  std::vector<Message> messages(stamps.size());
  for (std::size_t i = 0; i < stamps.size(); ++i) messages[i].stamp = stamps[i];
  return messages;
}

TEST(MessageLoopTest, MergesStreamsByStampThenSensorOrderAndCallsBackAfterEachScan) {
  const auto lidar = At<LidarScan>({0, 100, 100, 250});
  const auto stereo = At<StereoFrame>({100, 300});
  const auto odometry = At<EgoOdometry>({0, 50, 100, 250});
  Seen seen;
  Pipeline pipeline;
  pipeline.Add(std::make_unique<ProbeStage>(&seen));
  std::vector<std::size_t> cycles;
  MessageLoopOptions options;
  options.after_cycle = [&](const LidarCycle& c) {
    EXPECT_EQ(c.scan, &lidar[c.index]);
    EXPECT_EQ(c.objects, nullptr);  // no grid in this pipeline
    cycles.push_back(c.index);
  };
  const MessageLoopResult result =
      RunMessageLoop(SensorStreams{lidar, stereo, odometry}, pipeline, options);

  const Seen want = {{0, SensorOrder::kOdometry},   {0, SensorOrder::kLidar},
                     {50, SensorOrder::kOdometry},  {100, SensorOrder::kOdometry},
                     {100, SensorOrder::kStereo},   {100, SensorOrder::kLidar},
                     {100, SensorOrder::kLidar},    {250, SensorOrder::kOdometry},
                     {250, SensorOrder::kLidar},    {300, SensorOrder::kStereo}};
  EXPECT_EQ(seen, want);
  EXPECT_EQ(cycles, (std::vector<std::size_t>{0, 1, 2, 3}));
  EXPECT_EQ(result.step_ms.size(), 4u);
}

TEST(MessageLoopTest, RecordsEveryMessageAndFinishesTheRecording) {
  const auto lidar = At<LidarScan>({0, 100});
  const auto stereo = At<StereoFrame>({50});
  const auto odometry = At<EgoOdometry>({0, 50, 100});
  const std::string path =
      (std::filesystem::temp_directory_path() / "lookout_message_loop_test.mcap").string();
  Seen seen;
  Pipeline pipeline;
  pipeline.Add(std::make_unique<ProbeStage>(&seen));
  io::Recorder recorder(path);
  MessageLoopOptions options;
  options.recorder = &recorder;
  const MessageLoopResult result =
      RunMessageLoop(SensorStreams{lidar, stereo, odometry}, pipeline, options);

  const std::map<std::string, std::uint64_t> want = {
      {io::topics::kLidarScan, 2}, {io::topics::kStereoObjects, 1}, {io::topics::kOdometry, 3}};
  EXPECT_EQ(result.messages_per_topic, want);
  // Finished: the file is whole (its summary written), without the caller finishing it.
  const io::McapContents file = io::ReadMcapFile(path);
  EXPECT_EQ(file.messages.size(), 6u);
  ASSERT_TRUE(file.statistics.has_value());
  EXPECT_EQ(file.statistics->message_count, 6u);
  std::filesystem::remove(path);
}

TEST(MessageLoopTest, DeliversEveryMessageEvenAtTheLargestStampAndWithEmptyStreams) {
  constexpr TimeNs kMax = std::numeric_limits<TimeNs>::max();
  const auto lidar = At<LidarScan>({kMax});
  const auto odometry = At<EgoOdometry>({kMax});
  Seen seen;
  Pipeline pipeline;
  pipeline.Add(std::make_unique<ProbeStage>(&seen));
  RunMessageLoop(SensorStreams{lidar, {}, odometry}, pipeline, {});
  EXPECT_EQ(seen, (Seen{{kMax, SensorOrder::kOdometry}, {kMax, SensorOrder::kLidar}}));

  seen.clear();
  RunMessageLoop(SensorStreams{}, pipeline, {});
  EXPECT_TRUE(seen.empty());
}

}  // namespace
}  // namespace lookout::app
