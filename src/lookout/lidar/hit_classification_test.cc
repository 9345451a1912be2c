#include "lookout/lidar/hit_classification.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "lookout/core/input_error.h"

namespace lookout::lidar {
namespace {

MapOptions HitTestMap() {
  MapOptions o;
  o.cell_size_m = 0.1;
  o.window_cells = 256;  // 25.6 m, centred on the origin
  o.field_max_distance_m = 0.5;
  return o;
}

// An analytic map: a wall along x = 8 m for |y| <= 4 m, seen five times from the origin by
// beams every 0.5 degree over +-25 degrees. Before the wall the map saw free space, at the
// wall occupied, behind it and outside the fan nothing.
LocalMap WallMap() {
  LocalMap map(HitTestMap());
  std::vector<Eigen::Vector2d> hits;
  for (double a = -25.0; a <= 25.0; a += 0.5) {
    const double rad = a * kPi / 180.0;
    hits.emplace_back(8.0, 8.0 * std::tan(rad));
  }
  for (int i = 0; i < 5; ++i) map.InsertScan(Eigen::Vector2d::Zero(), hits, {});
  return map;
}

// A scan from the origin (mount and vehicle at the origin) with one beam per (range, angle).
LidarScan ScanOf(const std::vector<std::pair<float, double>>& beams) {
  // Beams at arbitrary angles: one scan per beam would do, but a scan has one increment. So
  // the angles here are multiples of 0.5 degrees from -30 degrees, and unlisted beams are NaN.
  LidarScan scan;
  scan.angle_min_rad = -30.0 * kPi / 180.0;
  scan.angle_increment_rad = 0.5 * kPi / 180.0;
  scan.max_range_m = 50.0;
  scan.ranges_m.assign(121, std::numeric_limits<float>::quiet_NaN());
  for (const auto& [range, degrees] : beams) {
    const auto i = static_cast<std::size_t>(std::lround((degrees + 30.0) / 0.5));
    scan.ranges_m[i] = range;
  }
  return scan;
}

std::size_t Beam(double degrees) {
  return static_cast<std::size_t>(std::lround((degrees + 30.0) / 0.5));
}

TEST(HitClassification, FreeSpaceIsDynamicOccupiedIsStaticTheRestUnknown) {
  const LocalMap map = WallMap();
  const LidarScan scan = ScanOf({
      {8.0f / static_cast<float>(std::cos(0.0)), 0.0},  // on the wall: static
      {5.0f, 10.0},                                      // in the free space before it
      {12.0f, -10.0},                                    // behind the wall: never seen
      {5.0f, -28.0},                                     // outside the mapped fan
      {7.96f, 5.0},                                      // a cell before the wall: static
  });
  const ScanHitClasses c = ClassifyHits(map, scan, Pose2(), HitClassificationOptions{});
  EXPECT_EQ(c.beam[Beam(0.0)], HitClass::kStatic);
  EXPECT_EQ(c.beam[Beam(10.0)], HitClass::kDynamic);
  EXPECT_EQ(c.beam[Beam(-10.0)], HitClass::kUnknown);
  EXPECT_EQ(c.beam[Beam(-28.0)], HitClass::kUnknown);
  EXPECT_EQ(c.beam[Beam(5.0)], HitClass::kStatic);
  EXPECT_EQ(c.static_count, 2);
  EXPECT_EQ(c.dynamic_count, 1);
  EXPECT_EQ(c.unknown_count, 2);
  EXPECT_EQ(c.no_return_count, 121 - 5);
}

TEST(HitClassification, ThresholdsAreOptions) {
  const LocalMap map = WallMap();
  // Three cells before the wall: dynamic with the default 0.15 m tolerance, static with 0.35 m.
  const LidarScan scan = ScanOf({{7.72f, 0.0}});
  HitClassificationOptions o;
  EXPECT_EQ(ClassifyHits(map, scan, Pose2(), o).beam[Beam(0.0)], HitClass::kDynamic);
  o.static_tolerance_m = 0.35;
  EXPECT_EQ(ClassifyHits(map, scan, Pose2(), o).beam[Beam(0.0)], HitClass::kStatic);
  // Five clear views make -1.5 (the miss is -0.3); a threshold below that is not reached.
  o.static_tolerance_m = 0.15;
  o.free_log_odds = -1.6f;
  EXPECT_EQ(ClassifyHits(map, scan, Pose2(), o).beam[Beam(0.0)], HitClass::kUnknown);
}

// A cell hit in one scan (log-odds 0.9) is occupied for the map, but no evidence that what is
// there stays: with static_min_log_odds 1.5 a return beside it is unknown until a second scan
// hits it (1.8). The default is the paper's rule: any occupied cell.
TEST(HitClassification, StaticCanNeedACellSeenOccupiedInTwoScans) {
  LocalMap map(HitTestMap());
  const std::vector<Eigen::Vector2d> post = {{6.0, 0.0}};
  const LidarScan scan = ScanOf({{5.95f, 0.0}});  // half a cell before the post's cell
  map.InsertScan(Eigen::Vector2d::Zero(), post, {});
  HitClassificationOptions o;
  o.static_min_log_odds = 1.5f;
  EXPECT_EQ(ClassifyHits(map, scan, Pose2(), o).beam[Beam(0.0)], HitClass::kUnknown);
  const HitClassificationOptions paper;
  EXPECT_EQ(ClassifyHits(map, scan, Pose2(), paper).beam[Beam(0.0)], HitClass::kStatic);
  map.InsertScan(Eigen::Vector2d::Zero(), post, {});
  EXPECT_EQ(ClassifyHits(map, scan, Pose2(), o).beam[Beam(0.0)], HitClass::kStatic);
}

TEST(HitClassification, UsesTheVehiclePoseAndTheMount) {
  const LocalMap map = WallMap();
  // The vehicle 3 m ahead, its lidar mounted 1 m further: a 4 m return reaches the wall.
  LidarScan scan = ScanOf({{4.0f, 0.0}, {2.0f, 0.0 + 0.5}});
  scan.mount = Pose2(1.0, 0.0, 0.0);
  const ScanHitClasses c = ClassifyHits(map, scan, Pose2(3.0, 0.0, 0.0), {});
  EXPECT_EQ(c.beam[Beam(0.0)], HitClass::kStatic);
  EXPECT_EQ(c.beam[Beam(0.5)], HitClass::kDynamic);
}

TEST(HitClassification, BeamsThatAreNotReturnsAreSkippedAndCounted) {
  const LocalMap map = WallMap();
  const float inf = std::numeric_limits<float>::infinity();
  LidarScan scan = ScanOf({{8.0f, 0.0}});
  scan.ranges_m[Beam(1.0)] = inf;
  scan.ranges_m[Beam(2.0)] = -3.0f;
  scan.ranges_m[Beam(3.0)] = 0.05f;   // under min_range_m
  scan.ranges_m[Beam(4.0)] = 50.0f;   // at the maximum: no return
  scan.ranges_m[Beam(5.0)] = -inf;
  const ScanHitClasses c = ClassifyHits(map, scan, Pose2(), {});
  EXPECT_EQ(c.static_count, 1);
  EXPECT_EQ(c.no_return_count, 120);
  for (double d : {1.0, 2.0, 3.0, 4.0, 5.0}) EXPECT_EQ(c.beam[Beam(d)], HitClass::kNoReturn) << d;
}

// The far map: 0.2 m cells, a wall at x = 100 m seen five times. Returns beyond 80 m that the
// fine map left unknown are classified against it; nearer ones, and returns the fine map
// already classified, keep their class; the counts follow.
TEST(HitClassification, FarReturnsAreClassifiedAgainstTheFarMap) {
  MapOptions o;
  o.cell_size_m = 0.2;
  o.window_cells = 2048;
  o.max_insert_range_m = 150.0;
  LocalMap far(o);
  std::vector<Eigen::Vector2d> wall;
  for (double a = -5.0; a <= 5.0; a += 0.1)
    wall.emplace_back(100.0, 100.0 * std::tan(a * kPi / 180.0));
  for (int i = 0; i < 5; ++i) far.InsertScan(Eigen::Vector2d::Zero(), wall, {});
  LidarScan scan = ScanOf({{100.0f, 0.0},    // on the wall: static
                           {90.0f, 1.0},     // before it, seen free: dynamic
                           {120.0f, 2.0},    // behind it: unknown
                           {50.0f, 3.0},     // within the fine map's reach: left alone
                           {95.0f, -1.0}});  // already static by the fine map
  scan.max_range_m = 150.0;
  ScanHitClasses c;
  c.beam.assign(scan.ranges_m.size(), HitClass::kNoReturn);
  for (double d : {0.0, 1.0, 2.0, 3.0}) c.beam[Beam(d)] = HitClass::kUnknown;
  c.beam[Beam(-1.0)] = HitClass::kStatic;
  c.unknown_count = 4;
  c.static_count = 1;
  ClassifyFarHits(far, scan, Pose2(), 80.0, 0.3, HitClassificationOptions{}, c);
  EXPECT_EQ(c.beam[Beam(0.0)], HitClass::kStatic);
  EXPECT_EQ(c.beam[Beam(1.0)], HitClass::kDynamic);
  EXPECT_EQ(c.beam[Beam(2.0)], HitClass::kUnknown);
  EXPECT_EQ(c.beam[Beam(3.0)], HitClass::kUnknown);
  EXPECT_EQ(c.beam[Beam(-1.0)], HitClass::kStatic);
  EXPECT_EQ(c.static_count, 2);
  EXPECT_EQ(c.dynamic_count, 1);
  EXPECT_EQ(c.unknown_count, 2);
}

TEST(HitClassification, OptionsNameTheBadField) {
  HitClassificationOptions o;
  o.free_log_odds = 0.2f;
  try {
    o.Validate();
    FAIL() << "accepted a positive free threshold";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "free_log_odds");
  }
  o = {};
  o.static_tolerance_m = std::nan("");
  EXPECT_THROW(o.Validate(), InputError);
}

}  // namespace
}  // namespace lookout::lidar
