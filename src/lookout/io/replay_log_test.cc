#include "lookout/io/replay_log.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

#include "lookout/core/dead_reckoning.h"
#include "lookout/core/input_error.h"
#include "lookout/io/recorder.h"
#include "lookout/io/ros_bag_test_support.h"

namespace lookout::io {
namespace {

namespace fs = std::filesystem;

std::string PoseText(const Pose2& p) {
  return fmt::format("{:.9f} {:.9f} {:.9f}", p.x(), p.y(), p.yaw);
}

// A raw CARMEN log (no anchors): odometry at 20 Hz along a curve, a scan after every fourth
// reading sharing its stamp (as the Radish logs print them), the laser 0.3 m ahead.
struct CarmenText {
  std::string text;
  std::vector<double> times;
  std::vector<Pose2> poses;  // odometry, one per ODOM line
};

// `early`: the reading whose ODOM line (and scan) are printed 10 s early, or -1.
CarmenText MakeCarmen(int readings, const std::vector<std::string>& ranges = {"1.5", "2", "2.5"},
                      int early = -1) {
  CarmenText c;
  c.text = "PARAM robot_frontlaser_offset 0.3 nohost 0\nPARAM laser_front_laser_fov 90 nohost 0\n";
  Pose2 pose(2.0, -1.0, 0.4);
  for (int i = 0; i < readings; ++i) {
    // Arcs of varying curvature, and once a stretch backwards.
    const double turn = 0.05 * std::sin(0.3 * i);
    const double step = i == 10 ? -0.04 : 0.05;
    if (i > 0) pose = pose * Pose2(step * std::cos(turn / 2), step * std::sin(turn / 2), turn);
    const double t = 1.0 + 0.05 * i - (i == early ? 10.0 : 0.0);
    c.times.push_back(t);
    c.poses.push_back(pose);
    c.text += fmt::format("ODOM {} 0 0 0 {:.6f} host {:.6f}\n", PoseText(pose), t, t);
    if (i % 4 == 3) {
      std::string line = fmt::format("FLASER {}", ranges.size());
      for (const std::string& r : ranges) line += " " + r;
      const Pose2 reference = Pose2(10, 0, 1.0) * pose;
      c.text += line + fmt::format(" {} {} {:.6f} host {:.6f}\n", PoseText(reference),
                                   PoseText(reference), t, t);
    }
  }
  return c;
}

TEST(ReplayLogTest, TellsFormatsApartByTheirBytes) {
  EXPECT_EQ(DetectLogFormat("#ROSBAG V2.0\n..."), LogFormat::kRosBag);
  EXPECT_EQ(DetectLogFormat(std::string("\x89MCAP0\r\n", 8) + "..."), LogFormat::kMcap);
  EXPECT_EQ(DetectLogFormat("ODOM 1 2 3"), LogFormat::kCarmen);
  EXPECT_EQ(DetectLogFormat(""), LogFormat::kCarmen);
  try {
    ReplayLogFromBytes("hello\x01\x02 this is no log", "junk.bin");
    FAIL() << "junk was read as a log";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "junk.bin");
    EXPECT_EQ(e.field(), "format");
  }
  EXPECT_THROW(ReplayLogFromBytes("\x1f\x8b\x08 gzip in memory", "x.gz"), InputError);
  EXPECT_THROW(ReplayLogFromBytes("PK\x03\x04 not really a zip", "x.zip"), InputError);
}

// Dead reckoning through the odometry readings made from a CARMEN log passes through the log's
// raw odometry poses: the conversion from poses to speed and yaw rate loses nothing the
// pipeline's motion model can use.
TEST(ReplayLogTest, CarmenOdometryAsSpeedAndYawRateReproducesTheRawPoses) {
  const CarmenText c = MakeCarmen(60);
  const ReplayLog log = ReplayLogFromBytes(c.text, "dir/test-corrected.log");
  EXPECT_EQ(log.format, LogFormat::kCarmen);
  EXPECT_EQ(log.name, "test-corrected");
  ASSERT_EQ(log.odometry.size(), c.poses.size());
  ASSERT_EQ(log.lidar.size(), 15u);
  ASSERT_EQ(log.reference.size(), 15u);
  DeadReckoningOptions options;
  options.initial_pose = c.poses.front();
  DeadReckoning dead_reckoning(options);
  for (std::size_t i = 0; i < log.odometry.size(); ++i) {
    EXPECT_EQ(log.odometry[i].stamp, FromSeconds(c.times[i]));
    ASSERT_TRUE(dead_reckoning.Add(log.odometry[i]));
    const Pose2 p = dead_reckoning.At(log.odometry[i].stamp).pose;
    EXPECT_NEAR((p.translation - c.poses[i].translation).norm(), 0.0, 1e-6) << "reading " << i;
    EXPECT_NEAR(WrapAngle(p.yaw - c.poses[i].yaw), 0.0, 1e-6) << "reading " << i;
  }
  // The scans: their stamps, the laser's mount, the field of view; the reference at each.
  const LidarScan& s = log.lidar.front();
  EXPECT_EQ(s.stamp, FromSeconds(c.times[3]));
  EXPECT_EQ(s.mount.x(), 0.3);
  EXPECT_NEAR(s.angle_min_rad, -kPi / 4, 1e-9);
  EXPECT_EQ(log.reference.front().stamp, s.stamp);
  EXPECT_NEAR(log.reference.front().pose.x(), (Pose2(10, 0, 1.0) * c.poses[3]).x(), 1e-6);
  EXPECT_NEAR(log.duration_s, c.times.back() - c.times.front(), 1e-9);
  EXPECT_TRUE(log.counts.empty());
}

TEST(ReplayLogTest, ALogWithoutATimeBaseIsRefusedNamingTheField) {
  std::string text = MakeCarmen(20).text;
  // Every time printed as 0, as freiburg-campus and orebro have them.
  std::string zeroed;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = text.find('\n', start);
    std::string line = text.substr(start, end - start);
    if (line.starts_with("ODOM") || line.starts_with("FLASER")) {
      const std::size_t host = line.find(" host ");
      const std::size_t before = line.rfind(' ', host - 1);
      line = line.substr(0, before) + " 0 host 0";
    }
    zeroed += line + "\n";
    start = end + 1;
  }
  try {
    ReplayLogFromBytes(zeroed, "zero.log");
    FAIL() << "a log without a time base was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "zero.log");
    EXPECT_EQ(e.field(), "ipc_timestamp");
  }
}

