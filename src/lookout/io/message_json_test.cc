#include "lookout/io/message_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lookout/core/input_error.h"
#include "lookout/io/json_schemas.h"

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

TEST(MessageJsonTest, LidarObjectsDrawnAsSceneUpdateInTheVehicleFrame) {
  LidarObjectFrame frame;
  frame.stamp = 1'500'000'000;
  LidarObject moving;
  moving.id = 0;
  moving.centroid_m = {10.0, 2.0};
  moving.length_m = 4.5;
  moving.width_m = 1.8;
  moving.velocity_mps = {3.0, 4.0};
  moving.class_pmf[static_cast<std::size_t>(ObjectClass::kCar)] = 1.0;
  moving.cell_count = 57;
  moving.dynamic = true;
  LidarObject standing = moving;
  standing.id = 1;
  standing.velocity_mps = {0.0, 0.0};
  standing.dynamic = false;
  frame.objects = {moving, standing};
  const nlohmann::json j = LidarObjectsSceneToJson(frame, "base_link");

  // Every update first deletes all earlier objects (type 1: all).
  ASSERT_EQ(j["deletions"].size(), 1u);
  EXPECT_EQ(j["deletions"][0]["type"], 1);
  ASSERT_EQ(j["entities"].size(), 2u);
  const nlohmann::json& e = j["entities"][0];
  EXPECT_EQ(e["frame_id"], "base_link");
  EXPECT_EQ(e["id"], "lidar-object-0");
  EXPECT_EQ(e["timestamp"]["sec"], 1);
  EXPECT_EQ(e["timestamp"]["nsec"], 500'000'000);
  // The velocity arrow: 5 m/s drawn 2.5 m long, along (3, 4); none for the standing object.
  ASSERT_EQ(e["arrows"].size(), 1u);
  EXPECT_DOUBLE_EQ(e["arrows"][0]["shaft_length"].get<double>() +
                       e["arrows"][0]["head_length"].get<double>(),
                   2.5);
  EXPECT_TRUE(j["entities"][1]["arrows"].empty());
  // The extent's outline is the 4.5 x 1.8 box about the centroid (yaw 0).
  const nlohmann::json& ring = e["lines"][0]["points"];
  ASSERT_EQ(ring.size(), 4u);
  EXPECT_DOUBLE_EQ(ring[0]["x"].get<double>(), 10.0 - 2.25);
  EXPECT_DOUBLE_EQ(ring[2]["y"].get<double>(), 2.0 + 0.9);
  bool found = false;
  for (const nlohmann::json& m : e["metadata"]) {
    if (m["key"] == "cell_count") {
      EXPECT_EQ(m["value"], "57");
      found = true;
    }
    if (m["key"] == "class") {
      EXPECT_EQ(m["value"], "car");
    }
  }
  EXPECT_TRUE(found);

  // Every primitive's fields are ones the SceneUpdate schema declares.
  const nlohmann::json schema = nlohmann::json::parse(FoxgloveSceneUpdateSchema().text);
  const nlohmann::json& entity = schema["properties"]["entities"]["items"]["properties"];
  for (const char* kind : {"arrows", "lines", "texts"}) {
    const nlohmann::json& declared = entity[kind]["items"]["properties"];
    for (const nlohmann::json& primitive : e[kind]) {
      for (const auto& [key, value] : primitive.items()) {
        EXPECT_TRUE(declared.contains(key)) << kind << "." << key << " is not in the schema";
      }
    }
  }
  EXPECT_EQ(j.dump(), LidarObjectsSceneToJson(frame, "base_link").dump());
}

}  // namespace
}  // namespace lookout::io
