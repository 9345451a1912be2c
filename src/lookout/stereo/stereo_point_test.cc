#include "lookout/stereo/stereo_point.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <vector>

#include "lookout/core/random.h"
#include "lookout/sim/stereo_sensor.h"

namespace lookout::stereo {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

const Pose2 kCameraMount(0.8, 0.0, 0.0);  // the simulator's default mounts
const Pose2 kLidarMount(2.2, 0.0, 0.0);

StereoObject CarAhead() {
  StereoObject o;
  o.id = 4;
  o.object_class = ObjectClass::kCar;
  o.center_m = Vector2d(20.0, 0.0);
  o.yaw_rad = 0.0;  // driving away: the laser sees its rear
  o.length_m = 4.5;
  o.width_m = 1.8;
  o.speed_longitudinal_mps = 5.0;
  o.speed_lateral_mps = 0.5;
  o.center_covariance << 0.1, 0.0, 0.0, 0.01;
  o.yaw_variance = 0.0025;
  o.speed_variance = 0.09;
  o.history = 3;
  return o;
}

TEST(StereoPointTest, CarAheadAnalytic) {
  const auto result = ProjectStereoObject(CarAhead(), kCameraMount, kLidarMount, {});
  ASSERT_TRUE(std::holds_alternative<StereoPoint>(result));
  const StereoPoint& p = std::get<StereoPoint>(result);
  // Centre at 20.8 m in the vehicle frame; the rear's middle 2.25 m nearer.
  EXPECT_LT((p.point.point_m - Vector2d(18.55, 0.0)).norm(), 1e-12);
  EXPECT_NEAR(p.polar.range_m, 16.35, 1e-12);
  EXPECT_NEAR(p.polar.bearing_rad, 0.0, 1e-15);
  EXPECT_NEAR(p.depth_m, 20.0, 1e-15);
  // Heading error swings the rear's middle sideways by 2.25 m per radian.
  EXPECT_NEAR(p.point.covariance(0, 0), 0.1, 1e-12);
  EXPECT_NEAR(p.point.covariance(1, 1), 0.01 + 0.0025 * 2.25 * 2.25, 1e-12);
  // Range variance = x variance; bearing variance = y variance / range^2.
  EXPECT_NEAR(p.polar.covariance(0, 0), 0.1, 1e-12);
  EXPECT_NEAR(p.polar.covariance(1, 1), (0.01 + 0.0025 * 2.25 * 2.25) / (16.35 * 16.35), 1e-12);
  EXPECT_EQ(p.id, 4u);
  EXPECT_EQ(p.history, 3u);
  EXPECT_EQ(p.object_class, ObjectClass::kCar);
}

TEST(StereoPointTest, RotatedCameraTurnsPositionVelocityAndCovariance) {
  const Pose2 mount(0.8, 0.5, 0.3);
  const auto result = ProjectStereoObject(CarAhead(), mount, kLidarMount, {});
  ASSERT_TRUE(std::holds_alternative<StereoPoint>(result));
  const StereoPoint& p = std::get<StereoPoint>(result);
  EXPECT_LT((p.footprint.center_m - mount * Vector2d(20.0, 0.0)).norm(), 1e-12);
  EXPECT_NEAR(p.footprint.yaw_rad, 0.3, 1e-15);
  EXPECT_LT((p.velocity_mps - mount.Rotation() * Vector2d(5.0, 0.5)).norm(), 1e-12);
  EXPECT_LT((p.velocity_covariance - 0.09 * Matrix2d::Identity()).norm(), 1e-15);
  // The centre's covariance turns with the camera: its x variance is now along 0.3 rad.
  const Vector2d axis(std::cos(0.3), std::sin(0.3));
  const Vector2d dm = p.front.midpoint_yaw_derivative;
  const double yaw_part = 0.0025 * std::pow(axis.dot(dm), 2);
  // (1e-9: the other side's share is below 1e-10 this far from a corner view.)
  EXPECT_NEAR(axis.dot(p.point.covariance * axis), 0.1 + yaw_part, 1e-9);
}

TEST(StereoPointTest, DepthModelCovarianceSource) {
  StereoObjectOptions options;
  options.covariance_source = CovarianceSource::kDepthModel;
  StereoObject o = CarAhead();
  o.yaw_variance = 0.0;
  const auto result = ProjectStereoObject(o, kCameraMount, kLidarMount, options);
  ASSERT_TRUE(std::holds_alternative<StereoPoint>(result));
  const Matrix2d expected = options.depth_model.PointCovariance(o.center_m);
  EXPECT_LT((std::get<StereoPoint>(result).point.covariance - expected).norm(), 1e-12);
}

TEST(StereoPointTest, BadObjectsAreDroppedAndCounted) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  StereoFrame frame;
  frame.stamp = 50'000'000;
  frame.mount = kCameraMount;
  std::vector<std::pair<StereoObject, std::optional<DropReason>>> cases;
  auto add = [&](auto change, std::optional<DropReason> reason) {
    StereoObject o = CarAhead();
    o.id = static_cast<std::uint32_t>(cases.size() + 1);
    change(o);
    cases.emplace_back(o, reason);
    frame.objects.push_back(o);
  };
  add([](StereoObject&) {}, std::nullopt);
  add([&](StereoObject& o) { o.center_m.x() = nan; }, DropReason::kNonFinite);
  add([&](StereoObject& o) { o.speed_lateral_mps = nan; }, DropReason::kNonFinite);
  add([&](StereoObject& o) { o.center_covariance(1, 0) = nan; }, DropReason::kNonFinite);
  add([](StereoObject& o) { o.yaw_variance = std::numeric_limits<double>::infinity(); },
      DropReason::kNonFinite);
  add([](StereoObject& o) { o.width_m = -0.1; }, DropReason::kNegativeSize);
  add([](StereoObject& o) { o.center_covariance << 1.0, 2.0, 2.0, 1.0; },
      DropReason::kCenterCovarianceNotPositiveDefinite);
  add([](StereoObject& o) { o.center_covariance << 1.0, 0.5, 0.0, 1.0; },
      DropReason::kCenterCovarianceNotPositiveDefinite);
  add([](StereoObject& o) { o.center_covariance << 0.0, 0.0, 0.0, 1.0; },
      DropReason::kCenterCovarianceNotPositiveDefinite);
  add([](StereoObject& o) { o.yaw_variance = -1e-3; }, DropReason::kNegativeYawVariance);
  add([](StereoObject& o) { o.speed_variance = 0.0; }, DropReason::kSpeedVarianceNotPositive);
  add([](StereoObject& o) { o.center_m = Vector2d(-3.0, 1.0); }, DropReason::kBehindCamera);
  // A box around the lidar (1.4 m ahead of the camera): no side faces it.
  add([](StereoObject& o) { o.center_m = Vector2d(1.4, 0.0); }, DropReason::kLidarOriginInside);
  add([](StereoObject& o) { o.length_m = 0.0; o.width_m = 0.0; }, std::nullopt);

