#include "lookout/io/ros_bag_log.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <string>

#include "lookout/core/input_error.h"
#include "lookout/io/file_bytes.h"
#include "lookout/io/ros_bag_test_support.h"
#include "lookout/io/zip_entry.h"

namespace lookout::io {
namespace {

using testing::SmallLog;
using testing::TestBagWriter;

TEST(RosBagLog, DecodesTopicsByTypeIntoOneTimeBase) {
  for (const std::string compression : {"none", "bz2", "lz4"}) {
    RosBag bag(SmallLog(compression), "small.bag");
    const RosBagLog log = ReadRosBagLog(bag);
    EXPECT_EQ(log.start_unix_ns, 100 * kNanosPerSecond);
    EXPECT_EQ(log.end_ns, 2 * kNanosPerSecond + 1);
    ASSERT_EQ(log.topics.size(), 5U);
    EXPECT_EQ(log.topics[0].topic, "/chatter");
    EXPECT_EQ(log.topics[0].type, "std_msgs/String");
    EXPECT_EQ(log.topics[2].topic, "/scan");
    EXPECT_EQ(log.topics[2].message_count, 4U);
    EXPECT_EQ(log.scan_topic, "/scan");
    EXPECT_EQ(log.truth_topic, "/truth");
    // The cut scan is skipped and counted; the others come in stamp order, the unstamped one
    // at its record time.
    EXPECT_EQ(log.messages_skipped, 1U);
    ASSERT_EQ(log.warnings.size(), 1U);
    EXPECT_NE(log.warnings[0].find("/scan message at 101.000000300"), std::string::npos)
        << log.warnings[0];
    ASSERT_EQ(log.scans.size(), 3U);
    EXPECT_EQ(log.scans[0].scan.stamp, 800000000);
    EXPECT_EQ(log.scans[1].scan.stamp, 900000000);
    EXPECT_EQ(log.scans[2].scan.stamp, kNanosPerSecond + 200);
    ASSERT_EQ(log.odometry.size(), 1U);
    EXPECT_EQ(log.odometry[0].stamp, kNanosPerSecond + 300);
    ASSERT_EQ(log.transforms.size(), 2U);
    EXPECT_EQ(log.transforms[1].child_frame, "laser");
    ASSERT_EQ(log.people.size(), 2U);
    EXPECT_EQ(log.people[1].id, 8U);
    EXPECT_EQ(log.people[1].stamp, 2 * kNanosPerSecond + 1);
    EXPECT_EQ(log.people[1].x_m, 3.0);
  }
}

TEST(RosBagLog, SeveralScanTopicsNeedAChoice) {
  RosBag bag(SmallLog("none", true), "two.bag");
  try {
    ReadRosBagLog(bag);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "scan_topic");
    EXPECT_NE(e.problem().find("/scan, /scan2"), std::string::npos) << e.problem();
  }
  RosBag again(SmallLog("none", true), "two.bag");
  RosBagLogOptions options;
  options.scan_topic = "/scan2";
  const RosBagLog log = ReadRosBagLog(again, options);
  ASSERT_EQ(log.scans.size(), 1U);
  EXPECT_EQ(log.scans[0].scan.angle_increment_rad, 0.5);
  RosBag third(SmallLog("none", true), "two.bag");
  options.scan_topic = "/odom";
  EXPECT_THROW(ReadRosBagLog(third, options), InputError);
  options.scan_topic = "scan";
  EXPECT_THROW(options.Validate(), InputError);
}

TEST(RosBagLog, ABadDefinitionOfATopicReadIsRefused) {
  TestBagWriter writer({"none", 4, true});
  writer.AddConnection(0, "/scan", "sensor_msgs/LaserScan", "Header header\nfloat32[ ranges\n");
  writer.AddMessage(0, {1, 0}, "");
  RosBag bag(writer.Finish(), "bad.bag");
  try {
    ReadRosBagLog(bag);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "connection 0 (/scan).message_definition");
  }
}

