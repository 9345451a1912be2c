#include "lookout/tracking/scan_visibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "lookout/core/input_error.h"

namespace lookout::tracking {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A 180-degree fan of 0.25-degree beams, 100 m reach, every beam returning at `range_m`.
LidarScan Fan(double range_m) {
  LidarScan scan;
  scan.angle_min_rad = -kPi / 2.0;
  scan.angle_increment_rad = 0.25 * kPi / 180.0;
  scan.max_range_m = 100.0;
  scan.ranges_m.assign(721, static_cast<float>(range_m));
  return scan;
}

// The beam nearest `bearing_rad`.
std::size_t Beam(const LidarScan& scan, double bearing_rad) {
  return static_cast<std::size_t>(
      std::lround((bearing_rad - scan.angle_min_rad) / scan.angle_increment_rad));
}

// Beams within `half_width_m` of the line of sight to a point `range_m` ahead at `bearing_rad`
// return at `at_m`.
void Put(LidarScan& scan, double bearing_rad, double range_m, double half_width_m, double at_m) {
  const double half = std::asin(half_width_m / range_m);
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    if (std::abs(scan.BeamAngle(i) - bearing_rad) <= half) {
      scan.ranges_m[i] = static_cast<float>(at_m);
    }
  }
}

TEST(ScanVisibility, OpenSpaceAndAnObjectsOwnReturnsSeeIt) {
  // No return anywhere: open space a walker 20 m ahead would have stopped.
  const ScanVisibility open(Fan(kInf), Pose2{});
  const ViewFraction v = open.View({20.0, 0.0}, ObjectClass::kPedestrian);
  EXPECT_DOUBLE_EQ(v.in_view, 1.0);
  EXPECT_DOUBLE_EQ(v.seen, 1.0);
  // The walker's own returns, 0.3 m before its centre; a wall behind it.
  LidarScan scan = Fan(40.0);
  Put(scan, 0.0, 20.0, 0.3, 19.7);
  EXPECT_DOUBLE_EQ(ScanVisibility(scan, Pose2{}).View({20.0, 0.0}, ObjectClass::kPedestrian).seen,
                   1.0);
  // A car end-on: its nose 2.25 m before its centre does not hide it.
  LidarScan car = Fan(40.0);
  Put(car, 0.0, 20.0, 0.9, 17.75);
  EXPECT_DOUBLE_EQ(ScanVisibility(car, Pose2{}).View({20.0, 0.0}, ObjectClass::kCar).seen, 1.0);
}

TEST(ScanVisibility, ANearerObjectHidesWhatIsBehindIt) {
  // A walker 8 m ahead hides a walker 18 m ahead on the same bearing, wholly.
  LidarScan scan = Fan(kInf);
  Put(scan, 0.0, 8.0, 0.3, 7.7);
  const ScanVisibility view(scan, Pose2{});
  const ViewFraction behind = view.View({18.0, 0.0}, ObjectClass::kPedestrian);
  EXPECT_DOUBLE_EQ(behind.in_view, 1.0);
  EXPECT_DOUBLE_EQ(behind.seen, 0.0);
  // Half of it: the occluder's edge on its line of sight.
  LidarScan half = Fan(kInf);
  for (std::size_t i = Beam(half, 0.0) + 1; i < half.ranges_m.size(); ++i) {
    half.ranges_m[i] = 7.7f;
  }
  const ViewFraction v = ScanVisibility(half, Pose2{}).View({18.0, 0.0}, ObjectClass::kPedestrian);
  EXPECT_NEAR(v.seen, 0.5, 0.1);
  // A building's wall 5 m ahead hides a car 15 m ahead.
  EXPECT_DOUBLE_EQ(ScanVisibility(Fan(5.0), Pose2{}).View({15.0, 0.0}, ObjectClass::kCar).seen,
                   0.0);
  // A neighbour beside it is no occluder: a walker 1.5 m to the side of a car's line of sight.
  LidarScan beside = Fan(kInf);
  Put(beside, std::atan2(1.5, 10.0), 10.1, 0.3, 9.8);
  EXPECT_DOUBLE_EQ(ScanVisibility(beside, Pose2{}).View({20.0, 0.0}, ObjectClass::kCar).seen, 1.0);
}

