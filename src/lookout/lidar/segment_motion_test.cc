#include "lookout/lidar/segment_motion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "lookout/core/input_error.h"
#include "lookout/lidar/cast_scan_for_tests.h"
#include "lookout/sim/shapes.h"

namespace lookout::lidar {
namespace {

constexpr int kStatic = sim::kStaticOwner;
constexpr double kMinRange = 0.1;
constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

// A wall across the view at x = 30 m, and `extra` in front of it; cast from the origin.
LidarScan CastWithWall(std::vector<sim::Shape> extra) {
  extra.push_back(sim::Shape::Box(Pose2(30.0, 0.0, 0.0), 0.3, 60.0, kStatic));
  return testing::CastScan(extra);
}

// A car 4.5 m x 1.8 m straight ahead, its rear at x_rear_m, facing away.
sim::Shape CarAhead(double x_rear_m) {
  return sim::Shape::Box(Pose2(x_rear_m + 2.25, 0.0, 0.0), 4.5, 1.8, kStatic);
}

// Every return classified `k`.
ScanHitClasses AllReturns(const LidarScan& scan, HitClass k) {
  ScanHitClasses c;
  c.beam.assign(scan.ranges_m.size(), HitClass::kNoReturn);
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    if (!IsReturn(scan, i, kMinRange)) continue;
    c.beam[i] = k;
    ++(k == HitClass::kStatic ? c.static_count
                              : (k == HitClass::kDynamic ? c.dynamic_count : c.unknown_count));
  }
  return c;
}

// The cluster whose first return is nearest `x` along the x axis.
std::size_t ClusterAt(const LidarScan& scan, const std::vector<ScanCluster>& clusters, double x) {
  std::size_t best = clusters.size();
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    const double d = std::abs(ReturnPoint(scan, clusters[c].beams.front()).x() - x);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

// The previous scan's segments, the one at `moving_x` moving by its own evidence (none: NaN).
ScanSegments Previous(const LidarScan& scan, double moving_x, const Pose2& pose = Pose2(),
                      std::span<const std::uint8_t> standing = {}) {
  const std::vector<ScanCluster> clusters = ClusterScan(scan, {}, SegmentationOptions{}, kMinRange);
  std::vector<bool> own(clusters.size(), false);
  if (!std::isnan(moving_x)) own[ClusterAt(scan, clusters, moving_x)] = true;
  const std::vector<int> none(clusters.size(), -1);
  return DescribeSegments(scan, pose, clusters, own, none, standing);
}

// The segment of the previous scan's returns nearer than 20 m (the car's; the wall is at 30 m).
std::size_t CarSegment(const ScanSegments& s) {
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    if (s.points[k].x() < 20.0) return s.segment[k];
  }
  return s.moving.size();
}

// Of the previous scan's returns flagged, those on the car and those elsewhere.
struct Split {
  int car = 0;
  int other = 0;
  int car_returns = 0;
};
Split SplitByCar(const ScanSegments& s, const std::vector<bool>& flags) {
  Split out;
  const std::size_t car = CarSegment(s);
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    const bool on_car = s.segment[k] == car;
    out.car_returns += on_car;
    if (flags[k]) ++(on_car ? out.car : out.other);
  }
  return out;
}

TEST(SegmentMotion, TheReturnsOfACarDrivingAwayAreSeenThrough) {
  // The car's rear at 12 m, then 0.8 m further (10 m/s at 12.5 Hz).
  const LidarScan before = CastWithWall({CarAhead(12.0)});
  const LidarScan after = CastWithWall({CarAhead(12.8)});
  const ScanSegments previous = Previous(before, 12.0);
  const std::vector<bool> vacated =
      VacatedReturns(previous, after, Pose2(), SegmentMotionOptions{}, kMinRange);
  const Split split = SplitByCar(previous, vacated);
  ASSERT_GT(split.car_returns, 20);
  // Every rear return but those at its two edges, where a bracketing beam passes the car.
  EXPECT_GE(split.car, split.car_returns - 2);
  EXPECT_EQ(split.other, 0);
}

TEST(SegmentMotion, AWallSeenAtAGrazingAngleFromAMovingEgoIsNotSeenThrough) {
  // A wall along the road 3 m to the left, 40 m long; the ego moves 0.8 m along it. The ranges
  // along a grazing wall change fast with the bearing: the beam nearest a previous return may
  // land beyond it, the beam on its other side short of it.
  const auto wall_from = [](double ego_x) {
    return testing::CastScan({sim::Shape::Box(Pose2(20.0 - ego_x, 3.15, 0.0), 40.0, 0.3, kStatic)});
  };
  const ScanSegments previous = Previous(wall_from(0.0), kNone);
  ASSERT_GT(previous.points.size(), 100u);
  const std::vector<bool> vacated = VacatedReturns(previous, wall_from(0.8), Pose2(0.8, 0.0, 0.0),
                                                   SegmentMotionOptions{}, kMinRange);
  int seen_through = 0;
  for (bool v : vacated) seen_through += v;
  EXPECT_EQ(seen_through, 0);
}