// The fuzz seeds are made by this writer: the bags by fuzz/make_ros_bag_seeds.cc at the fuzz
// build's time (binary seeds stay out of the repository), the messages of fuzz/corpus/ros_message
// committed. With LOOKOUT_WRITE_FUZZ_SEEDS=1 this test rewrites the latter; always, it checks
// that the seed bags read back as what they were made from, and the committed messages are the
// writer's.
TEST(RosBagFuzzSeeds, ReadBackAsWritten) {
  const std::filesystem::path corpus = std::filesystem::path(LOOKOUT_SOURCE_DIR) / "fuzz/corpus";
  const std::vector<std::pair<std::string, std::string>> bags = testing::FuzzSeedBags();
  const std::string scan_definition = testing::LaserScanDefinition();
  const std::vector<std::pair<std::string, std::string>> messages{
      {"laser_scan", "sensor_msgs/LaserScan\n" + scan_definition + '\0' +
                         testing::LaserScanMessage({1, 2}, -1.0F, 0.25F, {0.0F, 1.5F, 30.0F})},
      {"odometry", "nav_msgs/Odometry\n" + testing::OdometryDefinition() + '\0' +
                       testing::OdometryMessage({3, 4}, 1.0, 2.0, 0.5, 0.25, 0.125)},
      {"tf", "tf2_msgs/TFMessage\n" + testing::TfMessageDefinition() + '\0' +
                 testing::TfMessage({{{5, 6}, "odom", "base_link", 1, 2, 0.3}})},
      {"person", "leg_tracker/Person\n" + testing::PersonDefinition() + '\0' +
                     testing::PersonMessage(1.0, -2.0, 1005)}};
  const auto path_of = [&](const std::string& folder, const std::string& name) {
    return corpus / folder / name;
  };
  if (const char* write = std::getenv("LOOKOUT_WRITE_FUZZ_SEEDS"); write != nullptr &&
                                                                   std::string(write) == "1") {
    std::filesystem::create_directories(corpus / "ros_message");
    for (const auto& [name, bytes] : messages) {
      std::ofstream(path_of("ros_message", name), std::ios::binary) << bytes;
    }
  }
  for (const auto& [name, bytes] : bags) {
    if (name.find("two-scan") != std::string::npos) continue;
    RosBag bag(bytes, name);
    const RosBagLog log = ReadRosBagLog(bag);
    EXPECT_EQ(log.scans.size(), 3U) << name;
    EXPECT_EQ(log.people.size(), 2U) << name;
  }
  for (const auto& [name, bytes] : messages) {
    const std::string seed = ReadFileBytes(path_of("ros_message", name).string());
    EXPECT_EQ(seed, bytes) << name;
  }
}

// The leg_tracker benchmark bag (Leigh et al., ICRA 2015), read once for the tests below.
class LegTrackerBag : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string path = std::string(LOOKOUT_SOURCE_DIR) +
                             "/../shared/data/legtracker/general_tracking_moving_1.bag.zip";
    if (!std::filesystem::exists(path)) return;
    bytes_ = new std::string(ReadSingleZipEntry(path).data);
    RosBag bag(*bytes_, path);
    log_ = new RosBagLog(ReadRosBagLog(bag));
  }
  static void TearDownTestSuite() {
    delete log_;
    delete bytes_;
    log_ = nullptr;
    bytes_ = nullptr;
  }
  void SetUp() override {
    if (log_ == nullptr) GTEST_SKIP() << "the leg_tracker data set is not in ../shared/data";
  }
  static std::string* bytes_;
  static RosBagLog* log_;
};
std::string* LegTrackerBag::bytes_ = nullptr;
RosBagLog* LegTrackerBag::log_ = nullptr;

TEST_F(LegTrackerBag, TopicsAndCounts) {
  const RosBagLog& log = *log_;
  const std::vector<std::tuple<std::string, std::string, std::uint64_t>> expected{
      {"/ground_truth_people_tracks", "leg_tracker/Person", 153},
      {"/map", "nav_msgs/OccupancyGrid", 1},
      {"/odom", "nav_msgs/Odometry", 11561},
      {"/rosout", "rosgraph_msgs/Log", 21},
      {"/scan", "sensor_msgs/LaserScan", 873},
      {"/tf", "tf2_msgs/TFMessage", 21744},
      {"/visualization_marker", "visualization_msgs/Marker", 376}};
  ASSERT_EQ(log.topics.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(log.topics[i].topic, std::get<0>(expected[i]));
    EXPECT_EQ(log.topics[i].type, std::get<1>(expected[i]));
    EXPECT_EQ(log.topics[i].message_count, std::get<2>(expected[i]));
  }
  EXPECT_TRUE(log.bag.used_index);
  EXPECT_EQ(log.bag.chunks_read, 36U);
  EXPECT_EQ(log.bag.chunks_skipped, 0U);
  EXPECT_EQ(log.messages_skipped, 0U);
  EXPECT_EQ(log.scans.size(), 873U);
  EXPECT_EQ(log.odometry.size(), 11561U);
  EXPECT_EQ(log.transforms.size(), 139368U);  // 21744 messages of 1 to 24 transforms
  EXPECT_EQ(log.people.size(), 153U);
}