TEST(ReplayLogTest, TimeGoingBackwardsAndBadRangesAreCountedNotFatal) {
  // Reading 23 and its scan printed 10 s early: they go back in time.
  const CarmenText c = MakeCarmen(40, {"1.5", "-1", "nan", "2"}, 23);
  const ReplayLog log = ReplayLogFromBytes(c.text, "back.log");
  EXPECT_EQ(log.lidar.size(), 9u);
  EXPECT_EQ(log.counts.at("scans_backwards"), 1u);
  EXPECT_EQ(log.counts.at("odometry_backwards"), 1u);
  EXPECT_FALSE(log.warnings.empty());
  // Negative and NaN readings: no measurement (NaN), counted; the valid ones kept.
  for (const LidarScan& s : log.lidar) {
    ASSERT_EQ(s.ranges_m.size(), 4u);
    EXPECT_EQ(s.ranges_m[0], 1.5f);
    EXPECT_TRUE(std::isnan(s.ranges_m[1]));
    EXPECT_TRUE(std::isnan(s.ranges_m[2]));
  }
  EXPECT_EQ(log.counts.at("invalid_ranges"), 2u * log.lidar.size());
  for (std::size_t i = 1; i < log.odometry.size(); ++i) {
    EXPECT_GT(log.odometry[i].stamp, log.odometry[i - 1].stamp);
  }
}

