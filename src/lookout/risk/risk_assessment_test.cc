#include "lookout/risk/risk_assessment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lookout/core/input_error.h"

namespace lookout::risk {
namespace {

RiskOptions NoGrowth() {
  RiskOptions o;
  o.growth_per_metre = 0.0;
  o.covariance_sigmas = 0.0;
  return o;
}

// The paper's pedestrian: a circle at the detected position, radius r0 + speed * t.
TEST(RiskAssessmentTest, PedestrianCircleGrowsWithItsSpeed) {
  ObjectInput p;
  p.object_class = ObjectClass::kPedestrian;
  p.position_m = {3.0, 4.0};
  p.velocity_mps = {0.0, 1.5};
  const RiskOptions o = NoGrowth();
  const CircleTrack t = PredictObject(p, o);
  ASSERT_EQ(t.radius_m.size(), 51u);
  for (std::size_t k = 0; k < t.radius_m.size(); ++k) {
    EXPECT_EQ(t.centre_m[k], p.position_m) << "no direction is assumed";
    EXPECT_NEAR(t.radius_m[k], 0.3 + 1.5 * 0.1 * static_cast<double>(k), 1e-12);
  }
}

// A car coming head-on in the ego's lane: TTC = gap between the circles / closing speed.
TEST(RiskAssessmentTest, HeadOnCarTtcIsGapOverClosingSpeed) {
  const RiskOptions o = NoGrowth();
  EgoInput ego;
  ego.speed_mps = 10.0;
  ObjectInput car;
  car.id = 7;
  car.object_class = ObjectClass::kCar;
  car.position_m = {60.0, 0.0};
  car.velocity_mps = {-10.0, 0.0};
  const RiskAssessment a = AssessRisk(ego, {car}, o);
  ASSERT_TRUE(a.earliest.has_value());
  const double expected = (60.0 - o.ego_radius_m - o.car_radius_m) / 20.0;
  EXPECT_NEAR(*a.objects[*a.earliest].ttc_s, expected, 1e-9);
  EXPECT_DOUBLE_EQ(a.risk, RiskIndicator(expected, o));
}

TEST(RiskAssessmentTest, IndicatorFollowsTheReactionTime) {
  const RiskOptions o;
  EXPECT_EQ(RiskIndicator(std::nullopt, o), 0.0);
  EXPECT_EQ(RiskIndicator(0.5, o), 1.0);
  EXPECT_EQ(RiskIndicator(2.0, o), 1.0);
  EXPECT_NEAR(RiskIndicator(3.5, o), 0.5, 1e-12);
  EXPECT_EQ(RiskIndicator(5.0, o), 0.0);
}

TEST(RiskAssessmentTest, EarliestCollisionDecides) {
  const RiskOptions o = NoGrowth();
  EgoInput ego;
  ego.speed_mps = 10.0;
  ObjectInput far_car, near_walker, behind;
  far_car.object_class = ObjectClass::kCar;
  far_car.position_m = {80.0, 0.0};
  far_car.velocity_mps = {-10.0, 0.0};
  near_walker.object_class = ObjectClass::kPedestrian;
  near_walker.position_m = {20.0, 3.0};
  near_walker.velocity_mps = {0.0, -1.0};
  behind.object_class = ObjectClass::kCar;
  behind.position_m = {-30.0, 0.0};
  behind.velocity_mps = {5.0, 0.0};  // slower than the ego: never catches up
  const RiskAssessment a = AssessRisk(ego, {far_car, near_walker, behind}, o);
  ASSERT_EQ(a.objects.size(), 3u);
  ASSERT_TRUE(a.earliest.has_value());
  EXPECT_EQ(*a.earliest, 1u);
  EXPECT_FALSE(a.objects[2].ttc_s.has_value());
}

TEST(RiskAssessmentTest, BadTracksAreDroppedAndCounted) {
  const RiskOptions o;
  ObjectInput nan_position, not_psd, fine;
  nan_position.position_m = {std::numeric_limits<double>::quiet_NaN(), 0.0};
  not_psd.position_covariance << 1.0, 2.0, 2.0, 1.0;  // eigenvalues 3 and -1
  fine.position_m = {10.0, 10.0};
  const RiskAssessment a = AssessRisk(EgoInput{}, {nan_position, not_psd, fine}, o);
  EXPECT_EQ(a.dropped, 2u);
  EXPECT_EQ(a.objects.size(), 1u);
}

TEST(RiskAssessmentTest, ZeroWheelbaseIsRefused) {
  RiskOptions o;
  o.wheelbase_m = 0.0;
  try {
    o.Validate("test.yaml");
    FAIL() << "a zero wheelbase was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wheelbase_m"), std::string::npos) << e.what();
  }
}

// Uncertainty widens the circles: a car passing 5 m to the side is no collision with exact
// tracks, and becomes one when its position is uncertain enough.
TEST(RiskAssessmentTest, PositionUncertaintyWidensTheCircles) {
  RiskOptions o = NoGrowth();
  EgoInput ego;
  ego.speed_mps = 10.0;
  ObjectInput car;
  car.object_class = ObjectClass::kCar;
  car.position_m = {60.0, 5.2};
  car.velocity_mps = {-10.0, 0.0};
  EXPECT_FALSE(AssessRisk(ego, {car}, o).earliest.has_value());
  o.covariance_sigmas = 2.0;
  car.position_covariance = Eigen::Matrix2d::Identity() * 0.25;  // 0.5 m sigma: +1 m radius
  EXPECT_TRUE(AssessRisk(ego, {car}, o).earliest.has_value());
}

}  // namespace
}  // namespace lookout::risk

namespace lookout::risk {
namespace {

// A car whose lateral position is uncertain, passing 4 m beside the ego's path: the collision
// probability is the chance its lateral offset brings the circles within reach, and it rises
// with the uncertainty; the post-encroachment time of a head-on collision is 0.
TEST(RiskAssessmentTest, ProbabilityRisesWithUncertainty) {
  RiskOptions o = NoGrowth();
  o.seed = 3;
  EgoInput ego;
  ego.speed_mps = 10.0;
  ObjectInput car;
  car.object_class = ObjectClass::kCar;
  car.position_m = {60.0, 5.5};
  car.velocity_mps = {-10.0, 0.0};
  double previous = -1.0;
  for (const double sigma : {0.1, 0.5, 1.0, 2.0}) {
    car.position_covariance = Eigen::Matrix2d::Identity() * sigma * sigma;
    const RiskAssessment a = AssessRisk(ego, {car}, o);
    ASSERT_EQ(a.objects.size(), 1u);
    EXPECT_GT(a.objects[0].collision_probability, previous) << "sigma " << sigma;
    previous = a.objects[0].collision_probability;
  }
  // sigma 2 m, reach 4.84 m, offset 5.5 m: P(dy < -0.66 m) = Phi(-0.33), about 0.37.
  EXPECT_NEAR(previous, 0.5 * std::erfc(0.33 / std::sqrt(2.0)), 0.05);

  car.position_m = {60.0, 0.0};
  car.position_covariance.setZero();
  const RiskAssessment head_on = AssessRisk(ego, {car}, o);
  ASSERT_TRUE(head_on.objects[0].pet_s.has_value());
  EXPECT_EQ(*head_on.objects[0].pet_s, 0.0);
  EXPECT_EQ(head_on.objects[0].collision_probability, 1.0);
}

}  // namespace
}  // namespace lookout::risk