TEST_F(LegTrackerBag, FirstScanAndTimeSpan) {
  const RosBagLog& log = *log_;
  EXPECT_EQ(log.start_unix_ns, 1403024474411337448);
  EXPECT_NEAR(ToSeconds(log.end_ns), 116.43, 0.01);
  const RosLaserScan& first = log.scans.front();
  EXPECT_EQ(first.frame_id, "left_laser");
  EXPECT_EQ(first.scan.stamp, 1403024474631777750 - log.start_unix_ns);
  ASSERT_EQ(first.scan.ranges_m.size(), 768U);
  EXPECT_EQ(first.scan.angle_min_rad, static_cast<double>(-2.356194496154785F));
  EXPECT_EQ(first.scan.angle_increment_rad, static_cast<double>(0.006135923322290182F));
  EXPECT_NEAR(first.scan.BeamAngle(767), 2.3500585556030273, 1e-5);  // the message's angle_max
  EXPECT_EQ(first.scan.max_range_m, 11.0);
  // 36 zeros and 12 NaN discarded (REP 117); 282 beams without a return.
  EXPECT_EQ(first.invalid_beams, 48U);
  EXPECT_EQ(std::count(first.scan.ranges_m.begin(), first.scan.ranges_m.end(),
                       std::numeric_limits<float>::infinity()),
            282);
  for (std::size_t i = 1; i < log.scans.size(); ++i) {
    ASSERT_LE(log.scans[i - 1].scan.stamp, log.scans[i].scan.stamp) << i;
  }
  // About 7.5 Hz over the whole bag.
  EXPECT_NEAR(static_cast<double>(log.scans.size()) /
                  ToSeconds(log.scans.back().scan.stamp - log.scans.front().scan.stamp),
              7.5, 0.1);
}

TEST_F(LegTrackerBag, TwelvePeopleOverThirtySixSeconds) {
  const RosBagLog& log = *log_;
  std::set<std::uint32_t> ids;
  for (const PersonTruth& p : log.people) ids.insert(p.id);
  EXPECT_EQ(ids, (std::set<std::uint32_t>{1, 2, 3, 4, 5, 6, 1000, 1001, 1003, 1004, 1005, 1006}));
  EXPECT_NEAR(ToSeconds(log.people.back().stamp - log.people.front().stamp), 36.1, 0.05);
  EXPECT_EQ(log.people.front().id, 1U);
  EXPECT_NEAR(log.people.front().x_m, 4.76213264465332, 1e-12);
  EXPECT_NEAR(log.people.front().y_m, -2.8100929260253906, 1e-12);
}

// The annotations carry no frame; their markers do (the annotation tool's fixed frame, the
// scan's). Each annotation is stamped halfway between two scan records: between the record
// times, not the header stamps, which lead them by about 64 ms.
TEST_F(LegTrackerBag, AnnotationsAreInTheLaserFrameBetweenScanRecords) {
  const RosBagLog& log = *log_;
  EXPECT_EQ(log.people_frame_id, "left_laser");
  const RosLaserScan& first = log.scans.front();
  EXPECT_EQ(first.record_stamp, 1403024474695328780 - log.start_unix_ns);
  EXPECT_NEAR(ToSeconds(first.record_stamp - first.scan.stamp), 0.0636, 0.001);
  std::size_t between = 0;
  for (const PersonTruth& p : log.people) {
    const auto after = std::upper_bound(
        log.scans.begin(), log.scans.end(), p.stamp,
        [](TimeNs t, const RosLaserScan& s) { return t < s.record_stamp; });
    ASSERT_NE(after, log.scans.begin());
    ASSERT_NE(after, log.scans.end());
    const TimeNs before = std::prev(after)->record_stamp;
    const TimeNs mid = before + (after->record_stamp - before) / 2;
    // rospy's float arithmetic: within a millisecond (one is 0.23 ms off, the others 1 ns).
    if (std::abs(p.stamp - mid) <= 1'000'000) ++between;
  }
  EXPECT_EQ(between, log.people.size());
}

TEST_F(LegTrackerBag, OdometryAndTransformFrames) {
  const RosBagLog& log = *log_;
  EXPECT_EQ(log.odometry.front().frame_id, "/odom");  // ROS1's old global frame names
  EXPECT_EQ(log.odometry.front().child_frame_id, "/base_link");
  std::set<std::pair<std::string, std::string>> edges;
  for (const RosTransform& t : log.transforms) edges.emplace(t.parent_frame, t.child_frame);
  EXPECT_EQ(edges.size(), 24U);
  EXPECT_EQ(edges.count({"base_link", "left_laser"}), 1U);
  EXPECT_EQ(edges.count({"/odom", "/base_link"}), 1U);
}

