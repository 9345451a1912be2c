#include "lookout/fusion/shared_heading.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>

#include "lookout/core/random.h"
#include "lookout/fusion/sampled_moment_test_support.h"
#include "lookout/stereo/stereo_point.h"

namespace lookout::fusion {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

// A walker's square 12 m away, turned 0.3 rad from the ray (far from a corner view), estimated
// twice: the camera's box and the lidar's square, each with its own centre error but one
// heading error (the camera's, 0.05 rad). Over 100,000 draws, the two front points' errors
// have the cross-covariance SharedHeadingCovariance gives from their shares (within 4
// standard errors and the linearisation's 5 %).
TEST(SharedHeadingTest, OneHeadingErrorInBothPointsIsTheirCrossCovariance) {
  const stereo::OrientedBox truth{Vector2d(12.0, 1.0), 0.3 + std::atan2(1.0, 12.0), 0.6, 0.6};
  const Vector2d lidar = Vector2d::Zero();
  const double yaw_variance = 0.05 * 0.05;
  const Matrix2d camera_centre = Vector2d(0.04, 0.0025).asDiagonal();
  const Matrix2d lidar_centre = Vector2d(0.0009, 0.0016).asDiagonal();
  stereo::HeadingShare camera_share, lidar_share;
  const Vector2d truth_point =
      stereo::ExpectedFrontPoint(truth, camera_centre, yaw_variance, lidar, &camera_share)->point_m;
  stereo::ExpectedFrontPoint(truth, lidar_centre, yaw_variance, lidar, &lidar_share);
  const Matrix2d expected = SharedHeadingCovariance(camera_share, lidar_share);
  ASSERT_GT(expected.norm(), 1e-4);

  const Eigen::LLT<Matrix2d> camera_llt(camera_centre), lidar_llt(lidar_centre);
  const std::uint64_t seed = 20261209;
  Rng rng(seed);
  const int samples = 100000;
  testing::SampledMoment cross;
  for (int k = 0; k < samples; ++k) {
    const double heading_error = std::sqrt(yaw_variance) * rng.Normal();
    stereo::OrientedBox camera = truth, square = truth;
    camera.yaw_rad += heading_error;
    square.yaw_rad += heading_error;
    camera.center_m += camera_llt.matrixL() * Vector2d(rng.Normal(), rng.Normal());
    square.center_m += lidar_llt.matrixL() * Vector2d(rng.Normal(), rng.Normal());
    const Vector2d e_camera =
        stereo::ExpectedFrontPoint(camera, camera_centre, yaw_variance, lidar)->point_m -
        truth_point;
    const Vector2d e_lidar =
        stereo::ExpectedFrontPoint(square, lidar_centre, yaw_variance, lidar)->point_m -
        truth_point;
    cross.Add(e_camera * e_lidar.transpose());
  }
  cross.ExpectNear(expected, seed, 4.0, 0.05);
}

// The side choice, one fact in both: two estimates that chose the same side with the same q
// share q (1 - q) of the offset's outer product; that chose each the other's other, minus as
// much; either sharing nothing (a zero share): nothing.
TEST(SharedHeadingTest, TheSideChoiceIsOneIndicatorInBoth) {
  const Vector2d offset(0.3, 0.3);
  const stereo::HeadingShare chose_a{0.0, 0.25, offset, Vector2d::Zero()};
  const stereo::HeadingShare chose_b{0.0, 0.75, -offset, Vector2d::Zero()};
  const Matrix2d outer = offset * offset.transpose();
  EXPECT_LT((SharedHeadingCovariance(chose_a, chose_a) - 0.25 * 0.75 * outer).norm(), 1e-15);
  // b chose the side a left (its offset the opposite, its q a's 1 - q): one fact still, and
  // the two errors, each (q - I) along its own offset, move together as before.
  EXPECT_LT((SharedHeadingCovariance(chose_a, chose_b) - 0.25 * 0.75 * outer).norm(), 1e-15);
  EXPECT_EQ(SharedHeadingCovariance(chose_a, stereo::HeadingShare{}), Matrix2d::Zero());
}

}  // namespace
}  // namespace lookout::fusion
