#include "lookout/tracking/tracker.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace lookout::tracking {
namespace {

Detection At(double x, double y) {
  Detection d;
  d.position_m = Eigen::Vector2d(x, y);
  d.covariance = Eigen::Vector2d(0.04, 0.09).asDiagonal();
  return d;
}

TEST(UsableDetections, KeepsTheFiniteWithAPositiveDefiniteCovarianceInTheirOrder) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Detection not_finite = At(nan, 1.0);
  Detection singular = At(2.0, 2.0);
  singular.covariance << 0.04, 0.06, 0.06, 0.09;  // determinant 0
  Detection asymmetric = At(3.0, 3.0);
  asymmetric.covariance(0, 1) = 0.01;
  Detection nan_covariance = At(4.0, 4.0);
  nan_covariance.covariance(1, 1) = nan;
  Detection correlated = At(5.0, -5.0);
  correlated.covariance << 0.04, 0.05, 0.05, 0.09;  // determinant 0.0011 > 0
  const std::vector<Detection> usable = UsableDetections(
      {At(1.0, 0.0), not_finite, singular, asymmetric, nan_covariance, correlated, At(6.0, 0.0)});
  ASSERT_EQ(usable.size(), 3u);
  EXPECT_EQ(usable[0].position_m, Eigen::Vector2d(1.0, 0.0));
  EXPECT_EQ(usable[1].position_m, Eigen::Vector2d(5.0, -5.0));
  EXPECT_EQ(usable[2].position_m, Eigen::Vector2d(6.0, 0.0));
  EXPECT_TRUE(UsableDetections({}).empty());
}

TEST(BirthState, TakesTheDetectionsVelocityWhereItIsSurerThanThePrior) {
  Detection d = At(3.0, -2.0);
  const Gaussian without = BirthState(d, 5.0);
  EXPECT_EQ(without.mean, Eigen::Vector4d(3.0, -2.0, 0.0, 0.0));
  EXPECT_EQ(without.cov.topLeftCorner(2, 2), d.covariance);
  EXPECT_EQ(without.cov.bottomRightCorner(2, 2), 25.0 * Eigen::Matrix2d::Identity());
  EXPECT_EQ(without.cov.topRightCorner(2, 2), Eigen::Matrix2d::Zero());

  // A camera car crossing at 10 m/s, its velocity known to 0.3 m/s.
  d.velocity_mps = Eigen::Vector2d(0.0, 10.0);
  d.velocity_covariance = 0.09 * Eigen::Matrix2d::Identity();
  const Gaussian with = BirthState(d, 5.0);
  EXPECT_EQ(with.mean, Eigen::Vector4d(3.0, -2.0, 0.0, 10.0));
  EXPECT_EQ(with.cov.bottomRightCorner(2, 2), d.velocity_covariance);
  EXPECT_EQ(with.cov.topLeftCorner(2, 2), d.covariance);

  // Looser than the prior (a walker's 1.5 m/s prior against 2 m/s): the prior.
  d.velocity_covariance = 4.0 * Eigen::Matrix2d::Identity();
  EXPECT_EQ(BirthState(d, 1.5).mean.tail(2), Eigen::Vector2d::Zero());
  // Unusable: not positive definite, not finite.
  d.velocity_covariance << 0.09, 0.2, 0.2, 0.09;
  EXPECT_EQ(BirthState(d, 5.0).mean.tail(2), Eigen::Vector2d::Zero());
  d.velocity_covariance = 0.09 * Eigen::Matrix2d::Identity();
  d.velocity_mps = Eigen::Vector2d(std::numeric_limits<double>::quiet_NaN(), 1.0);
  EXPECT_EQ(BirthState(d, 5.0).mean.tail(2), Eigen::Vector2d::Zero());
  EXPECT_EQ(BirthState(d, 5.0).cov.bottomRightCorner(2, 2), 25.0 * Eigen::Matrix2d::Identity());
}

SeenPoint Seen(double t_s, double x, double y, double sigma_m = 0.03) {
  return {static_cast<TimeNs>(t_s * 1e9), Eigen::Vector2d(x, y),
          Eigen::Matrix2d::Identity() * sigma_m * sigma_m};
}