// Every connection's own definition text (comments, constants, nested types and all) parses,
// and every message of every topic decodes by it with no byte left over: the topics the log
// does not convert too (rosgraph_msgs/Log, nav_msgs/OccupancyGrid, visualization_msgs/Marker).
TEST_F(LegTrackerBag, EveryDefinitionParsesAndEveryMessageDecodes) {
  RosBag bag(*bytes_, "leg_tracker.bag");
  std::map<std::uint32_t, RosMessageDefinition> definitions;
  for (const auto& [id, connection] : bag.connections()) {
    definitions.emplace(id,
                        ParseRosMessageDefinition(connection.type, connection.message_definition));
  }
  ASSERT_EQ(definitions.size(), 7U);
  const RosMessageDefinition& marker = definitions.at(6);
  EXPECT_EQ(marker.root, "visualization_msgs/Marker");
  const std::vector<RosConstant>& constants = marker.Root().constants;
  ASSERT_FALSE(constants.empty());
  EXPECT_EQ(constants.front().name, "ARROW");
  EXPECT_EQ(constants.front().value, "0");
  EXPECT_EQ(definitions.at(2).Root().fields.size(), 4U);  // Odometry
  EXPECT_EQ(definitions.at(3).Root().fields.size(), 10U);  // LaserScan

  std::map<std::uint32_t, std::uint64_t> decoded;
  std::uint64_t failures = 0;
  bag.ForEachMessage([&](const RosConnection& c, const RosBagMessage& m) {
    try {
      DecodeRosMessage(definitions.at(c.id), m.data);
      ++decoded[c.id];
    } catch (const RosMessageError& e) {
      if (failures++ == 0) ADD_FAILURE() << c.topic << ": " << e.what();
    }
  });
  EXPECT_EQ(failures, 0U);
  EXPECT_EQ(decoded.at(0), 21U);
  EXPECT_EQ(decoded.at(4), 1U);
  EXPECT_EQ(decoded.at(6), 376U);
}

TEST_F(LegTrackerBag, WithoutItsIndexTheSameLog) {
  std::string bytes = *bytes_;
  const std::uint64_t zero = 0;
  // The bag header's index_pos field: what an unclosed recording has.
  const std::size_t at = bytes.find("index_pos=") + 10;
  std::memcpy(bytes.data() + at, &zero, 8);
  RosBag bag(std::move(bytes), "unindexed.bag");
  const RosBagLog log = ReadRosBagLog(bag);
  EXPECT_FALSE(log.bag.used_index);
  EXPECT_EQ(log.start_unix_ns, log_->start_unix_ns);
  EXPECT_EQ(log.scans.size(), log_->scans.size());
  EXPECT_EQ(log.transforms.size(), log_->transforms.size());
  ASSERT_EQ(log.people.size(), log_->people.size());
  for (std::size_t i = 0; i < log.people.size(); ++i) {
    EXPECT_EQ(log.people[i].stamp, log_->people[i].stamp);
    EXPECT_EQ(log.people[i].x_m, log_->people[i].x_m);
  }
  EXPECT_EQ(std::memcmp(log.scans.back().scan.ranges_m.data(),
                        log_->scans.back().scan.ranges_m.data(),
                        log.scans.back().scan.ranges_m.size() * sizeof(float)),
            0);
}

TEST_F(LegTrackerBag, CorruptedCopiesNeverCrash) {
  constexpr std::uint64_t kSeed = 20261122;
  std::mt19937_64 rng(kSeed);
  const auto read = [&](std::string bytes) {
    try {
      RosBag bag(std::move(bytes), "corrupt.bag");
      return ReadRosBagLog(bag).scans.size();
    } catch (const InputError&) {
      return std::size_t{0};
    }
  };
  for (int i = 0; i < 6; ++i) {
    std::string bytes = *bytes_;
    const std::size_t at = rng() % bytes.size();
    bytes[at] = static_cast<char>(bytes[at] ^ static_cast<char>(1 + rng() % 255));
    EXPECT_LE(read(std::move(bytes)), 873U) << "seed " << kSeed << ", flip at " << at;
  }
  for (int i = 0; i < 6; ++i) {
    const std::size_t at = rng() % bytes_->size();
    EXPECT_LE(read(bytes_->substr(0, at)), 873U) << "seed " << kSeed << ", cut at " << at;
  }
}

}  // namespace
}  // namespace lookout::io
