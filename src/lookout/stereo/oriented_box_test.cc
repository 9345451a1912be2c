#include "lookout/stereo/oriented_box.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lookout/core/pose2.h"

namespace lookout::stereo {
namespace {

using Eigen::Vector2d;

void ExpectNear(const Vector2d& a, const Vector2d& b, double tol) {
  EXPECT_LT((a - b).norm(), tol) << a.transpose() << " vs " << b.transpose();
}

TEST(OrientedBoxTest, CornersCounterClockwiseFromRearRight) {
  const OrientedBox box{Vector2d(10.0, 5.0), kPi / 2.0, 4.0, 2.0};
  const auto c = box.Corners();
  ExpectNear(c[0], Vector2d(11.0, 3.0), 1e-12);  // rear right: heading north, right is east
  ExpectNear(c[1], Vector2d(11.0, 7.0), 1e-12);
  ExpectNear(c[2], Vector2d(9.0, 7.0), 1e-12);
  ExpectNear(c[3], Vector2d(9.0, 3.0), 1e-12);
  EXPECT_TRUE(box.Contains(Vector2d(10.9, 6.9)));
  EXPECT_FALSE(box.Contains(Vector2d(11.1, 5.0)));
}

TEST(OrientedBoxTest, RearFacesAViewerBehind) {
  // A car 20 m ahead driving away: the laser sees its rear.
  const OrientedBox box{Vector2d(20.0, 0.0), 0.0, 4.5, 1.8};
  const auto front = FrontSegmentFacing(box, Vector2d::Zero());
  ASSERT_TRUE(front.has_value());
  ExpectNear(front->midpoint_m, Vector2d(17.75, 0.0), 1e-12);
  EXPECT_NEAR((front->start_m - front->end_m).norm(), 1.8, 1e-12);
}

TEST(OrientedBoxTest, LongSideFacesAViewerBeside) {
  // A car crossing 20 m ahead: its right side faces the viewer.
  const OrientedBox box{Vector2d(20.0, 0.0), kPi / 2.0, 4.5, 1.8};
  const auto front = FrontSegmentFacing(box, Vector2d::Zero());
  ASSERT_TRUE(front.has_value());
  ExpectNear(front->midpoint_m, Vector2d(19.1, 0.0), 1e-12);
  EXPECT_NEAR((front->start_m - front->end_m).norm(), 4.5, 1e-12);
}

// The side is the one the centre-to-viewer ray leaves through: for a 4 x 2 box that switches
// where the ray crosses the corner (2, 1), at atan(1/2) = 26.57 degrees, not at 45.
TEST(OrientedBoxTest, SideSwitchesAtTheCorner) {
  const OrientedBox box{Vector2d::Zero(), 0.0, 4.0, 2.0};
  const double corner_angle = std::atan2(1.0, 2.0);
  const auto before = FrontSegmentFacing(box, 50.0 * Vector2d(std::cos(corner_angle - 0.01),
                                                              std::sin(corner_angle - 0.01)));
  const auto after = FrontSegmentFacing(box, 50.0 * Vector2d(std::cos(corner_angle + 0.01),
                                                             std::sin(corner_angle + 0.01)));
  ASSERT_TRUE(before && after);
  ExpectNear(before->midpoint_m, Vector2d(2.0, 0.0), 1e-12);
  ExpectNear(after->midpoint_m, Vector2d(0.0, 1.0), 1e-12);
}

TEST(OrientedBoxTest, NoFrontFromInside) {
  const OrientedBox box{Vector2d(1.0, 1.0), 0.3, 4.0, 2.0};
  EXPECT_FALSE(FrontSegmentFacing(box, Vector2d(1.5, 1.2)).has_value());
}

TEST(OrientedBoxTest, ZeroSizeBoxIsItsCentre) {
  const OrientedBox box{Vector2d(7.0, -2.0), 0.7, 0.0, 0.0};
  const auto front = FrontSegmentFacing(box, Vector2d::Zero());
  ASSERT_TRUE(front.has_value());
  ExpectNear(front->midpoint_m, box.center_m, 1e-12);
}

// The yaw derivative against a central difference.
TEST(OrientedBoxTest, YawDerivativeMatchesFiniteDifference) {
  const Vector2d viewer(0.0, 0.0);
  for (const double yaw : {0.1, 1.0, 2.0, -2.5}) {
    OrientedBox box{Vector2d(15.0, 4.0), yaw, 4.5, 1.8};
    const auto front = FrontSegmentFacing(box, viewer);
    ASSERT_TRUE(front.has_value());
    const double h = 1e-6;
    box.yaw_rad = yaw + h;
    const auto plus = FrontSegmentFacing(box, viewer);
    box.yaw_rad = yaw - h;
    const auto minus = FrontSegmentFacing(box, viewer);
    ASSERT_TRUE(plus && minus);
    ExpectNear(front->midpoint_yaw_derivative, (plus->midpoint_m - minus->midpoint_m) / (2 * h),
               1e-6);
  }
}

}  // namespace
}  // namespace lookout::stereo