  const ProjectedStereoFrame projected = ProjectStereoFrame(frame, kLidarMount, {});
  EXPECT_EQ(projected.stamp, frame.stamp);
  DropCounts counts;
  std::size_t kept = 0, dropped = 0;
  for (const auto& [object, reason] : cases) {
    if (!reason) {
      ASSERT_LT(kept, projected.objects.size());
      EXPECT_EQ(projected.objects[kept++].id, object.id);
      continue;
    }
    counts.Add(*reason);
    ASSERT_LT(dropped, projected.drops.size());
    EXPECT_EQ(projected.drops[dropped].id, object.id);
    EXPECT_EQ(projected.drops[dropped].reason, *reason) << Describe(projected.drops[dropped]);
    ++dropped;
  }
  EXPECT_EQ(kept, projected.objects.size());
  EXPECT_EQ(dropped, projected.drops.size());
  EXPECT_EQ(counts.Total(), 12);
  EXPECT_EQ(counts.Count(DropReason::kNonFinite), 4);
  EXPECT_EQ(Describe(projected.drops[5]),
            "stereo object 7 dropped: centre covariance not positive definite");
}

// Against the simulator's camera: the projected point's error from the true front point has
// the covariance the point carries. 4,000 frames per pose; the mean NEES of 2-dof Gaussian
// errors is 2 with a standard error of sqrt(4 / N) = 0.032, so +-0.15 is over four of them.
TEST(StereoPointTest, PointCovarianceIsConsistentWithTheSimulatedCamera) {
  const std::uint64_t seed = 77;
  sim::StereoOptions camera;
  camera.miss_rate = 0.0;
  camera.false_rate = 0.0;
  const sim::StereoNoiseModel noise;
  const Pose2 camera_pose = sim::StereoMount(camera);  // the ego at the world origin
  struct Case {
    Pose2 pose;
    double length, width;
  };
  // A car crossing at 12 m, one driving away at 28 m slightly off axis, a pedestrian at 8 m;
  // all far from a corner view (see ExpectedFrontPointTest for those).
  for (const Case& c : {Case{Pose2(12.0, 3.0, kPi / 2.0), 4.5, 1.8},
                        Case{Pose2(28.0, -1.0, 0.02), 4.5, 1.8},
                        Case{Pose2(8.0, 2.0, -1.2), 0.6, 0.6}}) {
    sim::StereoTarget target;
    target.pose = c.pose;
    target.length_m = c.length;
    target.width_m = c.width;
    target.visible_fraction = 1.0;
    const OrientedBox truth_box{c.pose.translation, c.pose.yaw, c.length, c.width};
    const Vector2d truth = FrontSegmentFacing(truth_box, kLidarMount.translation)->midpoint_m;
    const int n = 4000;
    double nees_sum = 0.0;
    for (int k = 0; k < n; ++k) {
      const StereoFrame frame =
          sim::MakeStereoFrame(camera, noise, 0, k, camera_pose, {&target, 1},
                               DeriveSeed(seed, "stereo", static_cast<std::uint64_t>(k)));
      ASSERT_EQ(frame.objects.size(), 1u);
      const ProjectedStereoFrame p = ProjectStereoFrame(frame, kLidarMount, {});
      ASSERT_EQ(p.objects.size(), 1u);
      const Vector2d e = p.objects[0].point.point_m - truth;
      nees_sum += e.dot(p.objects[0].point.covariance.inverse() * e);
    }
    EXPECT_NEAR(nees_sum / n, 2.0, 0.15)
        << "seed " << seed << ", target at " << c.pose.translation.transpose();
  }
}