// A bag as a ROS robot records one: scans in the laser's frame, mounted on base_link through
// /tf; odometry of base_link; people annotated in the laser frame (the marker says so),
// stamped between scan records.
std::string SmallRobotBag(bool with_marker) {
  using testing::RosSerializer;
  testing::TestBagWriter writer({"bz2", 5, true});
  writer.AddConnection(0, "/scan", "sensor_msgs/LaserScan", testing::LaserScanDefinition());
  writer.AddConnection(1, "/odom", "nav_msgs/Odometry", testing::OdometryDefinition());
  writer.AddConnection(2, "/tf", "tf2_msgs/TFMessage", testing::TfMessageDefinition());
  writer.AddConnection(3, "/ground_truth_people_tracks", "leg_tracker/Person",
                       testing::PersonDefinition());
  writer.AddConnection(4, "/visualization_marker", "visualization_msgs/Marker",
                       "Header header\nstring ns\nint32 id\n" + testing::kSeparator + "\n" +
                           std::string(testing::kHeaderDefinition));
  writer.AddMessage(2, {100, 0},
                    testing::TfMessage({{{100, 0}, "base_link", "laser", 0.8, 0.2, 0.5}}));
  for (std::uint32_t k = 0; k < 5; ++k) {
    const RosTime stamp{101 + k, 0};
    writer.AddMessage(1, stamp, testing::OdometryMessage(stamp, k, 0, 0, 1.0, 0.0));
    // Scans recorded 50 ms after their header stamp.
    writer.AddMessage(0, {101 + k, 50'000'000},
                      testing::LaserScanMessage(stamp, -1.0F, 0.5F, {1, 2, 0, 3, 11.5F}));
  }
  // Annotated halfway between the records of scans 1 and 2, at (2, 0) in the laser frame.
  writer.AddMessage(3, {102, 550'000'000}, testing::PersonMessage(2.0, 0.0, 7));
  if (with_marker) {
    RosSerializer marker;
    marker.PutHeader(0, {102, 550'000'000}, "laser")
        .PutString("ground_truth_people_tracks_markers")
        .Put(std::int32_t{7});
    writer.AddMessage(4, {102, 550'000'000}, marker.bytes());
  }
  return writer.Finish();
}

TEST(ReplayLogTest, BagScansAreMountedThroughTfAndPeopleJoinTheScanOnScreen) {
  const ReplayLog log = ReplayLogFromBytes(SmallRobotBag(true), "robot.bag");
  EXPECT_EQ(log.format, LogFormat::kRosBag);
  ASSERT_EQ(log.lidar.size(), 5u);
  ASSERT_EQ(log.odometry.size(), 5u);
  const Pose2 mount(0.8, 0.2, 0.5);
  EXPECT_NEAR(log.lidar[0].mount.x(), mount.x(), 1e-12);
  EXPECT_NEAR(log.lidar[0].mount.yaw, mount.yaw, 1e-12);
  EXPECT_EQ(log.odometry[2].speed_mps, 1.0);
  // 0 (legacy "no reading") and 11.5 (beyond range_max) are discarded: NaN, counted.
  EXPECT_TRUE(std::isnan(log.lidar[0].ranges_m[2]));
  EXPECT_TRUE(std::isnan(log.lidar[0].ranges_m[4]));
  EXPECT_EQ(log.counts.at("invalid_ranges"), 10u);
  EXPECT_EQ(log.people_frame, "laser");
  ASSERT_EQ(log.people.size(), 1u);
  EXPECT_EQ(log.people[0].scan_index, 1u);
  EXPECT_EQ(log.people[0].stamp, log.lidar[1].stamp);
  ASSERT_EQ(log.people[0].people.size(), 1u);
  const Eigen::Vector2d want = mount * Eigen::Vector2d(2.0, 0.0);
  EXPECT_NEAR((log.people[0].people[0].position_m - want).norm(), 0.0, 1e-12);
  EXPECT_EQ(log.people[0].people[0].id, 7u);

  // Without the marker the annotations are taken in the scans' frame, with a warning.
  const ReplayLog unmarked = ReplayLogFromBytes(SmallRobotBag(false), "robot.bag");
  EXPECT_EQ(unmarked.people_frame, "laser");
  EXPECT_FALSE(unmarked.warnings.empty());
}

