#include "lookout/io/message_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lookout/core/input_error.h"

namespace lookout::io {
namespace {

TEST(MessageJsonTest, LidarScanRoundTripsWithNoReturnsAsNull) {
  LidarScan scan;
  scan.stamp = 3 * kNanosPerSecond + 80'000'000;
  scan.mount = Pose2(2.2, 0.1, 0.05);
  scan.angle_min_rad = -1.3962634;
  scan.angle_increment_rad = 0.0043633231;
  scan.max_range_m = 150.0;
  scan.ranges_m = {1.25f, std::numeric_limits<float>::infinity(), 149.99f};
  const nlohmann::json j = LidarScanToJson(scan, "lidar");
  EXPECT_TRUE(j["ranges"][1].is_null());
  EXPECT_EQ(j["timestamp"]["sec"], 3);
  EXPECT_EQ(j["timestamp"]["nsec"], 80'000'000);
  EXPECT_DOUBLE_EQ(j["end_angle"].get<double>(), scan.BeamAngle(2));

  const LidarScan back = LidarScanFromJson(nlohmann::json::parse(j.dump()), "test");
  EXPECT_EQ(back.stamp, scan.stamp);
  EXPECT_EQ(back.ranges_m[0], scan.ranges_m[0]);  // exact: floats survive the text
  EXPECT_TRUE(std::isinf(back.ranges_m[1]));
  EXPECT_EQ(back.ranges_m[2], scan.ranges_m[2]);
  EXPECT_DOUBLE_EQ(back.angle_increment_rad, scan.angle_increment_rad);
  EXPECT_DOUBLE_EQ(back.mount.yaw, scan.mount.yaw);
}

TEST(MessageJsonTest, StereoFrameRoundTrips) {
  StereoFrame f;
  f.stamp = 50'000'000;
  f.mount = Pose2(0.8, 0.0, 0.0);
  StereoObject o;
  o.id = 7;
  o.object_class = ObjectClass::kCyclist;
  o.center_m = {12.5, -1.25};
  o.yaw_rad = 1.5;
  o.length_m = 1.8;
  o.width_m = 0.6;
  o.speed_longitudinal_mps = -0.5;
  o.speed_lateral_mps = 4.0;
  o.center_covariance << 0.2, 0.01, 0.01, 0.05;
  o.yaw_variance = 0.01;
  o.speed_variance = 0.25;
  o.history = 12;
  f.objects.push_back(o);
  const StereoFrame back =
      StereoFrameFromJson(nlohmann::json::parse(StereoFrameToJson(f, "stereo").dump()), "t");
  ASSERT_EQ(back.objects.size(), 1u);
  const StereoObject& b = back.objects[0];
  EXPECT_EQ(b.id, 7u);
  EXPECT_EQ(b.object_class, ObjectClass::kCyclist);
  EXPECT_EQ(b.center_m, o.center_m);
  EXPECT_EQ(b.center_covariance, o.center_covariance);
  EXPECT_EQ(b.history, 12u);
  EXPECT_DOUBLE_EQ(b.speed_lateral_mps, 4.0);
}

TEST(MessageJsonTest, OdometryRoundTripsAndMalformedIsRefusedWithField) {
  const EgoOdometry o{20'000'000, 11.1, -0.02};
  const EgoOdometry back = EgoOdometryFromJson(EgoOdometryToJson(o), "t");
  EXPECT_EQ(back.stamp, o.stamp);
  EXPECT_DOUBLE_EQ(back.speed_mps, o.speed_mps);
  EXPECT_DOUBLE_EQ(back.yaw_rate_radps, o.yaw_rate_radps);

  nlohmann::json bad = EgoOdometryToJson(o);
  bad["speed"] = "fast";
  try {
    EgoOdometryFromJson(bad, "rec.mcap");
    FAIL() << "a string speed was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "speed");
    EXPECT_EQ(e.file(), "rec.mcap");
  }
}

TEST(MessageJsonTest, GridInterleavesUint8LayersRowByRowFromTheOrigin) {
  const GridGeometry g{Eigen::Vector2d(-1.5, 2.0), 0.5, 2, 2};
  const nlohmann::json j =
      GridToJson(7, "odom", g, {{"occupancy", {0, 1, 2, 3}}, {"speed", {10, 11, 12, 13}}});
  EXPECT_EQ(j["frame_id"], "odom");
  EXPECT_EQ(j["column_count"], 2);
  EXPECT_EQ(j["cell_stride"], 2);
  EXPECT_EQ(j["row_stride"], 4);
  EXPECT_DOUBLE_EQ(j["cell_size"]["x"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["pose"]["position"]["x"].get<double>(), -1.5);
  EXPECT_EQ(j["fields"][1]["name"], "speed");
  EXPECT_EQ(j["fields"][1]["offset"], 1);
  EXPECT_EQ(j["fields"][1]["type"], 1);  // UINT8
  // Bytes 00 0a 01 0b 02 0c 03 0d: cell by cell, each cell's layers together.
  EXPECT_EQ(j["data"], "AAoBCwIMAw0=");
  EXPECT_THROW(GridToJson(7, "odom", g, {{"short", {1, 2, 3}}}), std::invalid_argument);
}

TEST(MessageJsonTest, EncodingIsDeterministic) {
  const EgoOdometry o{1, 0.1, 0.2};
  EXPECT_EQ(EgoOdometryToJson(o).dump(), EgoOdometryToJson(o).dump());
  EXPECT_EQ(EgoOdometryToJson(o).dump(),
            R"({"speed":0.1,"timestamp":{"nsec":1,"sec":0},"yaw_rate":0.2})");
}

}  // namespace
}  // namespace lookout::io