TEST(SegmentMotion, BeamsWithoutAMeasurementSayNothing) {
  const ScanSegments previous = Previous(CastWithWall({CarAhead(12.0)}), 12.0);
  LidarScan after = CastWithWall({CarAhead(12.8)});
  for (float& r : after.ranges_m) r = std::numeric_limits<float>::quiet_NaN();
  const std::vector<bool> vacated =
      VacatedReturns(previous, after, Pose2(), SegmentMotionOptions{}, kMinRange);
  for (bool v : vacated) EXPECT_FALSE(v);
}

TEST(SegmentMotion, AVacatedSegmentMovesAndOnlyIt) {
  const LidarScan before = CastWithWall({CarAhead(12.0)});
  ScanSegments previous = Previous(before, kNone);
  for (bool m : previous.moving) ASSERT_FALSE(m);
  const std::vector<bool> vacated = VacatedReturns(previous, CastWithWall({CarAhead(12.8)}),
                                                   Pose2(), SegmentMotionOptions{}, kMinRange);
  previous.carried_scans.assign(previous.moving.size(), 2);
  MarkVacatedSegments(vacated, SegmentMotionOptions{}, previous);
  const std::size_t car = CarSegment(previous);
  for (std::size_t s = 0; s < previous.moving.size(); ++s) {
    EXPECT_EQ(previous.moving[s], s == car);
    EXPECT_EQ(previous.carried_scans[s], s == car ? 0 : 2);
  }
}

TEST(SegmentMotion, AMovingSegmentCarriesToWhereItWent) {
  // The car's returns land in space its body hid: unknown to the map. The wall is static.
  const ScanSegments previous = Previous(CastWithWall({CarAhead(12.0)}), 12.0);
  const LidarScan scan = CastWithWall({CarAhead(12.8)});
  const std::vector<ScanCluster> clusters = ClusterScan(scan, {}, SegmentationOptions{}, kMinRange);
  ScanHitClasses classes = AllReturns(scan, HitClass::kStatic);
  const std::size_t car = ClusterAt(scan, clusters, 12.8);
  for (std::size_t i : clusters[car].beams) {
    classes.beam[i] = HitClass::kUnknown;
    --classes.static_count;
    ++classes.unknown_count;
  }
  const std::int64_t total = classes.static_count + classes.unknown_count;
  const std::vector<int> carried =
      CarrySegmentMotion(previous, scan, Pose2(), clusters, SegmentMotionOptions{}, classes);
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    EXPECT_EQ(carried[c], c == car ? 1 : -1);
    const HitClass expected = c == car ? HitClass::kDynamic : HitClass::kStatic;
    for (std::size_t i : clusters[c].beams) EXPECT_EQ(classes.beam[i], expected);
  }
  EXPECT_EQ(classes.unknown_count, 0);
  EXPECT_EQ(classes.dynamic_count, static_cast<std::int64_t>(clusters[car].beams.size()));
  EXPECT_EQ(classes.static_count + classes.dynamic_count, total);
}

TEST(SegmentMotion, OnlyTheMutuallyNearestSegmentIsCarriedOnto) {
  // A walker (0.25 m radius) at 10 m steps 0.1 m to the left; a post 0.9 m to the left of where
  // it was is within the step too, but further than the walker's new place.
  const auto walker = [](double y) { return sim::Shape::Circle({10.0, y}, 0.25, kStatic); };
  const sim::Shape post = sim::Shape::Circle({10.0, 0.9 + 0.25 + 0.1}, 0.1, kStatic);
  const ScanSegments previous = Previous(CastWithWall({walker(0.0), post}), 9.75);
  const LidarScan scan = CastWithWall({walker(0.1), post});
  const std::vector<ScanCluster> clusters = ClusterScan(scan, {}, SegmentationOptions{}, kMinRange);
  ScanHitClasses classes = AllReturns(scan, HitClass::kUnknown);
  const std::vector<int> carried =
      CarrySegmentMotion(previous, scan, Pose2(), clusters, SegmentMotionOptions{}, classes);
  int carried_clusters = 0;
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    if (carried[c] < 0) continue;
    ++carried_clusters;
    // The walker's returns: left of the post's.
    EXPECT_LT(ReturnPoint(scan, clusters[c].beams.back()).y(), 0.5);
  }
  EXPECT_EQ(carried_clusters, 1);
}