// Far from a corner view the expected point is the facing side's middle; seen exactly along
// the diagonal, either side is as likely, and the point is half way with the spread between
// the two middles in its covariance.
TEST(ExpectedFrontPointTest, MixesTheTwoSidesOnlyNearACornerView) {
  const Matrix2d c = 0.01 * Matrix2d::Identity();
  const OrientedBox box{Vector2d(20.0, 0.0), 0.0, 4.0, 2.0};
  const auto far = ExpectedFrontPoint(box, c, 1e-4, Vector2d::Zero());
  ASSERT_TRUE(far.has_value());
  EXPECT_LT((far->point_m - Vector2d(18.0, 0.0)).norm(), 1e-12);
  EXPECT_NEAR(far->covariance(1, 1), 0.01 + 1e-4 * 4.0, 1e-12);

  // The viewer on the line through the corner (22, 1) - (20, 0) extended: g = 0.
  const Vector2d viewer = box.center_m + 10.0 * Vector2d(2.0, 1.0);
  const auto corner = ExpectedFrontPoint(box, c, 1e-4, viewer);
  ASSERT_TRUE(corner.has_value());
  const Vector2d end_middle(22.0, 0.0), side_middle(20.0, 1.0);
  EXPECT_LT((corner->point_m - 0.5 * (end_middle + side_middle)).norm(), 1e-9);
  const Vector2d d = side_middle - end_middle;
  EXPECT_GT(d.normalized().dot(corner->covariance * d.normalized()), 0.25 * d.squaredNorm());
  EXPECT_FALSE(ExpectedFrontPoint(box, c, 1e-4, Vector2d(20.5, 0.2)).has_value());
}

