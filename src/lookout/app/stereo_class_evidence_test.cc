#include "lookout/app/stereo_class_evidence.h"

#include <gtest/gtest.h>

#include "lookout/core/input_error.h"

namespace lookout::app {
namespace {

using Eigen::Vector2d;

float At(const grid::ClassPmf& l, grid::GridClass c) { return l[static_cast<std::size_t>(c)]; }

TEST(StereoClassEvidenceTest, LikelihoodIsTheCamerasConfusionModel) {
  // P(report | true) = a for the true class, (1 - a) / 5 for each other (a = 0.9: 0.02).
  const auto pedestrian = GridClassLikelihood(ObjectClass::kPedestrian, 0.9);
  ASSERT_TRUE(pedestrian);
  EXPECT_NEAR(At(*pedestrian, grid::GridClass::kPedestrian), 0.9, 1e-6);
  EXPECT_NEAR(At(*pedestrian, grid::GridClass::kCyclist), 0.02, 1e-6);
  EXPECT_NEAR(At(*pedestrian, grid::GridClass::kVehicle), 0.02, 1e-6);  // car and truck alike
  EXPECT_NEAR(At(*pedestrian, grid::GridClass::kStatic), 0.02, 1e-6);   // a pole
  EXPECT_NEAR(At(*pedestrian, grid::GridClass::kUnknown), 0.02, 1e-6);
  // A car: the vehicle class holds car (0.9) and truck (0.02), their mean.
  const auto car = GridClassLikelihood(ObjectClass::kCar, 0.9);
  ASSERT_TRUE(car);
  EXPECT_NEAR(At(*car, grid::GridClass::kVehicle), 0.46, 1e-6);
  EXPECT_NEAR(At(*car, grid::GridClass::kPedestrian), 0.02, 1e-6);
  const auto pole = GridClassLikelihood(ObjectClass::kPole, 0.8);
  ASSERT_TRUE(pole);
  EXPECT_NEAR(At(*pole, grid::GridClass::kStatic), 0.8, 1e-6);
  EXPECT_NEAR(At(*pole, grid::GridClass::kVehicle), 0.04, 1e-6);
  EXPECT_FALSE(GridClassLikelihood(ObjectClass::kUnknown, 0.9));
}

stereo::StereoPoint Object(ObjectClass c, const Vector2d& centre, double sigma_m) {
  stereo::StereoPoint p;
  p.object_class = c;
  p.footprint = stereo::OrientedBox{centre, 0.0, 4.0, 2.0};
  p.point.point_m = centre - Vector2d(2.0, 0.0);
  p.point.covariance = sigma_m * sigma_m * Eigen::Matrix2d::Identity();
  p.velocity_mps = Vector2d(10.0, 0.0);
  p.front = stereo::FrontSegment{Vector2d::Zero(), Vector2d::Zero(), p.point.point_m,
                                 Vector2d::Zero()};
  return p;
}

TEST(StereoClassEvidenceTest, RegionIsTheFootprintMovedToTheScanInTheOdometryFrame) {
  stereo::ProjectedStereoFrame frame;
  frame.objects = {Object(ObjectClass::kCar, Vector2d(20.0, 0.0), 0.5),
                   Object(ObjectClass::kUnknown, Vector2d(10.0, 5.0), 0.5)};
  const Pose2 ego(100.0, 50.0, 0.5 * kPi);  // facing +y in the odometry frame
  StereoClassEvidenceOptions options;
  const auto regions = StereoClassRegions(frame, ego, 0.05, options);
  ASSERT_EQ(regions.size(), 1u);  // the unknown report gives none
  const grid::StereoClassRegion& r = regions[0];
  ASSERT_EQ(r.polygon_m.size(), 4u);
  // Centre moved 0.5 m forward (10 m/s for 50 ms), then into the odometry frame.
  Vector2d centre = Vector2d::Zero();
  for (const Vector2d& p : r.polygon_m) centre += 0.25 * p;
  EXPECT_NEAR((centre - Vector2d(100.0, 70.5)).norm(), 0.0, 1e-9);
  // Grown by one sigma (0.5 m) on every side: 5 m along the heading (+y), 3 m across.
  EXPECT_NEAR((r.polygon_m[1] - r.polygon_m[0]).norm(), 5.0, 1e-9);
  EXPECT_NEAR((r.polygon_m[2] - r.polygon_m[1]).norm(), 3.0, 1e-9);
  // p = 8 / 15 of the region is the car's: L' = p L + (1 - p) / 6.
  const double p = 8.0 / 15.0;
  EXPECT_NEAR(At(r.likelihood, grid::GridClass::kVehicle), p * 0.46 + (1.0 - p) / 6.0, 1e-6);
  EXPECT_NEAR(At(r.likelihood, grid::GridClass::kPedestrian), p * 0.02 + (1.0 - p) / 6.0, 1e-6);
}

TEST(StereoClassEvidenceTest, AFarObjectGivesWeakerEvidenceThanANearOne) {
  stereo::ProjectedStereoFrame frame;
  frame.objects = {Object(ObjectClass::kCar, Vector2d(5.0, 0.0), 0.05),
                   Object(ObjectClass::kCar, Vector2d(30.0, 0.0), 1.0)};
  const auto regions = StereoClassRegions(frame, Pose2(), 0.0, StereoClassEvidenceOptions{});
  ASSERT_EQ(regions.size(), 2u);
  const auto ratio = [](const grid::StereoClassRegion& r) {
    return static_cast<double>(At(r.likelihood, grid::GridClass::kVehicle)) /
           static_cast<double>(At(r.likelihood, grid::GridClass::kPedestrian));
  };
  EXPECT_GT(ratio(regions[0]), 10.0);  // 23 untempered
  EXPECT_LT(ratio(regions[1]), ratio(regions[0]) / 2.0);
  EXPECT_GT(ratio(regions[1]), 1.0);
}

TEST(StereoClassEvidenceTest, OptionsNameTheBadField) {
  StereoClassEvidenceOptions options;
  options.class_accuracy = 1.0;
  try {
    options.Validate();
    FAIL() << "accepted class_accuracy = 1";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "stereo_class.class_accuracy");
  }
}

}  // namespace
}  // namespace lookout::app
