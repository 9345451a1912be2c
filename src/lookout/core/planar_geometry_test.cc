#include "lookout/core/planar_geometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace lookout {
namespace {

TEST(PlanarGeometry, InsidePolygonOfANonConvexRingEitherOrientation) {
  // An L: the square [0, 2] x [0, 2] less its top-right quarter.
  std::vector<Eigen::Vector2d> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  for (int orientation = 0; orientation < 2; ++orientation) {
    EXPECT_TRUE(InsidePolygon(l, {0.5, 0.5}));
    EXPECT_TRUE(InsidePolygon(l, {1.5, 0.5}));
    EXPECT_TRUE(InsidePolygon(l, {0.5, 1.5}));
    EXPECT_FALSE(InsidePolygon(l, {1.5, 1.5}));  // the notch
    EXPECT_FALSE(InsidePolygon(l, {-0.5, 0.5}));
    EXPECT_FALSE(InsidePolygon(l, {0.5, 2.5}));
    std::reverse(l.begin(), l.end());
  }
}

TEST(PlanarGeometry, PointToSegmentAlongBeyondAndDegenerate) {
  const Eigen::Vector2d a(0.0, 0.0);
  const Eigen::Vector2d b(4.0, 0.0);
  EXPECT_DOUBLE_EQ(PointToSegment({2.0, 3.0}, a, b), 3.0);   // beside: perpendicular
  EXPECT_DOUBLE_EQ(PointToSegment({7.0, 4.0}, a, b), 5.0);   // beyond b: to b
  EXPECT_DOUBLE_EQ(PointToSegment({-3.0, -4.0}, a, b), 5.0); // before a: to a
  EXPECT_DOUBLE_EQ(PointToSegment({3.0, 4.0}, a, a), 5.0);   // a point
}

}  // namespace
}  // namespace lookout
