#include "lookout/lidar/scan_matcher.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lookout/core/random.h"
#include "lookout/lidar/lidar_test_support.h"

namespace lookout::lidar {
namespace {

// A map of the hall built from scans at known poses.
LocalMap MappedHall(const std::vector<sim::Shape>& world, const MatcherOptions& matcher) {
  LocalMap map;
  for (const Pose2& pose : {Pose2(0.0, 0.0, 0.0), Pose2(-10.0, -1.0, 2.0), Pose2(10.0, 1.0, -1.0),
                            Pose2(0.0, -6.0, 1.5)}) {
    const LidarScan scan = testing::CastScan(world, pose);
    const ScanPoints points = ExtractScanPoints(scan, matcher);
    std::vector<Eigen::Vector2d> hits;
    for (const Eigen::Vector2d& p : points.all) hits.push_back(pose * p);
    map.InsertScan(pose * scan.mount.translation, hits, {});
  }
  return map;
}

TEST(ScanMatcher, ExtractSkipsInvalidBeamsAndSubsamples) {
  LidarScan scan;
  scan.angle_min_rad = 0.0;
  scan.angle_increment_rad = 0.001;
  scan.max_range_m = 10.0;
  scan.ranges_m = {5.0f, std::nanf(""), INFINITY, 10.0f, 0.01f, 5.0f, 5.0f, 6.0f};
  MatcherOptions o;
  o.point_spacing_m = 0.5;
  const ScanPoints p = ExtractScanPoints(scan, o);
  EXPECT_EQ(p.all.size(), 4u);    // NaN, inf, max range and too short are left out
  EXPECT_EQ(p.match.size(), 2u);  // the 5 m returns are 5 mm apart; 6 m is 1 m further
}

TEST(ScanMatcher, LikelihoodIsHighestAtTheTruePose) {
  const std::vector<sim::Shape> world = testing::Hall();
  const MatcherOptions o;
  const LocalMap map = MappedHall(world, o);
  const Pose2 truth(1.0, 2.0, 0.4);
  const ScanPoints points = ExtractScanPoints(testing::CastScan(world, truth), o);
  const double at_truth = ScanLogLikelihood(map, truth, points.match, o);
  for (const Pose2& off : {Pose2(0.2, 0.0, 0.0), Pose2(0.0, -0.2, 0.0), Pose2(0.0, 0.0, 0.05)}) {
    EXPECT_LT(ScanLogLikelihood(map, truth * off, points.match, o), at_truth);
  }
  EXPECT_NEAR(PointLogLikelihood(0.0, o), std::log(1.0), 1e-12);
  EXPECT_NEAR(PointLogLikelihood(100.0, o), std::log(o.z_rand), 1e-12);
}

TEST(ScanMatcher, RecoversAKnownOffset) {
  const std::vector<sim::Shape> world = testing::Hall();
  const MatcherOptions o;
  const LocalMap map = MappedHall(world, o);
  const std::uint64_t seed = 31;
  Rng rng(seed);
  for (int trial = 0; trial < 10; ++trial) {
    const Pose2 truth{rng.Uniform(-12.0, 12.0), rng.Uniform(-4.0, 4.0), rng.Uniform(-kPi, kPi)};
    const ScanPoints points = ExtractScanPoints(testing::CastScan(world, truth), o);
    // An odometry error of up to 0.3 m and 0.15 rad, inside the window of a 1 m, 0.3 rad step.
    const Pose2 guess = truth * Pose2{rng.Uniform(-0.3, 0.3), rng.Uniform(-0.3, 0.3),
                                      rng.Uniform(-0.15, 0.15)};
    const SearchWindow window = SearchWindowFor(Pose2(1.0, 0.0, 0.3), o);
    ASSERT_GE(window.xy_m, 0.3);
    ASSERT_GE(window.yaw_rad, 0.15);
    // The search and the fit on the scan alone find the truth to within the map's cells ...
    const Pose2 searched = CorrelativeSearch(map, points.match, guess, window, o);
    const Refinement r = RefineGaussNewton(map, points.match, searched, 10, o);
    EXPECT_LT((r.pose.translation - truth.translation).norm(), 0.03)
        << "seed " << seed << " trial " << trial;
    EXPECT_LT(std::abs(WrapAngle(r.pose.yaw - truth.yaw)), 0.005)
        << "seed " << seed << " trial " << trial;
    EXPECT_GT(r.covariance(0, 0), 0.0);
    // ... and with the odometry prior (MatchScan) the pull towards the guess stays small.
    const Refinement with_prior = MatchScan(map, points.match, guess, window, o);
    EXPECT_LT((with_prior.pose.translation - truth.translation).norm(), 0.06)
        << "seed " << seed << " trial " << trial;
  }
}

TEST(ScanMatcher, HeadingWindowExtendsWhenTheBestIsOnItsEdge) {
  const std::vector<sim::Shape> world = testing::Hall();
  MatcherOptions off;
  MatcherOptions on;
  on.search_yaw_edge_extend = 2.0;
  const LocalMap map = MappedHall(world, off);
  const SearchWindow window{0.3, 0.15};
  const std::uint64_t seed = 47;
  Rng rng(seed);
  for (int trial = 0; trial < 10; ++trial) {
    const Pose2 truth{rng.Uniform(-12.0, 12.0), rng.Uniform(-4.0, 4.0), rng.Uniform(-kPi, kPi)};
    const ScanPoints points = ExtractScanPoints(testing::CastScan(world, truth), off);
    // A heading error of 0.2-0.25 rad, beyond the 0.15 rad window, either sign.
    const double sign = trial % 2 == 0 ? 1.0 : -1.0;
    const Pose2 guess = truth * Pose2{rng.Uniform(-0.1, 0.1), rng.Uniform(-0.1, 0.1),
                                      sign * rng.Uniform(0.2, 0.25)};
    const double err_off = std::abs(
        WrapAngle(CorrelativeSearch(map, points.match, guess, window, off).yaw - truth.yaw));
    const Pose2 extended = CorrelativeSearch(map, points.match, guess, window, on);
    // Without the extension the search stops at the window's edge, 0.05 rad or more short ...
    EXPECT_GT(err_off, 0.04) << "seed " << seed << " trial " << trial;
    // ... with it the heading comes out at the truth's coarse angle step, and the position too.
    EXPECT_LT(std::abs(WrapAngle(extended.yaw - truth.yaw)), 0.01)
        << "seed " << seed << " trial " << trial;
    EXPECT_LT((extended.translation - truth.translation).norm(), 0.08)
        << "seed " << seed << " trial " << trial;
    // Inside the window the extension changes nothing: the best is not on the edge there.
    const Pose2 near = truth * Pose2{0.05, -0.05, sign * 0.08};
    const Pose2 a = CorrelativeSearch(map, points.match, near, window, off);
    const Pose2 b = CorrelativeSearch(map, points.match, near, window, on);
    EXPECT_EQ(a.translation, b.translation) << "seed " << seed << " trial " << trial;
    EXPECT_EQ(a.yaw, b.yaw) << "seed " << seed << " trial " << trial;
  }
}

TEST(ScanMatcher, GaussNewtonAloneConvergesFromASmallOffset) {
  const std::vector<sim::Shape> world = testing::Hall();
  const MatcherOptions o;
  const LocalMap map = MappedHall(world, o);
  const Pose2 truth(-3.0, 1.0, 1.0);
  const ScanPoints points = ExtractScanPoints(testing::CastScan(world, truth), o);
  // 8 cm and 1.1 degrees off; the fit ends within the map's own error (cells of 5 cm).
  const Refinement r =
      RefineGaussNewton(map, points.match, truth * Pose2(0.06, -0.05, 0.02), 20, o);
  EXPECT_LT((r.pose.translation - truth.translation).norm(), 0.03);
  EXPECT_LT(std::abs(WrapAngle(r.pose.yaw - truth.yaw)), 0.005);
  EXPECT_GT(r.iterations, 0);
}

}  // namespace
}  // namespace lookout::lidar
