#include "lookout/io/ros_message.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lookout/io/ros_bag_test_support.h"

namespace lookout::io {
namespace {

using testing::LaserScanDefinition;
using testing::OdometryDefinition;
using testing::PersonDefinition;
using testing::RosSerializer;
using testing::TfMessageDefinition;

const RosField& FieldOf(const RosMessageDefinition& d, const std::string& type,
                        const std::string& name) {
  const RosMessageSpec& spec = d.specs.at(type);
  return spec.fields.at(spec.FieldIndex(name).value());
}

TEST(RosMessageDefinition, LaserScanFieldsAndHeader) {
  // The real text with its comments, as the sensor_msgs package has it.
  const std::string text =
      "Header header            # timestamp in the header is the acquisition time of \n"
      "                         # the first ray in the scan.\n"
      "float32 angle_min        # start angle of the scan [rad]\n"
      "float32 angle_max\nfloat32 angle_increment\nfloat32 time_increment\nfloat32 scan_time\n"
      "float32 range_min\nfloat32 range_max\n"
      "float32[] ranges         # range data [m] (Note: values < range_min or > range_max "
      "should be discarded)\n"
      "float32[] intensities    # intensity data [device-specific units].  If your\n"
      "\n================================================================================\n"
      "MSG: std_msgs/Header\n# Standard metadata\nuint32 seq\ntime stamp\nstring frame_id\n";
  const RosMessageDefinition d = ParseRosMessageDefinition("sensor_msgs/LaserScan", text);
  EXPECT_EQ(d.root, "sensor_msgs/LaserScan");
  ASSERT_EQ(d.Root().fields.size(), 10U);
  EXPECT_EQ(d.Root().fields[0].type, RosType::kMessage);
  EXPECT_EQ(d.Root().fields[0].message_type, "std_msgs/Header");
  EXPECT_EQ(FieldOf(d, "sensor_msgs/LaserScan", "ranges").type, RosType::kFloat32);
  EXPECT_EQ(FieldOf(d, "sensor_msgs/LaserScan", "ranges").array, RosArray::kVariable);
  EXPECT_EQ(FieldOf(d, "std_msgs/Header", "stamp").type, RosType::kTime);
  EXPECT_EQ(FieldOf(d, "std_msgs/Header", "frame_id").type, RosType::kString);
  // header 16 + 7 floats + two empty arrays.
  EXPECT_EQ(MinimumSerializedSize(d, d.root), 16U + 28U + 8U);
}

TEST(RosMessageDefinition, OdometryResolvesPackagesAndFixedArrays) {
  const RosMessageDefinition d =
      ParseRosMessageDefinition("nav_msgs/Odometry", OdometryDefinition());
  EXPECT_EQ(d.specs.size(), 9U);
  // "Pose pose" inside geometry_msgs/PoseWithCovariance means geometry_msgs/Pose.
  EXPECT_EQ(FieldOf(d, "geometry_msgs/PoseWithCovariance", "pose").message_type,
            "geometry_msgs/Pose");
  const RosField& covariance = FieldOf(d, "geometry_msgs/PoseWithCovariance", "covariance");
  EXPECT_EQ(covariance.array, RosArray::kFixed);
  EXPECT_EQ(covariance.fixed_length, 36U);
  EXPECT_EQ(covariance.type, RosType::kFloat64);
  // header 16, child_frame_id 4, pose 7*8 + 36*8, twist 6*8 + 36*8.
  EXPECT_EQ(MinimumSerializedSize(d, d.root), 16U + 4U + 344U + 336U);
}

TEST(RosMessageDefinition, TfMessageAndPerson) {
  const RosMessageDefinition tf =
      ParseRosMessageDefinition("tf2_msgs/TFMessage", TfMessageDefinition());
  EXPECT_EQ(tf.Root().fields.at(0).message_type, "geometry_msgs/TransformStamped");
  EXPECT_EQ(tf.Root().fields.at(0).array, RosArray::kVariable);
  const RosMessageDefinition person =
      ParseRosMessageDefinition("leg_tracker/Person", PersonDefinition());
  EXPECT_EQ(FieldOf(person, "leg_tracker/Person", "id").type, RosType::kUint32);
  EXPECT_EQ(FieldOf(person, "leg_tracker/Person", "pose").message_type, "geometry_msgs/Pose");
}

TEST(RosMessageDefinition, Constants) {
  const RosMessageDefinition d = ParseRosMessageDefinition(
      "test_msgs/C",
      "uint8 DEBUG=1 # a comment\nint8 LOW = -128\nstring GREETING= hello # not a comment\n"
      "float64 PI=3.14159\nbool ON=True\nuint8 level\n");
  const RosMessageSpec& spec = d.Root();
  ASSERT_EQ(spec.constants.size(), 5U);
  EXPECT_EQ(spec.constants[0].name, "DEBUG");
  EXPECT_EQ(spec.constants[0].value, "1");
  EXPECT_EQ(spec.constants[1].value, "-128");
  EXPECT_EQ(spec.constants[2].value, "hello # not a comment");
  EXPECT_EQ(spec.constants[3].type, RosType::kFloat64);
  ASSERT_EQ(spec.fields.size(), 1U);  // constants take no bytes
  EXPECT_EQ(MinimumSerializedSize(d, d.root), 1U);
}

TEST(RosMessageDefinition, RefusesBadDefinitionsNamingTheLine) {
  const auto error_of = [](const std::string& type, const std::string& text) {
    try {
      ParseRosMessageDefinition(type, text);
    } catch (const RosMessageError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error_of("a/B", "uint8 X=300\n"),
            "MSG: a/B line 1: bad value '300' for constant X of type uint8");
  EXPECT_EQ(error_of("a/B", "uint8 ok\nfloat32[x] bad\n"),
            "MSG: a/B line 2: bad array length 'x'");
  EXPECT_EQ(error_of("a/B", "uint8\n"), "MSG: a/B line 1: 'uint8' has a type but no name");
  EXPECT_EQ(error_of("a/B", "uint8 a\nuint8 a\n"), "MSG: a/B line 2: field a defined twice");
  EXPECT_EQ(error_of("a/B", "C c\n"),
            "MSG: a/B: field c has type a/C, which the definition lacks");
  EXPECT_EQ(error_of("a/B", "C[] c\n===\nMSG: a/C\nB b\n"), "MSG: a/B: the type contains itself");
  EXPECT_EQ(error_of("a/B", "uint8 x\n===\nuint8 y\n"),
            "MSG: a/B line 3: a section after '===' must start with 'MSG: pkg/Type'");
  EXPECT_EQ(error_of("B", "uint8 x\n"), "type: 'B' is not a pkg/Type name");
  EXPECT_EQ(error_of("a/B", "uint8 x extra\n"),
            "MSG: a/B line 1: unexpected 'extra' after field x");
}

TEST(RosMessageDecode, OdometryValues) {
  const RosMessageDefinition d =
      ParseRosMessageDefinition("nav_msgs/Odometry", OdometryDefinition());
  const std::string bytes = testing::OdometryMessage({100, 5}, 1.5, -2.0, 0.5, 0.75, -0.25);
  ASSERT_EQ(bytes.size(), 700U + 4U + 9U);  // two strings: "odom" and "base_link"
  const RosValue v = DecodeRosMessage(d, bytes);
  EXPECT_EQ(v["header"]["seq"].AsUint(), 1U);
  EXPECT_EQ(v["header"]["stamp"].AsTime(), (RosTime{100, 5}));
  EXPECT_EQ(v["header"]["frame_id"].AsString(), "odom");
  EXPECT_EQ(v["child_frame_id"].AsString(), "base_link");
  EXPECT_EQ(v["pose"]["pose"]["position"]["x"].AsDouble(), 1.5);
  EXPECT_EQ(v["pose"]["pose"]["position"]["y"].AsDouble(), -2.0);
  EXPECT_DOUBLE_EQ(v["pose"]["pose"]["orientation"]["w"].AsDouble(), std::cos(0.25));
  const std::vector<double>& covariance = v["pose"]["covariance"].AsDoubles();
  ASSERT_EQ(covariance.size(), 36U);
  EXPECT_EQ(covariance[0], 0.01);
  EXPECT_EQ(v["twist"]["twist"]["linear"]["x"].AsDouble(), 0.75);
  EXPECT_EQ(v["twist"]["twist"]["angular"]["z"].AsDouble(), -0.25);
  EXPECT_THROW(v["nope"], RosMessageError);
  EXPECT_THROW(v["header"]["seq"].AsString(), RosMessageError);
}

TEST(RosMessageDecode, ScalarKindsAndArrays) {
  const RosMessageDefinition d = ParseRosMessageDefinition(
      "t/All",
      "bool b\nint8 i8\nuint8 u8\nint16 i16\nuint16 u16\nint32 i32\nuint32 u32\nint64 i64\n"
      "uint64 u64\nfloat32 f32\nfloat64 f64\nstring s\ntime t\nduration d\nint16[2] pair\n"
      "string[] names\nuint8[] blob\n");
  RosSerializer s;
  s.Put(std::uint8_t{1}).Put(std::int8_t{-5}).Put(std::uint8_t{250}).Put(std::int16_t{-300});
  s.Put(std::uint16_t{60000}).Put(std::int32_t{-70000}).Put(std::uint32_t{4000000000U});
  s.Put(std::int64_t{-5000000000}).Put(std::uint64_t{18000000000000000000ULL});
  s.Put(0.5F)
      .Put(-0.125)
      .PutString("héllo")
      .PutTime({7, 8})
      .Put(std::int32_t{-1})
      .Put(std::int32_t{500});
  s.Put(std::int16_t{3}).Put(std::int16_t{-4});
  s.Put(std::uint32_t{2}).PutString("a").PutString("");
  s.Put(std::uint32_t{3}).Put(std::uint8_t{1}).Put(std::uint8_t{2}).Put(std::uint8_t{255});
  const RosValue v = DecodeRosMessage(d, s.bytes());
  EXPECT_TRUE(v["b"].AsBool());
  EXPECT_EQ(v["i8"].AsInt(), -5);
  EXPECT_EQ(v["u8"].AsUint(), 250U);
  EXPECT_EQ(v["i16"].AsInt(), -300);
  EXPECT_EQ(v["u16"].AsUint(), 60000U);
  EXPECT_EQ(v["i32"].AsInt(), -70000);
  EXPECT_EQ(v["u32"].AsUint(), 4000000000U);
  EXPECT_EQ(v["i64"].AsInt(), -5000000000);
  EXPECT_EQ(v["u64"].AsUint(), 18000000000000000000ULL);
  EXPECT_EQ(v["f32"].AsDouble(), 0.5);
  EXPECT_EQ(v["f64"].AsDouble(), -0.125);
  EXPECT_EQ(v["s"].AsString(), "héllo");
  EXPECT_EQ(v["t"].AsTime(), (RosTime{7, 8}));
  EXPECT_EQ(std::get<RosDuration>(v["d"].data), (RosDuration{-1, 500}));
  EXPECT_EQ(std::get<std::vector<std::int64_t>>(v["pair"].data),
            (std::vector<std::int64_t>{3, -4}));
  ASSERT_EQ(v["names"].AsArray().size(), 2U);
  EXPECT_EQ(v["names"].AsArray()[0].AsString(), "a");
  EXPECT_EQ(std::get<std::vector<std::uint64_t>>(v["blob"].data),
            (std::vector<std::uint64_t>{1, 2, 255}));
}

TEST(RosMessageDecode, ErrorsNameTheFieldPath) {
  const RosMessageDefinition d =
      ParseRosMessageDefinition("tf2_msgs/TFMessage", TfMessageDefinition());
  const std::string good = testing::TfMessage({{{1, 2}, "odom", "base_link", 1, 2, 0.3},
                                               {{1, 2}, "base_link", "laser", 0.1, 0, 0}});
  EXPECT_EQ(DecodeRosMessage(d, good)["transforms"].AsArray().size(), 2U);
  try {
    DecodeRosMessage(d, good.substr(0, good.size() - 4));
    FAIL() << "a cut message was accepted";
  } catch (const RosMessageError& e) {
    EXPECT_EQ(e.field(), "transforms[1].transform.rotation.w");
  }
  try {
    DecodeRosMessage(d, good + "x");
    FAIL() << "trailing bytes were accepted";
  } catch (const RosMessageError& e) {
    EXPECT_EQ(e.problem(), "1 bytes left over after the message's " + std::to_string(good.size()) +
                               " bytes");
  }
  // Every prefix is refused cleanly (never read past the end).
  for (std::size_t n = 0; n < good.size(); ++n) {
    EXPECT_THROW(DecodeRosMessage(d, good.substr(0, n)), RosMessageError) << n;
  }
}

TEST(RosMessageDecode, CountsThatCannotFitAreRefusedBeforeAllocating) {
  const RosMessageDefinition d =
      ParseRosMessageDefinition("t/A", "float64[] values\nstring name\n===\nMSG: t/E\n");
  RosSerializer s;
  s.Put(std::uint32_t{0xffffffff});  // 32 GiB of doubles claimed, 4 bytes there
  s.Put(std::uint32_t{0});
  try {
    DecodeRosMessage(d, s.bytes());
    FAIL();
  } catch (const RosMessageError& e) {
    EXPECT_EQ(e.field(), "values");
  }
  RosSerializer t;
  t.Put(std::uint32_t{0}).Put(std::uint32_t{0xfffffff0});  // a 4 GiB string
  EXPECT_THROW(DecodeRosMessage(d, t.bytes()), RosMessageError);
  // Arrays of an empty type take no bytes: their count has a fixed bound instead.
  const RosMessageDefinition empty = ParseRosMessageDefinition("t/A", "E[] e\n===\nMSG: t/E\n");
  RosSerializer u;
  u.Put(std::uint32_t{kMaxZeroSizeElements + 1});
  EXPECT_THROW(DecodeRosMessage(empty, u.bytes()), RosMessageError);
  RosSerializer w;
  w.Put(std::uint32_t{5});
  EXPECT_EQ(DecodeRosMessage(empty, w.bytes())["e"].AsArray().size(), 5U);
  // Nested, the budget is shared: 2000 x 1000 empty elements would pass each count alone.
  const RosMessageDefinition nested =
      ParseRosMessageDefinition("t/A", "E[2000] e\n===\nMSG: t/E\nF[1000] f\n===\nMSG: t/F\n");
  try {
    DecodeRosMessage(nested, "");
    FAIL();
  } catch (const RosMessageError& e) {
    EXPECT_EQ(e.field(), "e[1046].f");  // 2000 + 1047 x 1000 elements pass 2^20
  }
}

TEST(RosMessageDecode, BoolMustBeZeroOrOne) {
  const RosMessageDefinition d = ParseRosMessageDefinition("t/A", "bool flag\n");
  EXPECT_FALSE(DecodeRosMessage(d, std::string(1, '\0'))["flag"].AsBool());
  EXPECT_THROW(DecodeRosMessage(d, std::string(1, '\x02')), RosMessageError);
}

}  // namespace
}  // namespace lookout::io