TEST(ReplayLogTest, AScanFrameWithoutATransformIsRefused) {
  testing::TestBagWriter writer({"none", 5, true});
  writer.AddConnection(0, "/scan", "sensor_msgs/LaserScan", testing::LaserScanDefinition());
  writer.AddConnection(1, "/odom", "nav_msgs/Odometry", testing::OdometryDefinition());
  writer.AddMessage(1, {101, 0}, testing::OdometryMessage({101, 0}, 0, 0, 0, 1.0, 0.0));
  writer.AddMessage(0, {101, 0}, testing::LaserScanMessage({101, 0}, -1.0F, 0.5F, {1, 2}));
  try {
    ReplayLogFromBytes(writer.Finish(), "untransformed.bag");
    FAIL() << "a scan with no mount was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "untransformed.bag");
    EXPECT_EQ(e.field(), "/scan.header.frame_id");
  }
}

// A recording of this program reads back into the messages that were recorded.
TEST(ReplayLogTest, AnMcapRecordingReadsBackIntoItsMessages) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("lookout-replay-{}", getpid());
  fs::create_directories(dir);
  const std::string path = (dir / "recording.mcap").string();
  std::vector<LidarScan> scans;
  std::vector<EgoOdometry> odometry;
  {
    Recorder recorder(path);
    for (int k = 0; k < 4; ++k) {
      EgoOdometry o{FromSeconds(0.02 * k), 3.0 + 0.1 * k, -0.01 * k};
      recorder.Write(o);
      odometry.push_back(o);
      LidarScan s;
      s.stamp = FromSeconds(0.08 * k);
      s.mount = Pose2(1.2, -0.1, 0.02);
      s.angle_min_rad = -1.4;
      s.angle_increment_rad = 0.01;
      s.max_range_m = 80.0;
      s.ranges_m = {1.25f, std::numeric_limits<float>::infinity(), 7.0f / 3.0f};
      recorder.Write(s);
      scans.push_back(s);
    }
    recorder.Finish();
  }
  const ReplayLog log = ReadReplayLog(path);
  fs::remove_all(dir);
  EXPECT_EQ(log.format, LogFormat::kMcap);
  EXPECT_EQ(log.name, "recording");
  ASSERT_EQ(log.lidar.size(), scans.size());
  ASSERT_EQ(log.odometry.size(), odometry.size());
  for (std::size_t k = 0; k < scans.size(); ++k) {
    EXPECT_EQ(log.lidar[k].stamp, scans[k].stamp);
    EXPECT_EQ(log.lidar[k].ranges_m, scans[k].ranges_m);  // bit for bit, inf included
    EXPECT_EQ(log.lidar[k].mount.x(), scans[k].mount.x());
    EXPECT_EQ(log.lidar[k].angle_increment_rad, scans[k].angle_increment_rad);
    EXPECT_EQ(log.odometry[k].speed_mps, odometry[k].speed_mps);
    EXPECT_EQ(log.odometry[k].yaw_rate_radps, odometry[k].yaw_rate_radps);
  }
}

TEST(ReplayLogTest, TopicNamesAreChecked) {
  ReplayLogOptions options;
  options.scan_topic = "scan";
  EXPECT_THROW(options.Validate(), InputError);
  options.scan_topic = "/scan";
  options.odom_topic = "/odom;rm";
  EXPECT_THROW(options.Validate(), InputError);
}

}  // namespace
}  // namespace lookout::io