TEST(SegmentMotion, NoCarryOntoMostlyStaticSegmentsNorAfterTooManyScans) {
  const ScanSegments moving = Previous(CastWithWall({CarAhead(12.0)}), 12.0);
  const LidarScan scan = CastWithWall({CarAhead(12.8)});
  const std::vector<ScanCluster> clusters = ClusterScan(scan, {}, SegmentationOptions{}, kMinRange);
  const SegmentMotionOptions options;
  {
    ScanHitClasses classes = AllReturns(scan, HitClass::kStatic);  // the car's trace: mapped
    const std::vector<int> carried =
        CarrySegmentMotion(moving, scan, Pose2(), clusters, options, classes);
    for (int c : carried) EXPECT_EQ(c, -1);
    EXPECT_EQ(classes.dynamic_count, 0);
  }
  {
    ScanSegments stale = moving;
    for (int& n : stale.carried_scans) n = options.max_carried_scans;
    ScanHitClasses classes = AllReturns(scan, HitClass::kUnknown);
    const std::vector<int> carried =
        CarrySegmentMotion(stale, scan, Pose2(), clusters, options, classes);
    for (int c : carried) EXPECT_EQ(c, -1);
  }
}

TEST(SegmentMotion, OwnEvidenceNeedsEnoughDynamicReturns) {
  const LidarScan scan = CastWithWall({CarAhead(12.0)});
  const std::vector<ScanCluster> clusters = ClusterScan(scan, {}, SegmentationOptions{}, kMinRange);
  ScanHitClasses classes = AllReturns(scan, HitClass::kStatic);
  const std::size_t car = ClusterAt(scan, clusters, 12.0);
  const std::size_t wall = car == 0 ? 1 : 0;
  classes.beam[clusters[car].beams[3]] = HitClass::kDynamic;
  classes.beam[clusters[wall].beams[3]] = HitClass::kDynamic;
  classes.beam[clusters[wall].beams[7]] = HitClass::kDynamic;
  const std::vector<bool> own = OwnMotionEvidence(clusters, classes.beam, SegmentMotionOptions{});
  EXPECT_FALSE(own[car]);  // one dynamic return: a stray
  EXPECT_TRUE(own[wall]);
}

TEST(SegmentMotion, OptionsAreValidated) {
  SegmentMotionOptions o;
  EXPECT_NO_THROW(o.Validate());
  o.max_step_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(o.Validate(), InputError);
  o = {};
  o.max_static_share = 1.5;
  EXPECT_THROW(o.Validate(), InputError);
  o = {};
  o.min_vacated_returns = 0;
  EXPECT_THROW(o.Validate(), InputError);
  o = {};
  o.max_carried_scans = -1;
  EXPECT_THROW(o.Validate(), InputError);
}

// The static returns a moving body leaves on its own trace (a car's side sliding along itself
// lands on cells the map holds) are flagged; those of something standing beside it are not.
TEST(SegmentMotion, StaticReturnsOnAMoversTraceAreFlagged) {
  // The previous scan: the car with its rear at 10 m, moving; the wall standing.
  const LidarScan before = CastWithWall({CarAhead(10.0)});
  const ScanSegments previous = Previous(before, 10.0);
  // This scan: the car 0.2 m further on (its returns within the trace radius of its previous
  // ones), every return called static by the map.
  const LidarScan after = CastWithWall({CarAhead(10.2)});
  const ScanHitClasses classes = AllReturns(after, HitClass::kStatic);
  const std::vector<std::uint8_t> on_trace =
      StaticOnMovingTrace(previous, after, Pose2(), classes.beam, SegmentMotionOptions{});
  int car = 0, wall = 0, car_returns = 0;
  for (std::size_t i = 0; i < after.ranges_m.size(); ++i) {
    if (!IsReturn(after, i, kMinRange)) continue;
    const bool on_car = ReturnPoint(after, i).x() < 20.0;
    car_returns += on_car;
    if (on_trace[i] != 0) ++(on_car ? car : wall);
  }
  EXPECT_GT(car_returns, 5);
  EXPECT_EQ(car, car_returns);
  EXPECT_EQ(wall, 0);
  // Returns the map held standing in the scan before (a pole that joined a walker's segment
  // within the class break) make no trace, though their segment moved.
  const std::vector<std::uint8_t> standing(before.ranges_m.size(), 1);
  const std::vector<std::uint8_t> held =
      StaticOnMovingTrace(Previous(before, 10.0, Pose2(), standing), after, Pose2(), classes.beam,
                          SegmentMotionOptions{});
  EXPECT_EQ(std::count(held.begin(), held.end(), std::uint8_t{1}), 0);
  // Nothing moved before: nothing is a trace.
  const std::vector<std::uint8_t> none = StaticOnMovingTrace(
      Previous(before, kNone), after, Pose2(), classes.beam, SegmentMotionOptions{});
  EXPECT_EQ(std::count(none.begin(), none.end(), std::uint8_t{1}), 0);
}

}  // namespace
}  // namespace lookout::lidar