// The mixture's weight alone: nothing far from a corner view, a half on the diagonal, and
// towards a half as the viewer nears the diagonal.
TEST(ExpectedFrontPointTest, OtherSideProbabilityGrowsTowardsTheCornerView) {
  const Matrix2d c = 0.01 * Matrix2d::Identity();
  const OrientedBox box{Vector2d(20.0, 0.0), 0.0, 4.0, 2.0};
  EXPECT_LT(OtherSideProbability(box, c, 1e-4, Vector2d::Zero()), 1e-12);
  const Vector2d diagonal = box.center_m + 10.0 * Vector2d(2.0, 1.0);
  EXPECT_NEAR(OtherSideProbability(box, c, 1e-4, diagonal), 0.5, 1e-12);
  const double near = OtherSideProbability(box, c, 1e-4, diagonal + Vector2d(0.0, 0.3));
  const double nearer = OtherSideProbability(box, c, 1e-4, diagonal + Vector2d(0.0, 0.1));
  EXPECT_GT(near, 1e-3);
  EXPECT_LT(near, nearer);
  EXPECT_LT(nearer, 0.5);
  EXPECT_EQ(OtherSideProbability(box, c, 1e-4, Vector2d(20.5, 0.2)), 0.0);  // inside
}

// The heading's share of the point's error: far from a corner view, the turn of the facing
// side's middle, d(m)/d(yaw), against a central difference of the box turned; the side choice
// none. On the diagonal: q one half, the offset from the chosen side's middle to the other's.
TEST(ExpectedFrontPointTest, TheHeadingShareIsTheTurnsSlopeAndTheSideChoice) {
  const Matrix2d c = 0.01 * Matrix2d::Identity();
  const OrientedBox box{Vector2d(20.0, 1.0), 0.3, 4.0, 2.0};
  HeadingShare share;
  ASSERT_TRUE(ExpectedFrontPoint(box, c, 1e-4, Vector2d::Zero(), &share).has_value());
  const double h = 1e-6;
  OrientedBox left = box, right = box;
  left.yaw_rad += h;
  right.yaw_rad -= h;
  const Vector2d slope = (ExpectedFrontPoint(left, c, 1e-4, Vector2d::Zero())->point_m -
                          ExpectedFrontPoint(right, c, 1e-4, Vector2d::Zero())->point_m) /
                         (2.0 * h);
  EXPECT_LT((share.heading_slope_m - slope).norm(), 1e-6);
  EXPECT_GT(share.heading_slope_m.norm(), 0.9);  // the rear's middle, 2 m from the centre
  EXPECT_EQ(share.yaw_variance, 1e-4);
  EXPECT_LT(share.other_side_probability, 1e-12);

  const OrientedBox square_on{Vector2d(20.0, 0.0), 0.0, 4.0, 2.0};
  const Vector2d diagonal = square_on.center_m + 10.0 * Vector2d(2.0, 1.0);
  ASSERT_TRUE(ExpectedFrontPoint(square_on, c, 1e-4, diagonal, &share).has_value());
  EXPECT_NEAR(share.other_side_probability, 0.5, 1e-12);
  EXPECT_NEAR(std::abs(share.other_side_offset_m.dot(Vector2d(-2.0, 1.0).normalized())),
              std::sqrt(5.0), 1e-9);
}

}  // namespace
}  // namespace lookout::stereo