TEST(ScanVisibility, OutsideTheFanOrBeyondReachIsOutOfView) {
  const ScanVisibility view(Fan(kInf), Pose2{});
  const ViewFraction behind = view.View({-10.0, 0.0}, ObjectClass::kPedestrian);
  EXPECT_DOUBLE_EQ(behind.in_view, 0.0);
  EXPECT_DOUBLE_EQ(behind.seen, 0.0);
  EXPECT_DOUBLE_EQ(view.View({120.0, 0.0}, ObjectClass::kPedestrian).in_view, 0.0);
  // On the fan's edge, half in.
  EXPECT_NEAR(view.View({0.0, 10.0}, ObjectClass::kCar).in_view, 0.5, 0.05);
}

// The sensor's pose in the tracker's frame: a lidar at (100, 50) looking north sees a point
// 20 m north of it, and a wall 5 m north of it hides that point.
TEST(ScanVisibility, TheSensorsPoseMapsTheTrackersFrame) {
  const Pose2 pose(100.0, 50.0, kPi / 2.0);
  EXPECT_DOUBLE_EQ(ScanVisibility(Fan(kInf), pose).View({100.0, 70.0}, ObjectClass::kCyclist).seen,
                   1.0);
  EXPECT_DOUBLE_EQ(ScanVisibility(Fan(5.0), pose).View({100.0, 70.0}, ObjectClass::kCyclist).seen,
                   0.0);
  EXPECT_NEAR(ScanVisibility(Fan(kInf), pose).View({80.0, 50.0}, ObjectClass::kCyclist).in_view,
              0.5, 0.1);  // on the fan's left edge
}

// A detection near the position overrules the beams (the camera saw round an edge); a NaN beam
// says nothing; a scan without beams sees nothing.
TEST(ScanVisibility, DetectionsOverruleTheBeamsAndBrokenScansSeeNothing) {
  const LidarScan wall = Fan(5.0);
  EXPECT_DOUBLE_EQ(ScanVisibility(wall, Pose2{}, {}, {{20.8, 0.0}})
                       .View({20.0, 0.0}, ObjectClass::kPedestrian)
                       .seen,
                   1.0);
  EXPECT_DOUBLE_EQ(ScanVisibility(wall, Pose2{}, {}, {{22.0, 0.0}})
                       .View({20.0, 0.0}, ObjectClass::kPedestrian)
                       .seen,
                   0.0);
  LidarScan nan = Fan(std::numeric_limits<double>::quiet_NaN());
  EXPECT_DOUBLE_EQ(ScanVisibility(nan, Pose2{}).View({20.0, 0.0}, ObjectClass::kPedestrian).seen,
                   0.0);
  LidarScan empty = Fan(kInf);
  empty.ranges_m.clear();
  EXPECT_DOUBLE_EQ(ScanVisibility(empty, Pose2{}).View({20.0, 0.0}, ObjectClass::kCar).in_view,
                   0.0);
  EXPECT_DOUBLE_EQ(ScanVisibility(Fan(kInf), Pose2{})
                       .View({std::numeric_limits<double>::quiet_NaN(), 0.0}, ObjectClass::kCar)
                       .seen,
                   0.0);
}

TEST(ScanVisibility, ValidateNamesTheField) {
  const auto message = [](const ScanVisibilityOptions& o) {
    try {
      o.Validate("test");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(ScanVisibilityOptions{}), "no error");
  ScanVisibilityOptions o;
  o.footprints.car_length_m = -1.0;
  EXPECT_NE(message(o).find("car_length_m"), std::string::npos) << message(o);
  o = ScanVisibilityOptions{};
  o.depth_margin_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(o).find("depth_margin_m"), std::string::npos) << message(o);
  o = ScanVisibilityOptions{};
  o.detection_margin_m = -0.5;
  EXPECT_NE(message(o).find("detection_margin_m"), std::string::npos) << message(o);
}

}  // namespace
}  // namespace lookout::tracking