TEST(ThreePointVelocity, TheSeenPointsStepsGiveTheVelocityWhereTheyAgree) {
  // A car's front face crossing at 8 m/s, seen every 0.08 s to 3 cm.
  const std::vector<SeenPoint> car = {Seen(4.24, 21.7, -24.35), Seen(4.32, 21.7, -23.71),
                                      Seen(4.40, 21.7, -23.07)};
  const std::optional<Gaussian> v = ThreePointVelocity(car, 0.99);
  ASSERT_TRUE(v.has_value());
  EXPECT_LT((v->mean - Eigen::Vector2d(0.0, 8.0)).norm(), 1e-9);
  // (C1 + C3) / (t3 - t1)^2: 2 (0.03)^2 / 0.16^2.
  EXPECT_NEAR(v->cov(1, 1), 2.0 * 0.0009 / (0.16 * 0.16), 1e-12);
  EXPECT_NEAR(v->cov(0, 1), 0.0, 1e-12);

  // The third point on another piece of the body, 1.5 m along it: the steps disagree.
  std::vector<SeenPoint> pieces = car;
  pieces[2].point_m.x() += 1.5;
  EXPECT_FALSE(ThreePointVelocity(pieces, 0.99).has_value());
  // ... unless the points say they could be anywhere there (a 1 m sigma across).
  for (SeenPoint& p : pieces) p.covariance(0, 0) = 1.0;
  EXPECT_TRUE(ThreePointVelocity(pieces, 0.99).has_value());

  // Two points, or stamps not increasing: nothing.
  EXPECT_FALSE(ThreePointVelocity(std::vector<SeenPoint>{car[0], car[1]}, 0.99).has_value());
  EXPECT_FALSE(
      ThreePointVelocity(std::vector<SeenPoint>{car[0], car[2], car[1]}, 0.99).has_value());
}

TEST(ThreePointVelocity, ReplacesTheFiltersVelocityOnlyWhereSurer) {
  Gaussian state{Eigen::Vector4d(1.0, 2.0, 0.5, 3.0), Eigen::Matrix4d::Identity() * 4.0};
  state.cov(0, 2) = state.cov(2, 0) = 1.0;
  const EarlySeenPoints car = {Seen(0.0, 0.0, 0.0), Seen(0.1, 0.0, 0.8), Seen(0.2, 0.0, 1.6)};
  const Gaussian seen = WithSeenVelocity(state, car, 0.99);
  EXPECT_EQ(seen.mean.head(2), state.mean.head(2));
  EXPECT_LT((seen.mean.tail(2) - Eigen::Vector2d(0.0, 8.0)).norm(), 1e-9);
  EXPECT_EQ(seen.cov(0, 2), 0.0) << "the velocity is the points', not the filter's";
  EXPECT_EQ(seen.cov.topLeftCorner(2, 2), state.cov.topLeftCorner(2, 2));
  // Off, or the filter surer already: unchanged.
  EXPECT_EQ(WithSeenVelocity(state, car, 0.0).mean, state.mean);
  Gaussian sure = state;
  sure.cov.bottomRightCorner(2, 2) = Eigen::Matrix2d::Identity() * 1e-4;
  EXPECT_EQ(WithSeenVelocity(sure, car, 0.99).mean, sure.mean);
}

// An object of unknown class seen on one side: a cyclist's track measures the cyclist's centre
// behind it, a track of unknown class (or a walker's, for which none is given) the detection's
// own; a detection whose class is known, or whose class centre is unusable, gives its own.
TEST(MeasurementFor, ATrackOfKnownClassMeasuresItsClasssCentre) {
  Detection d = At(11.0, 4.0);  // half a car's depth behind the side at x = 10
  ClassCentre cyclist{Eigen::Vector2d(10.3, 4.0), 0.01 * Eigen::Matrix2d::Identity()};
  d.class_centres[static_cast<std::size_t>(ObjectClass::kCyclist)] = cyclist;
  EXPECT_EQ(MeasurementFor(d, ObjectClass::kCyclist).position_m, cyclist.position_m);
  EXPECT_EQ(MeasurementFor(d, ObjectClass::kCyclist).covariance, cyclist.covariance);
  for (const ObjectClass c : {ObjectClass::kUnknown, ObjectClass::kPedestrian, ObjectClass::kCar}) {
    EXPECT_EQ(MeasurementFor(d, c).position_m, d.position_m);
    EXPECT_EQ(MeasurementFor(d, c).covariance, d.covariance);
  }
  Detection known = d;
  known.object_class = ObjectClass::kCar;
  EXPECT_EQ(MeasurementFor(known, ObjectClass::kCyclist).position_m, d.position_m);
  Detection unusable = d;
  unusable.class_centres[static_cast<std::size_t>(ObjectClass::kCyclist)]->covariance(1, 1) = -1.0;
  EXPECT_EQ(MeasurementFor(unusable, ObjectClass::kCyclist).position_m, d.position_m);
  unusable.class_centres[static_cast<std::size_t>(ObjectClass::kCyclist)] =
      ClassCentre{Eigen::Vector2d(std::numeric_limits<double>::quiet_NaN(), 4.0),
                  0.01 * Eigen::Matrix2d::Identity()};
  EXPECT_EQ(MeasurementFor(unusable, ObjectClass::kCyclist).position_m, d.position_m);
}

}  // namespace
}  // namespace lookout::tracking
