#include "lookout/lidar/dynamic_segments.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "lookout/core/input_error.h"
#include "lookout/lidar/cast_scan_for_tests.h"
#include "lookout/sim/shapes.h"

namespace lookout::lidar {
namespace {

// A car 10 m ahead (its rear faces the lidar) in front of a long wall at x = 29.85 m, cast
// exactly over 160 degrees at 0.25 degrees from the origin (testing::CastScan).
LidarScan CarBeforeWall() {
  const int s = sim::kStaticOwner;
  const std::vector<sim::Shape> world = {
      sim::Shape::Box(Pose2(10.0, 3.0, 0.0), 4.5, 1.8, s),
      sim::Shape::Box(Pose2(30.0, -5.0, 0.0), 0.3, 40.0, s),
  };
  return testing::CastScan(world);
}

struct Scene {
  LidarScan scan = CarBeforeWall();
  std::vector<ScanCluster> clusters;
  const ScanCluster* car = nullptr;
  const ScanCluster* wall = nullptr;
  ScanHitClasses classes;

  Scene() {
    clusters = ClusterScan(scan, {}, SegmentationOptions{}, 0.1);
    for (const ScanCluster& c : clusters) {
      const double x = ReturnPoint(scan, c.beams.front()).x();
      if (x < 15.0 && !car) car = &c;
      if (x > 29.0 && (!wall || c.beams.size() > wall->beams.size())) wall = &c;
    }
    classes.beam.assign(scan.ranges_m.size(), HitClass::kNoReturn);
    for (const ScanCluster& c : clusters) {
      for (std::size_t i : c.beams) classes.beam[i] = HitClass::kStatic;
      classes.static_count += static_cast<std::int64_t>(c.beams.size());
    }
  }
  // Marks the first k returns of `c` dynamic.
  void MarkDynamic(const ScanCluster& c, std::size_t k) {
    for (std::size_t j = 0; j < k; ++j) {
      classes.beam[c.beams[j]] = HitClass::kDynamic;
      --classes.static_count;
      ++classes.dynamic_count;
    }
  }
  int DynamicIn(const ScanCluster& c) const {
    int n = 0;
    for (std::size_t i : c.beams) n += classes.beam[i] == HitClass::kDynamic ? 1 : 0;
    return n;
  }
};

TEST(DynamicSegments, AMovingCarsReturnsAllBecomeDynamic) {
  Scene s;
  ASSERT_NE(s.car, nullptr);
  ASSERT_NE(s.wall, nullptr);
  const std::size_t n = s.car->beams.size();
  ASSERT_GT(n, 20u);
  s.MarkDynamic(*s.car, n / 2);  // half of it in free space, half beside its mapped cells
  s.classes.beam[s.car->beams.back()] = HitClass::kUnknown;
  --s.classes.static_count;
  ++s.classes.unknown_count;
  const std::int64_t total = s.classes.static_count + s.classes.dynamic_count +
                             s.classes.unknown_count;
  const std::int64_t changed = PropagateDynamicSegments(s.scan, s.clusters, {}, s.classes);
  EXPECT_EQ(changed, static_cast<std::int64_t>(n - n / 2));
  EXPECT_EQ(s.DynamicIn(*s.car), static_cast<int>(n));
  EXPECT_EQ(s.DynamicIn(*s.wall), 0);
  EXPECT_EQ(s.classes.unknown_count, 0);
  EXPECT_EQ(s.classes.static_count + s.classes.dynamic_count + s.classes.unknown_count, total);
}

TEST(DynamicSegments, ALoneOrRareDynamicReturnChangesNothing) {
  Scene s;
  ASSERT_NE(s.car, nullptr);
  s.MarkDynamic(*s.car, 1);  // under min_dynamic_returns
  EXPECT_EQ(PropagateDynamicSegments(s.scan, s.clusters, {}, s.classes), 0);
  Scene w;
  ASSERT_NE(w.wall, nullptr);
  const std::size_t n = w.wall->beams.size();
  w.MarkDynamic(*w.wall, 3);  // a few false ones on a long wall: under min_dynamic_share
  ASSERT_LT(3.0, 0.3 * static_cast<double>(n));
  EXPECT_EQ(PropagateDynamicSegments(w.scan, w.clusters, {}, w.classes), 0);
  EXPECT_EQ(w.DynamicIn(*w.wall), 3);
}

TEST(DynamicSegments, ASegmentLongerThanTheChordIsNotPropagated) {
  Scene s;
  ASSERT_NE(s.wall, nullptr);
  const std::size_t n = s.wall->beams.size();
  s.MarkDynamic(*s.wall, n / 2);
  ASSERT_GT((ReturnPoint(s.scan, s.wall->beams.back()) -
             ReturnPoint(s.scan, s.wall->beams.front())).norm(), 6.0);
  EXPECT_EQ(PropagateDynamicSegments(s.scan, s.clusters, {}, s.classes), 0);
  DynamicSegmentOptions longer;
  longer.max_chord_m = 100.0;
  EXPECT_EQ(PropagateDynamicSegments(s.scan, s.clusters, longer, s.classes),
            static_cast<std::int64_t>(n - n / 2));
}

TEST(DynamicSegments, DisabledChangesNothing) {
  Scene s;
  ASSERT_NE(s.car, nullptr);
  s.MarkDynamic(*s.car, s.car->beams.size() / 2);
  DynamicSegmentOptions off;
  off.enabled = false;
  EXPECT_EQ(PropagateDynamicSegments(s.scan, s.clusters, off, s.classes), 0);
}

TEST(DynamicSegments, OptionsNameTheBadField) {
  auto field_of = [](const DynamicSegmentOptions& o) {
    try {
      o.Validate();
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string();
  };
  DynamicSegmentOptions o;
  EXPECT_EQ(field_of(o), "");
  o.min_dynamic_returns = 0;
  EXPECT_EQ(field_of(o), "min_dynamic_returns");
  o = {};
  o.min_dynamic_share = 1.5;
  EXPECT_EQ(field_of(o), "min_dynamic_share");
  o = {};
  o.max_chord_m = std::nan("");
  EXPECT_EQ(field_of(o), "max_chord_m");
}

}  // namespace
}  // namespace lookout::lidar
