#include "lookout/fusion/fuse_objects.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <variant>

#include "lookout/core/chi_square.h"
#include "lookout/fusion/fusion_test_support.h"
#include "lookout/fusion/gaussian_fusion.h"
#include "lookout/fusion/lidar_point_model.h"

namespace lookout::fusion {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

using testing::kCameraMount;
using testing::kLidarMount;

LidarObject MakeLidar(std::uint32_t id, const Vector2d& point, bool dynamic = true) {
  LidarObject o;
  o.id = id;
  o.point_m = point;
  o.point_covariance = Vector2d(0.01, 0.04).asDiagonal();
  o.front_start_m = point + Vector2d(0, -0.9);
  o.front_end_m = point + Vector2d(0, 0.9);
  o.velocity_mps = Vector2d(4.0, 0.0);
  o.velocity_covariance = 0.25 * Matrix2d::Identity();
  o.class_pmf = {0.0, 0.0, 0.0, 1.0, 0.0, 0.0};  // car
  o.dynamic = dynamic;
  return o;
}

// A stereo pedestrian (0.6 m square) whose front point lies at `front` in the vehicle frame.
stereo::StereoPoint MakeStereo(std::uint32_t id, const Vector2d& front) {
  StereoObject o;
  o.id = id;
  o.object_class = ObjectClass::kPedestrian;
  o.center_m = kCameraMount.Inverse() * (front + Vector2d(0.3, 0.0));
  o.length_m = 0.6;
  o.width_m = 0.6;
  o.speed_longitudinal_mps = 0.0;
  o.speed_lateral_mps = 1.5;
  o.center_covariance = Vector2d(0.09, 0.0025).asDiagonal();
  o.yaw_variance = 0.0;
  o.speed_variance = 0.04;
  auto result = stereo::ProjectStereoObject(o, kCameraMount, kLidarMount, {});
  return std::get<stereo::StereoPoint>(result);
}

LidarObjectFrame Frame(std::vector<LidarObject> objects) {
  LidarObjectFrame frame;
  frame.stamp = 800'000'000;
  frame.mount = kLidarMount;
  frame.ego_pose = Pose2(5.0, 1.0, 0.1);
  frame.objects = std::move(objects);
  return frame;
}

// The covariances as given: the lidar point model (which would add a pedestrian's round body
// to the lidar's, TheLidarPointTakesTheCamerasClass, and the side's heading) off.
FusionOptions CovariancesAsGiven() {
  FusionOptions options;
  options.lidar_point.round_body = false;
  options.lidar_point.side_heading = false;
  return options;
}

TEST(FuseObjectsTest, PairIsFusedByCovariances) {
  const LidarObjectFrame lidar = Frame({MakeLidar(7, Vector2d(15.2, 0.1))});
  const std::vector<stereo::StereoPoint> stereo = {MakeStereo(3, Vector2d(15.0, 0.0))};
  const FuseObjectsResult result = FuseObjects(lidar, stereo, CovariancesAsGiven());
  ASSERT_EQ(result.frame.objects.size(), 1u);
  EXPECT_EQ(result.pairs, 1u);
  const FusedObject& f = result.frame.objects[0];
  EXPECT_EQ(f.sensor_count, 2);
  EXPECT_EQ(f.lidar_id, 7u);
  EXPECT_EQ(f.stereo_id, 3u);
  const Gaussian2 expected =
      FuseGaussians({lidar.objects[0].point_m, lidar.objects[0].point_covariance},
                    {stereo[0].point.point_m, stereo[0].point.covariance});
  EXPECT_LT((f.point_m - expected.mean).norm(), 1e-9);
  EXPECT_LT((f.point_covariance - expected.covariance).norm(), 1e-9);
  // x: lidar 0.01 against stereo 0.09 -> 0.9 of the way to the lidar's 15.2.
  EXPECT_NEAR(f.point_m.x(), 15.18, 1e-9);
  // Class from the camera (pedestrian, 0.9), velocity weighted: lidar (4, 0) var 0.25 and
  // stereo (0, 1.5) var 0.04.
  EXPECT_NEAR(f.class_pmf[static_cast<std::size_t>(ObjectClass::kPedestrian)], 0.9, 1e-15);
  EXPECT_NEAR(f.class_pmf[static_cast<std::size_t>(ObjectClass::kCar)], 0.02, 1e-15);
  EXPECT_NEAR(f.velocity_mps.x(), 4.0 * 0.04 / 0.29, 1e-9);
  EXPECT_NEAR(f.velocity_mps.y(), 1.5 * 0.25 / 0.29, 1e-9);
  EXPECT_TRUE(f.dynamic);
  EXPECT_EQ(result.frame.stamp, lidar.stamp);
  EXPECT_EQ(result.frame.ego_pose.yaw, 0.1);
}

// A pair inside the gate (which allows point_definition_sigma_m) whose points disagree beyond
// the 99 % quantile under their own covariances: 1.1 m apart along x against 0.1 m^2, d^2
// about 12. The fused point stays the information-weighted mean, its covariance is scaled by
// d^2 / quantile; with the option off it is FuseGaussians' alone.
TEST(FuseObjectsTest, APairThatDisagreesHoldsItsDisagreement) {
  const LidarObjectFrame lidar = Frame({MakeLidar(7, Vector2d(16.1, 0.1))});
  const std::vector<stereo::StereoPoint> stereo = {MakeStereo(3, Vector2d(15.0, 0.0))};
  FusionOptions options = CovariancesAsGiven();
  const Gaussian2 l{lidar.objects[0].point_m, lidar.objects[0].point_covariance};
  const Gaussian2 s{stereo[0].point.point_m, stereo[0].point.covariance};
  const double quantile = ChiSquareQuantile(options.disagreement_probability, 2.0);
  const double scale = DisagreementScale(l, s, quantile);
  ASSERT_GT(scale, 1.2);
  const Gaussian2 expected = FuseGaussians(l, s);
  const FuseObjectsResult result = FuseObjects(lidar, stereo, options);
  ASSERT_EQ(result.pairs, 1u);
  const FusedObject& f = result.frame.objects[0];
  EXPECT_LT((f.point_m - expected.mean).norm(), 1e-9);
  EXPECT_LT((f.point_covariance - scale * expected.covariance).norm(), 1e-9);
  options.disagreement_probability = 1.0;
  const FuseObjectsResult off = FuseObjects(lidar, stereo, options);
  ASSERT_EQ(off.pairs, 1u);
  EXPECT_LT((off.frame.objects[0].point_covariance - expected.covariance).norm(), 1e-9);
}

// A pair inside the gate (which allows point_definition_sigma_m) whose points disagree beyond
// the 99.9 % quantile under their own covariances (1.2 m apart along x against 0.1 m^2, d^2
// about 14.6): one of the two is on something else. The fused point stays; its covariance,
// scaled as any disagreement's, becomes TwoBodiesMixture's, as wide along x as the two points'
// spread about it allows. With the option off it is the scaled covariance alone.
TEST(FuseObjectsTest, APairTooFarApartForItsCovariancesMayBeTwoBodies) {
  const LidarObjectFrame lidar = Frame({MakeLidar(7, Vector2d(16.2, 0.1))});
  const std::vector<stereo::StereoPoint> stereo = {MakeStereo(3, Vector2d(15.0, 0.0))};
  FusionOptions options = CovariancesAsGiven();
  const Gaussian2 l{lidar.objects[0].point_m, lidar.objects[0].point_covariance};
  const Gaussian2 s{stereo[0].point.point_m, stereo[0].point.covariance};
  const double two_bodies = ChiSquareQuantile(options.two_bodies_probability, 2.0);
  ASSERT_GT(MahalanobisSquared(l.mean - s.mean, l.covariance + s.covariance), two_bodies);
  const Gaussian2 fused = FuseGaussians(l, s);
  const Gaussian2 scaled{
      fused.mean,
      DisagreementScale(l, s, ChiSquareQuantile(options.disagreement_probability, 2.0)) *
          fused.covariance};
  const FuseObjectsResult result = FuseObjects(lidar, stereo, options);
  ASSERT_EQ(result.pairs, 1u);
  const FusedObject& f = result.frame.objects[0];
  EXPECT_LT((f.point_m - fused.mean).norm(), 1e-9);
  EXPECT_LT((f.point_covariance - TwoBodiesMixture(scaled, l, s, two_bodies)).norm(), 1e-9);
  EXPECT_GT(f.point_covariance(0, 0), 2.0 * scaled.covariance(0, 0));
  options.two_bodies_probability = 1.0;
  const FuseObjectsResult off = FuseObjects(lidar, stereo, options);
  ASSERT_EQ(off.pairs, 1u);
  EXPECT_LT((off.frame.objects[0].point_covariance - scaled.covariance).norm(), 1e-9);
}

// A pair that agrees within its own covariances, where its camera track's prior (its last pair
// predicted to this stamp) puts the body 0.6 m away against 5 cm: the fused point stays, its
// covariance is scaled by d^2 / quantile under the fused and the prior's covariances summed,
// and, the two still further apart than the 99.9 % point, becomes DisagreementMixture's with
// the prior: spread along the 0.6 m to it. A prior that agrees, another camera track's prior,
// or the option off leave it as the pair alone makes it.
TEST(FuseObjectsTest, APairItsCameraTrackPutsElsewhereHoldsTheDisagreement) {
  const LidarObjectFrame lidar = Frame({MakeLidar(7, Vector2d(15.1, 0.05))});
  const std::vector<stereo::StereoPoint> stereo = {MakeStereo(3, Vector2d(15.0, 0.0))};
  FusionOptions options = CovariancesAsGiven();
  const FuseObjectsResult alone = FuseObjects(lidar, stereo, options);
  ASSERT_EQ(alone.pairs, 1u);
  const FusedObject& f = alone.frame.objects[0];
  const auto fused_with = [&](const std::vector<PairPrior>& priors) {
    const FuseObjectsResult r = FuseObjects(lidar, stereo, options, priors);
    EXPECT_EQ(r.pairs, 1u);
    return r.frame.objects.at(0);
  };

  const stereo::CartesianPoint elsewhere{f.point_m + Vector2d(0.0, 0.6),
                                         0.0025 * Matrix2d::Identity()};
  const double d2 =
      MahalanobisSquared(elsewhere.point_m - f.point_m, elsewhere.covariance + f.point_covariance);
  const double quantile = ChiSquareQuantile(options.history_disagreement_probability, 2.0);
  ASSERT_GT(d2, 2.0 * quantile);
  const FusedObject widened = fused_with({PairPrior{0, elsewhere}});
  EXPECT_LT((widened.point_m - f.point_m).norm(), 1e-12);
  const Gaussian2 history{elsewhere.point_m, elsewhere.covariance};
  const Gaussian2 scaled{f.point_m, d2 / quantile * f.point_covariance};
  const double two_bodies = ChiSquareQuantile(options.two_bodies_probability, 2.0);
  const double scaled_d2 =
      MahalanobisSquared(history.mean - scaled.mean, history.covariance + scaled.covariance);
  ASSERT_GT(scaled_d2, two_bodies);
  EXPECT_LT((widened.point_covariance - DisagreementMixture(scaled, history, two_bodies)).norm(),
            1e-12);
  // Across the offset (y) it holds the offset's share: more than (1 - q / d^2) 0.36 m^2.
  EXPECT_GT(widened.point_covariance(1, 1), (1.0 - two_bodies / scaled_d2) * 0.36);

  const stereo::CartesianPoint agreeing{f.point_m + Vector2d(0.0, 0.02), elsewhere.covariance};
  EXPECT_LT((fused_with({PairPrior{0, agreeing}}).point_covariance - f.point_covariance).norm(),
            1e-15);
  EXPECT_LT((fused_with({PairPrior{std::nullopt, elsewhere}}).point_covariance - f.point_covariance)
                .norm(),
            1e-15);
  options.history_disagreement_probability = 1.0;
  EXPECT_LT((fused_with({PairPrior{0, elsewhere}}).point_covariance - f.point_covariance).norm(),
            1e-15);
}

// The lidar point's covariance is the model's (lidar_point_model.h) with the camera's class
// where the camera paired the object, and the pair is fused with it: a segmentation object
// (its own class unknown) paired with a stereo pedestrian gets the round body's spread; one
// the camera did not see keeps its own covariance.
TEST(FuseObjectsTest, TheLidarPointTakesTheCamerasClass) {
  LidarObject paired = MakeLidar(7, Vector2d(15.2, 0.1));
  LidarObject alone = MakeLidar(8, Vector2d(15.0, 6.0));
  paired.class_pmf = {1.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  alone.class_pmf = paired.class_pmf;
  const LidarObjectFrame lidar = Frame({paired, alone});
  const std::vector<stereo::StereoPoint> stereo = {MakeStereo(3, Vector2d(15.0, 0.0))};
  FusionOptions options;
  options.lidar_point.round_body = true;
  const FuseObjectsResult result = FuseObjects(lidar, stereo, options);
  ASSERT_EQ(result.pairs, 1u);
  ASSERT_EQ(result.lidar.objects.size(), 2u);
  const Matrix2d modelled = LidarPointCovariance(paired, ObjectClass::kPedestrian,
                                                 kLidarMount.translation, options.lidar_point);
  EXPECT_GT((modelled - paired.point_covariance).norm(), 1e-3);
  EXPECT_EQ(result.lidar.objects[0].point_covariance, modelled);
  EXPECT_EQ(result.lidar.objects[1].point_covariance, alone.point_covariance);
  const Gaussian2 expected = FuseGaussians({paired.point_m, modelled},
                                           {stereo[0].point.point_m, stereo[0].point.covariance});
  const FusedObject& f = result.frame.objects[0];
  EXPECT_LT((f.point_m - expected.mean).norm(), 1e-12);
  EXPECT_LT((f.point_covariance - expected.covariance).norm(), 1e-12);
  EXPECT_EQ(result.frame.objects[1].point_covariance, alone.point_covariance);
}

// A small L the scan read as an arc too: paired with the camera's walker, the lidar object
// the fusion keeps and the point it fuses are the arc's (ReadAsBody); unpaired, the L stays.
TEST(FuseObjectsTest, AWalkersSmallLIsFusedAsItsArc) {
  LidarObject paired = MakeLidar(7, Vector2d(15.2, 0.1));
  paired.front_start_m = paired.point_m + Vector2d(0.0, -0.1);
  paired.front_end_m = paired.point_m + Vector2d(0.0, 0.2);
  LidarObject::FrontReading arc;
  arc.point_m = Vector2d(15.1, 0.0);
  arc.point_covariance = Vector2d(0.0009, 0.0016).asDiagonal();
  arc.front_start_m = Vector2d(15.1, -0.28);
  arc.front_end_m = Vector2d(15.1, 0.28);
  arc.hidden_start_m = 0.05;
  arc.hidden_end_m = 0.05;
  paired.arc_reading = arc;
  paired.has_arc_reading = true;
  LidarObject alone = paired;
  alone.id = 8;
  alone.point_m = Vector2d(15.0, 6.0);
  const LidarObjectFrame lidar = Frame({paired, alone});
  const std::vector<stereo::StereoPoint> stereo = {MakeStereo(3, Vector2d(15.0, 0.0))};
  const FusionOptions options;
  const FuseObjectsResult result = FuseObjects(lidar, stereo, options);
  ASSERT_EQ(result.pairs, 1u);
  ASSERT_EQ(result.lidar.objects.size(), 2u);
  EXPECT_EQ(result.lidar.objects[0].point_m, arc.point_m);
  EXPECT_EQ(result.lidar.objects[0].front_end_m, arc.front_end_m);
  EXPECT_EQ(result.lidar.objects[1].point_m, alone.point_m);
  // The fused point is what the arc's reading fuses to, not the L's.
  const PairedBody body{stereo[0].object_class, stereo[0].footprint.length_m,
                        stereo[0].footprint.width_m,
                        stereo[0].front.end_m - stereo[0].front.start_m, stereo[0].yaw_variance};
  const LidarObject read = ReadAsBody(paired, body, options.lidar_point);
  const LidarSidePoint side =
      FacingSidePoint(read, body, kLidarMount.translation, options.lidar_point);
  paired.has_arc_reading = false;
  const LidarSidePoint l_side =
      FacingSidePoint(paired, body, kLidarMount.translation, options.lidar_point);
  EXPECT_LT((result.frame.objects[0].front_end_m - side.front_end_m).norm(), 1e-12);
  EXPECT_GT((side.point_m - l_side.point_m).norm(), 0.05);
}

TEST(FuseObjectsTest, ObjectsSeenByOneSensorAreKept) {
  // A lidar object with no stereo partner, a stereo object far from any lidar object.
  const LidarObjectFrame lidar = Frame({MakeLidar(1, Vector2d(15.0, 5.0), false)});
  const std::vector<stereo::StereoPoint> stereo = {MakeStereo(2, Vector2d(12.0, -3.0))};
  const FuseObjectsResult result = FuseObjects(lidar, stereo, {});
  ASSERT_EQ(result.frame.objects.size(), 2u);
  EXPECT_EQ(result.pairs, 0u);
  const FusedObject& l = result.frame.objects[0];
  EXPECT_EQ(l.sensor_count, 1);
  EXPECT_EQ(l.lidar_id, 1u);
  EXPECT_FALSE(l.stereo_id.has_value());
  EXPECT_EQ(l.point_m, lidar.objects[0].point_m);
  EXPECT_EQ(l.class_pmf, lidar.objects[0].class_pmf);  // the lidar's class without a camera
  EXPECT_FALSE(l.dynamic);
  const FusedObject& s = result.frame.objects[1];
  EXPECT_EQ(s.sensor_count, 1);
  EXPECT_EQ(s.stereo_id, 2u);
  EXPECT_FALSE(s.lidar_id.has_value());
  EXPECT_LT((s.point_m - Vector2d(12.0, -3.0)).norm(), 1e-9);
  EXPECT_LT((s.point_covariance - stereo[0].point.covariance).norm(), 1e-12);
  EXPECT_TRUE(s.dynamic);  // 1.5 m/s against sigma 0.2
  EXPECT_EQ(s.id, 1u);
}

// A stereo body of `object_class`, `length_m` long across the lidar's view (its length along
// the vehicle's y axis), whose near side's middle is at `front` in the vehicle frame.
stereo::StereoPoint MakeStereoBody(std::uint32_t id, ObjectClass object_class,
                                   const Vector2d& front, double length_m, double width_m) {
  StereoObject o;
  o.id = id;
  o.object_class = object_class;
  o.center_m = kCameraMount.Inverse() * (front + Vector2d(0.5 * width_m, 0.0));
  o.yaw_rad = 0.5 * kPi;
  o.length_m = length_m;
  o.width_m = width_m;
  o.speed_lateral_mps = 2.5;
  o.center_covariance = Vector2d(0.09, 0.0025).asDiagonal();
  o.speed_variance = 0.04;
  auto result = stereo::ProjectStereoObject(o, kCameraMount, kLidarMount, {});
  return std::get<stereo::StereoPoint>(result);
}

// A piece of a body's near side at x = 15, from y0 to y1, seen sharply (2 cm).
LidarObject SidePiece(std::uint32_t id, double y0, double y1) {
  LidarObject o = MakeLidar(id, Vector2d(15.0, 0.5 * (y0 + y1)));
  o.front_start_m = Vector2d(15.0, y0);
  o.front_end_m = Vector2d(15.0, y1);
  o.point_covariance = Vector2d(0.0004, 0.0004).asDiagonal();
  return o;
}

TEST(FuseObjectsTest, APairedBodysOtherPiecesAreItsFragments) {
  // A cyclist crossing 15 m ahead, its near side split into two pieces by the gap between its
  // wheels, and a third object 1.5 m beyond its front wheel.
  const LidarObjectFrame lidar =
      Frame({SidePiece(1, -0.9, -0.2), SidePiece(2, 0.2, 0.9), SidePiece(3, 2.4, 2.9)});
  const std::vector<stereo::StereoPoint> cyclist = {
      MakeStereoBody(5, ObjectClass::kCyclist, Vector2d(15.0, 0.0), 1.8, 0.6)};
  const FuseObjectsResult result = FuseObjects(lidar, cyclist, {});
  EXPECT_EQ(result.pairs, 1u);
  ASSERT_EQ(result.fragment_lidar_ids.size(), 1u);
  ASSERT_EQ(result.frame.objects.size(), 2u) << "the pair and the object beyond the wheel";
  const FusedObject& pair = result.frame.objects[0];
  ASSERT_TRUE(pair.lidar_id.has_value());
  EXPECT_EQ(pair.stereo_id, 5u);
  // The piece the camera did not pair is the fragment.
  EXPECT_EQ(result.fragment_lidar_ids[0], *pair.lidar_id == 1u ? 2u : 1u);
  EXPECT_EQ(result.frame.objects[1].lidar_id, 3u);
  EXPECT_EQ(result.frame.objects[1].sensor_count, 1);
  EXPECT_EQ(result.lidar.objects.size(), 3u) << "the lidar objects as fused keep every one";

  // The camera's rule alone from here on (the pieces' rule, next test, would join what lies
  // within 0.5 m whatever its class).
  FusionOptions fragments_only;
  fragments_only.piece_gap_m = 0.0;
  // A walker is one arc: two walkers side by side stay two, however close.
  const std::vector<stereo::StereoPoint> walker = {
      MakeStereoBody(6, ObjectClass::kPedestrian, Vector2d(15.0, -0.55), 0.6, 0.6)};
  const FuseObjectsResult walkers = FuseObjects(
      Frame({SidePiece(1, -0.8, -0.3), SidePiece(2, -0.15, 0.25)}), walker, fragments_only);
  EXPECT_TRUE(walkers.fragment_lidar_ids.empty());
  EXPECT_EQ(walkers.frame.objects.size(), 2u);

  // Without the camera's pair nothing is a fragment: the stereo object pairs no piece (all
  // 4 m off), and each piece stays an object.
  const std::vector<stereo::StereoPoint> far = {
      MakeStereoBody(7, ObjectClass::kCyclist, Vector2d(11.0, 0.0), 1.8, 0.6)};
  const FuseObjectsResult unpaired = FuseObjects(lidar, far, fragments_only);
  EXPECT_EQ(unpaired.pairs, 0u);
  EXPECT_TRUE(unpaired.fragment_lidar_ids.empty());
  EXPECT_EQ(unpaired.frame.objects.size(), 4u);
}

TEST(FuseObjectsTest, ACarSeenOnTwoSidesIsOneObjectWithTheCamerasPoint) {
  // The camera sees a car crossing 15 m ahead, 4.5 m long, its near side at x = 15; the lidar
  // sees only its nose, the front face from x = 15.0 to 16.8 at y = 2.25, past a corner block.
  // The two middles are 2.4 m apart, and the point gate refuses them.
  LidarObject nose = MakeLidar(4, Vector2d(15.9, 2.25));
  nose.front_start_m = Vector2d(15.0, 2.25);
  nose.front_end_m = Vector2d(16.8, 2.25);
  nose.point_covariance = Vector2d(0.0004, 0.0004).asDiagonal();
  const std::vector<stereo::StereoPoint> car = {
      MakeStereoBody(8, ObjectClass::kCar, Vector2d(15.0, 0.0), 4.5, 1.8)};
  const FuseObjectsResult result = FuseObjects(Frame({nose}), car, {});
  EXPECT_EQ(result.pairs, 0u);
  EXPECT_EQ(result.footprint_pairs, 1u);
  ASSERT_EQ(result.frame.objects.size(), 1u);
  const FusedObject& f = result.frame.objects[0];
  EXPECT_EQ(f.sensor_count, 2);
  EXPECT_EQ(f.lidar_id, 4u);
  EXPECT_EQ(f.stereo_id, 8u);
  EXPECT_TRUE(f.footprint_pair);
  const stereo::CartesianPoint camera = stereo::ToCartesian(car[0].polar, kLidarMount);
  EXPECT_LT((f.point_m - camera.point_m).norm(), 1e-9) << "two sides' middles are not fused";
  EXPECT_EQ(f.front_start_m, car[0].front.start_m);
  EXPECT_GT(f.class_pmf[static_cast<std::size_t>(ObjectClass::kCar)], 0.5);

  // A lidar object 3 m beyond the car's front pairs with nothing.
  LidarObject beyond = nose;
  beyond.front_start_m.y() += 3.0;
  beyond.front_end_m.y() += 3.0;
  beyond.point_m.y() += 3.0;
  const FuseObjectsResult apart = FuseObjects(Frame({beyond}), car, {});
  EXPECT_EQ(apart.footprint_pairs, 0u);
  EXPECT_EQ(apart.frame.objects.size(), 2u);
}

// A dynamic lidar object whose front segment runs from `a` to `b`.
LidarObject Segment(std::uint32_t id, const Vector2d& a, const Vector2d& b) {
  LidarObject o = MakeLidar(id, 0.5 * (a + b));
  o.front_start_m = a;
  o.front_end_m = b;
  return o;
}

TEST(FuseObjectsTest, FrontSegmentDistance) {
  EXPECT_NEAR(FrontSegmentDistance(Segment(1, {0, 0}, {0, 2}), Segment(2, {0.5, 3}, {2, 3})),
              std::hypot(0.5, 1.0), 1e-12);  // end to end
  EXPECT_NEAR(FrontSegmentDistance(Segment(1, {0, 0}, {0, 2}), Segment(2, {0.4, 1}, {2, 1})), 0.4,
              1e-12);  // an end to the other's middle
  EXPECT_EQ(FrontSegmentDistance(Segment(1, {0, 0}, {2, 2}), Segment(2, {0, 2}, {2, 0})), 0.0);
}

TEST(FuseObjectsTest, WithoutTheCameraASplitBodysShorterPieceIsLeftOut) {
  // fig8's cyclist out of the camera's view at 3.20 s: its west side (1.75 m) and, 0.46 m from
  // its end, a piece of its front face; a walker 1.5 m further on is another body.
  const LidarObject side = Segment(1, {15.0, 1.75}, {15.0, 0.0});
  const LidarObject face = Segment(2, {15.46, 0.0}, {15.55, 0.0});
  const LidarObject walker = Segment(3, {15.0, -1.5}, {15.0, -1.9});
  FuseObjectsResult result = FuseObjects(Frame({side, face, walker}), {}, {});
  ASSERT_EQ(result.piece_lidar_ids.size(), 1u);
  EXPECT_EQ(result.piece_lidar_ids[0], 2u);
  ASSERT_EQ(result.frame.objects.size(), 2u);
  EXPECT_EQ(result.frame.objects[0].lidar_id, 1u);
  EXPECT_EQ(result.frame.objects[1].lidar_id, 3u);

  // Off, or a static piece (the tracking stage takes no static lidar-only object): all kept.
  FusionOptions off;
  off.piece_gap_m = 0.0;
  EXPECT_EQ(FuseObjects(Frame({side, face, walker}), {}, off).frame.objects.size(), 3u);
  LidarObject still = face;
  still.dynamic = false;
  EXPECT_TRUE(FuseObjects(Frame({side, still, walker}), {}, {}).piece_lidar_ids.empty());

  // A piece the camera paired is never left out; the longer unpaired one beside it is.
  const std::vector<stereo::StereoPoint> walker_seen = {
      MakeStereoBody(9, ObjectClass::kPedestrian, Vector2d(15.0, 0.35), 0.6, 0.6)};
  const LidarObject arc = Segment(4, {15.0, 0.5}, {15.0, 0.2});
  const LidarObject beside = Segment(5, {15.0, 0.0}, {15.0, -0.9});
  result = FuseObjects(Frame({arc, beside}), walker_seen, {});
  EXPECT_EQ(result.pairs, 1u);
  ASSERT_EQ(result.piece_lidar_ids.size(), 1u);
  EXPECT_EQ(result.piece_lidar_ids[0], 5u);
}

TEST(FuseObjectsTest, VelocitySourceOption) {
  const LidarObjectFrame lidar = Frame({MakeLidar(7, Vector2d(15.2, 0.1))});
  const std::vector<stereo::StereoPoint> stereo = {MakeStereo(3, Vector2d(15.0, 0.0))};
  FusionOptions options;
  options.velocity_source = VelocitySource::kLidar;
  EXPECT_EQ(FuseObjects(lidar, stereo, options).frame.objects[0].velocity_mps, Vector2d(4.0, 0.0));
  options.velocity_source = VelocitySource::kStereo;
  EXPECT_LT((FuseObjects(lidar, stereo, options).frame.objects[0].velocity_mps - Vector2d(0.0, 1.5))
                .norm(),
            1e-12);
}

TEST(FuseObjectsTest, UnusableLidarObjectsAreDroppedAndCounted) {
  LidarObject nan_point = MakeLidar(5, Vector2d(10, 0));
  nan_point.point_m.x() = std::numeric_limits<double>::quiet_NaN();
  LidarObject singular = MakeLidar(6, Vector2d(10, 0));
  singular.point_covariance = Matrix2d::Zero();
  const LidarObjectFrame lidar = Frame({nan_point, MakeLidar(4, Vector2d(20, 0)), singular});
  const FuseObjectsResult result = FuseObjects(lidar, {}, {});
  ASSERT_EQ(result.frame.objects.size(), 1u);
  EXPECT_EQ(result.frame.objects[0].lidar_id, 4u);
  EXPECT_EQ(result.dropped_lidar_ids, (std::vector<std::uint32_t>{5, 6}));
}

TEST(FuseObjectsTest, StereoClassPmfSumsToOne) {
  const auto pmf = StereoClassPmf(ObjectClass::kPole, 0.7);
  double sum = 0.0;
  for (const double p : pmf) sum += p;
  EXPECT_NEAR(sum, 1.0, 1e-15);
  EXPECT_EQ(pmf[static_cast<std::size_t>(ObjectClass::kPole)], 0.7);
}

TEST(FuseObjectsTest, MovingNeedsSpeedAndSignificance) {
  const Matrix2d c = 0.09 * Matrix2d::Identity();                         // sigma 0.3 m/s
  EXPECT_FALSE(IsSignificantlyMoving(Vector2d(0.4, 0.0), c, 0.5, 0.99));  // too slow
  EXPECT_FALSE(IsSignificantlyMoving(Vector2d(0.8, 0.0), c, 0.5, 0.99));  // d2 7.1 < 9.21
  EXPECT_TRUE(IsSignificantlyMoving(Vector2d(1.0, 0.0), c, 0.5, 0.99));   // d2 11.1
}

}  // namespace
}  // namespace lookout::fusion
