#include "lookout/io/ros_conversions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lookout/io/ros_bag_test_support.h"

namespace lookout::io {
namespace {

TEST(RosConversions, LaserScanFollowsRep117) {
  const RosMessageDefinition d =
      ParseRosMessageDefinition("sensor_msgs/LaserScan", testing::LaserScanDefinition());
  constexpr float kInf = std::numeric_limits<float>::infinity();
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  // range_min 0.03, range_max 11.
  const std::vector<float> ranges{0.0F, 0.5F, kInf, -kInf, kNaN, 12.0F, 0.02F, 11.0F, 0.03F, -1.0F};
  const RosLaserScan scan = ToLaserScan(DecodeRosMessage(
      d, testing::LaserScanMessage({1403024474, 631777750}, -2.356194496F, 0.006135923F, ranges)));
  EXPECT_EQ(scan.scan.stamp, 1403024474631777750);
  EXPECT_EQ(scan.frame_id, "laser");
  EXPECT_EQ(scan.scan.angle_min_rad, static_cast<double>(-2.356194496F));
  EXPECT_EQ(scan.scan.angle_increment_rad, static_cast<double>(0.006135923F));
  EXPECT_EQ(scan.scan.max_range_m, 11.0);
  EXPECT_EQ(scan.range_min_m, static_cast<double>(0.03F));
  ASSERT_EQ(scan.scan.ranges_m.size(), ranges.size());
  const std::vector<bool> nan{true, false, false, true, true, true, true, false, false, true};
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    EXPECT_EQ(std::isnan(scan.scan.ranges_m[i]), nan[i]) << i;
  }
  EXPECT_EQ(scan.scan.ranges_m[1], 0.5F);
  EXPECT_EQ(scan.scan.ranges_m[2], kInf);  // no return within range stays +inf
  EXPECT_EQ(scan.scan.ranges_m[7], 11.0F);  // both limits are inside
  EXPECT_EQ(scan.scan.ranges_m[8], 0.03F);
  EXPECT_EQ(scan.invalid_beams, 6U);
}

TEST(RosConversions, OdometryPoseTwistAndYaw) {
  const RosMessageDefinition d =
      ParseRosMessageDefinition("nav_msgs/Odometry", testing::OdometryDefinition());
  for (const double yaw : {0.0, 0.7, -2.5, 3.0}) {
    const RosOdometry odometry = ToOdometry(
        DecodeRosMessage(d, testing::OdometryMessage({10, 20}, 3.0, -4.0, yaw, 1.25, 0.5)));
    EXPECT_EQ(odometry.stamp, 10 * kNanosPerSecond + 20);
    EXPECT_EQ(odometry.frame_id, "odom");
    EXPECT_EQ(odometry.child_frame_id, "base_link");
    const Pose2 pose = odometry.Planar();
    EXPECT_EQ(pose.x(), 3.0);
    EXPECT_EQ(pose.y(), -4.0);
    EXPECT_NEAR(pose.yaw, yaw, 1e-12);
    const EgoOdometry ego = odometry.Ego();
    EXPECT_EQ(ego.speed_mps, 1.25);
    EXPECT_EQ(ego.yaw_rate_radps, 0.5);
  }
}

TEST(RosConversions, TransformsAndTheirErrors) {
  const RosMessageDefinition d =
      ParseRosMessageDefinition("tf2_msgs/TFMessage", testing::TfMessageDefinition());
  const std::vector<RosTransform> transforms = ToTransforms(DecodeRosMessage(
      d, testing::TfMessage({{{5, 0}, "odom", "base_link", 1.0, 2.0, 0.25},
                             {{5, 1}, "base_link", "laser", 0.2, -0.1, kPi / 2}})));
  ASSERT_EQ(transforms.size(), 2U);
  EXPECT_EQ(transforms[0].parent_frame, "odom");
  EXPECT_EQ(transforms[0].child_frame, "base_link");
  EXPECT_EQ(transforms[1].stamp, 5 * kNanosPerSecond + 1);
  EXPECT_EQ(transforms[1].translation_m.x(), 0.2);
  EXPECT_NEAR(transforms[1].Planar().yaw, kPi / 2, 1e-12);
  EXPECT_NEAR(transforms[0].Planar().yaw, 0.25, 1e-12);

  // An all-zero quaternion (an unset rotation) is no rotation: refused, naming the transform.
  testing::RosSerializer s;
  s.Put(std::uint32_t{1}).PutHeader(0, {1, 0}, "a").PutString("b");
  for (int i = 0; i < 7; ++i) s.Put(0.0);
  try {
    ToTransforms(DecodeRosMessage(d, s.bytes()));
    FAIL();
  } catch (const RosMessageError& e) {
    EXPECT_EQ(e.field(), "transforms[0]");
  }
}

TEST(RosConversions, PersonTruth) {
  const RosMessageDefinition d =
      ParseRosMessageDefinition("leg_tracker/Person", testing::PersonDefinition());
  const PersonTruth person =
      ToPersonTruth(DecodeRosMessage(d, testing::PersonMessage(4.76, -2.81, 1005)), 1234);
  EXPECT_EQ(person.stamp, 1234);
  EXPECT_EQ(person.id, 1005U);
  EXPECT_EQ(person.x_m, 4.76);
  EXPECT_EQ(person.y_m, -2.81);
}

TEST(RosConversions, AMessageOfAnotherShapeIsRefusedByFieldName) {
  // A "LaserScan" whose ranges are float64: the definition decodes, the conversion refuses it.
  const RosMessageDefinition d = ParseRosMessageDefinition(
      "sensor_msgs/LaserScan",
      "Header header\nfloat32 angle_min\nfloat32 angle_increment\nfloat32 scan_time\n"
      "float32 range_min\nfloat32 range_max\nstring[] ranges\n===\nMSG: std_msgs/Header\n"
      "uint32 seq\ntime stamp\nstring frame_id\n");
  testing::RosSerializer s;
  s.PutHeader(0, {1, 0}, "l");
  for (int i = 0; i < 5; ++i) s.Put(1.0F);
  s.Put(std::uint32_t{0});
  try {
    ToLaserScan(DecodeRosMessage(d, s.bytes()));
    FAIL();
  } catch (const RosMessageError& e) {
    EXPECT_EQ(e.field(), "ranges");
  }
}

}  // namespace
}  // namespace lookout::io
