#include "lookout/app/building_map.h"

#include <gtest/gtest.h>

#include <cmath>


namespace lookout::app {
namespace {

// An L-shaped block (non-convex): 10 x 10 with the 5 x 5 corner at the top right cut out.
const BuildingOutlines kL = {{{0, 0}, {10, 0}, {10, 5}, {5, 5}, {5, 10}, {0, 10}}};

TEST(BuildingMapTest, DepthIsTheDistanceToTheNearestWall) {
  EXPECT_NEAR(DepthInsideBuildings(kL, {2.0, 2.0}), 2.0, 1e-12);
  EXPECT_NEAR(DepthInsideBuildings(kL, {8.0, 4.0}), 1.0, 1e-12);   // under the cut-out
  EXPECT_NEAR(DepthInsideBuildings(kL, {4.0, 7.0}), 1.0, 1e-12);   // beside it
  // Before the reflex corner (5, 5) the nearest wall point is the corner itself.
  EXPECT_NEAR(DepthInsideBuildings(kL, {4.5, 4.5}), std::sqrt(0.5), 1e-12);
}

TEST(BuildingMapTest, OutsideAndOnTheWallIsNoDepth) {
  EXPECT_EQ(DepthInsideBuildings(kL, {7.0, 7.0}), 0.0);  // in the cut-out corner
  EXPECT_EQ(DepthInsideBuildings(kL, {-0.3, 5.0}), 0.0);
  EXPECT_EQ(DepthInsideBuildings(kL, {12.0, 2.0}), 0.0);
  EXPECT_NEAR(DepthInsideBuildings(kL, {0.0, 5.0}), 0.0, 1e-12);
  EXPECT_EQ(DepthInsideBuildings({}, {2.0, 2.0}), 0.0);  // no map
}

TEST(BuildingMapTest, EitherOrientationAndTheDeepestOfOverlaps) {
  BuildingOutlines clockwise = {{{0, 0}, {0, 10}, {10, 10}, {10, 0}}};
  EXPECT_NEAR(DepthInsideBuildings(clockwise, {3.0, 6.0}), 3.0, 1e-12);
  clockwise.push_back({{2, 2}, {8, 2}, {8, 8}, {2, 8}});
  EXPECT_NEAR(DepthInsideBuildings(clockwise, {5.0, 5.0}), 5.0, 1e-12);
}

TEST(BuildingMapTest, TransformedMovesEveryVertex) {
  const Pose2 frame_from_map(3.0, -1.0, 0.5 * kPi);
  const BuildingOutlines moved = Transformed(kL, frame_from_map);
  ASSERT_EQ(moved.size(), 1u);
  ASSERT_EQ(moved[0].size(), kL[0].size());
  // The point (2, 2) of the map is 2 m inside; the same point in the new frame is too.
  const Eigen::Vector2d p = frame_from_map * Eigen::Vector2d(2.0, 2.0);
  EXPECT_NEAR(DepthInsideBuildings(moved, p), 2.0, 1e-12);
  EXPECT_NEAR(moved[0][1].x(), 3.0, 1e-12);   // (10, 0) turned a quarter and moved
  EXPECT_NEAR(moved[0][1].y(), 9.0, 1e-12);
}

}  // namespace
}  // namespace lookout::app
