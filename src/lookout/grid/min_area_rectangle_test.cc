#include "lookout/grid/min_area_rectangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "lookout/core/pose2.h"

namespace lookout::grid {
namespace {

using Eigen::Vector2d;

// The literal reference: the smallest bounding-box area over directions swept in fine steps.
// The optimum is at a hull edge's direction, which the sweep samples to within step/2, so the
// sweep's minimum is never below the exact one and is above it by O(step).
double SweptMinArea(const std::vector<Vector2d>& points, int steps) {
  double best = std::numeric_limits<double>::infinity();
  for (int s = 0; s < steps; ++s) {
    const double a = kPi / 2.0 * s / steps;
    const Vector2d u(std::cos(a), std::sin(a)), v(-std::sin(a), std::cos(a));
    double u0 = std::numeric_limits<double>::infinity(), u1 = -u0, v0 = u0, v1 = -u0;
    for (const Vector2d& p : points) {
      u0 = std::min(u0, p.dot(u));
      u1 = std::max(u1, p.dot(u));
      v0 = std::min(v0, p.dot(v));
      v1 = std::max(v1, p.dot(v));
    }
    best = std::min(best, (u1 - u0) * (v1 - v0));
  }
  return best;
}

TEST(ConvexHullTest, SquareWithInteriorAndEdgePointsKeepsTheFourCorners) {
  const std::vector<Vector2d> hull = ConvexHull(
      {{0, 0}, {1, 0}, {2, 0}, {2, 2}, {1, 1}, {0, 2}, {0, 1}, {2, 2}, {1, 2}});
  ASSERT_EQ(hull.size(), 4u);
  EXPECT_EQ(hull[0], Vector2d(0, 0));  // counter-clockwise from the lowest-leftmost
  EXPECT_EQ(hull[1], Vector2d(2, 0));
  EXPECT_EQ(hull[2], Vector2d(2, 2));
  EXPECT_EQ(hull[3], Vector2d(0, 2));
}

TEST(ConvexHullTest, DegenerateInputs) {
  EXPECT_TRUE(ConvexHull({}).empty());
  EXPECT_EQ(ConvexHull({{1, 1}, {1, 1}}).size(), 1u);
  EXPECT_EQ(ConvexHull({{0, 0}, {1, 1}, {2, 2}}).size(), 2u);  // collinear: the two ends
}

TEST(MinAreaRectangleTest, RecoversARotatedRectangle) {
  // A 4.5 x 1.8 rectangle at 30 degrees about (3, -2), its corners and points inside.
  const Pose2 pose(3.0, -2.0, DegToRad(30.0));
  std::vector<Vector2d> points;
  for (const double x : {-2.25, -1.0, 0.5, 2.25}) {
    for (const double y : {-0.9, 0.0, 0.9}) points.push_back(pose * Vector2d(x, y));
  }
  const OrientedRectangle r = MinAreaRectangle(points);
  EXPECT_NEAR(r.length_m, 4.5, 1e-9);
  EXPECT_NEAR(r.width_m, 1.8, 1e-9);
  EXPECT_NEAR(r.yaw_rad, DegToRad(30.0), 1e-9);
  EXPECT_NEAR((r.center_m - pose.translation).norm(), 0.0, 1e-9);
}

TEST(MinAreaRectangleTest, AxisIsReportedInMinusHalfPiToHalfPi) {
  // Length along 120 degrees: reported as the same axis at -60 degrees.
  const Pose2 pose(0.0, 0.0, DegToRad(120.0));
  const OrientedRectangle r = MinAreaRectangle({pose * Vector2d(-2, -0.5), pose * Vector2d(2, -0.5),
                                                pose * Vector2d(2, 0.5), pose * Vector2d(-2, 0.5)});
  EXPECT_NEAR(r.yaw_rad, DegToRad(-60.0), 1e-9);
  EXPECT_NEAR(r.length_m, 4.0, 1e-9);
  EXPECT_NEAR(r.width_m, 1.0, 1e-9);
}

TEST(MinAreaRectangleTest, DegenerateInputs) {
  const OrientedRectangle none = MinAreaRectangle({});
  EXPECT_EQ(none.length_m, 0.0);
  const OrientedRectangle point = MinAreaRectangle({{1.0, 2.0}});
  EXPECT_EQ(point.center_m, Vector2d(1.0, 2.0));
  EXPECT_EQ(point.length_m, 0.0);
  const OrientedRectangle segment = MinAreaRectangle({{0.0, 0.0}, {3.0, 4.0}});
  EXPECT_NEAR(segment.length_m, 5.0, 1e-12);
  EXPECT_NEAR(segment.width_m, 0.0, 1e-12);
  EXPECT_NEAR(segment.center_m.x(), 1.5, 1e-12);
}

TEST(MinAreaRectangleTest, MatchesTheSweptReferenceOnRandomClouds) {
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> coord(-5.0, 5.0);
    std::vector<Vector2d> points;
    const int n = 3 + static_cast<int>(rng() % 40);
    for (int i = 0; i < n; ++i) points.push_back({coord(rng), 0.3 * coord(rng)});
    const OrientedRectangle r = MinAreaRectangle(points);
    const double area = r.length_m * r.width_m;
    const double swept = SweptMinArea(points, 20000);
    EXPECT_LE(area, swept + 1e-9) << "seed " << seed;
    EXPECT_GE(area, swept * (1.0 - 1e-3)) << "seed " << seed;
    // Every point lies in the rectangle.
    const Vector2d u(std::cos(r.yaw_rad), std::sin(r.yaw_rad)), v(-u.y(), u.x());
    for (const Vector2d& p : points) {
      EXPECT_LE(std::abs((p - r.center_m).dot(u)), r.length_m / 2.0 + 1e-9) << "seed " << seed;
      EXPECT_LE(std::abs((p - r.center_m).dot(v)), r.width_m / 2.0 + 1e-9) << "seed " << seed;
    }
  }
}

}  // namespace
}  // namespace lookout::grid
