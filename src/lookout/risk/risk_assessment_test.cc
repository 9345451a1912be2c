#include "lookout/risk/risk_assessment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "lookout/core/input_error.h"
#include "lookout/risk/warning_levels.h"

namespace lookout::risk {
namespace {

RiskOptions NoGrowth() {
  RiskOptions o;
  o.growth_per_metre = 0.0;
  o.covariance_sigmas = 0.0;
  return o;
}

ObjectInput Object(ObjectClass c, Eigen::Vector2d position, Eigen::Vector2d velocity) {
  ObjectInput o;
  o.object_class = c;
  o.position_m = position;
  o.velocity_mps = velocity;
  return o;
}

// The paper's pedestrian: a circle at the detected position, radius r0 + speed * t.
TEST(RiskAssessmentTest, PedestrianCircleGrowsWithItsSpeed) {
  RiskOptions o = NoGrowth();
  o.pedestrian_model = PedestrianModel::kGrowingCircle;
  const ObjectInput p = Object(ObjectClass::kPedestrian, {3.0, 4.0}, {0.0, 1.5});
  const FootprintTrack t = PredictObject(p, o);
  ASSERT_EQ(t.size(), 51u);
  for (std::size_t k = 0; k < t.size(); ++k) {
    EXPECT_EQ(t[k].centre_m, p.position_m) << "no direction is assumed";
    EXPECT_EQ(t[k].half_length_m, 0.0);
    EXPECT_NEAR(t[k].radius_m, 0.3 + 1.5 * 0.1 * static_cast<double>(k), 1e-12);
  }
}

// The default: along its velocity, its own radius throughout.
TEST(RiskAssessmentTest, PedestrianWalksAlongItsVelocity) {
  const ObjectInput p = Object(ObjectClass::kPedestrian, {3.0, 4.0}, {0.0, 1.5});
  const FootprintTrack t = PredictObject(p, NoGrowth());
  ASSERT_EQ(t.size(), 51u);
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double time = 0.1 * static_cast<double>(k);
    EXPECT_NEAR((t[k].centre_m - Eigen::Vector2d(3.0, 4.0 + 1.5 * time)).norm(), 0.0, 1e-12);
    EXPECT_EQ(t[k].radius_m, 0.3);
  }
}

// A car coming head-on in the ego's lane: TTC = gap / closing speed, between the boxes' fronts
// (the default) or between the circles of half their diagonals (the paper).
TEST(RiskAssessmentTest, HeadOnCarTtcIsGapOverClosingSpeed) {
  RiskOptions o = NoGrowth();
  EgoInput ego;
  ego.speed_mps = 10.0;
  ObjectInput car = Object(ObjectClass::kCar, {60.0, 0.0}, {-10.0, 0.0});
  car.id = 7;
  const RiskAssessment boxes = AssessRisk(ego, {car}, o);
  ASSERT_TRUE(boxes.earliest.has_value());
  const double box_ttc = (60.0 - 0.5 * o.ego_length_m - 0.5 * o.footprints.car_length_m) / 20.0;
  EXPECT_NEAR(*boxes.objects[*boxes.earliest].ttc_s, box_ttc, 1e-9);
  EXPECT_DOUBLE_EQ(boxes.risk, RiskIndicator(box_ttc, o));
  EXPECT_EQ(boxes.objects[0].id, 7u);

  o.shape = CollisionShape::kCircles;
  const RiskAssessment circles = AssessRisk(ego, {car}, o);
  ASSERT_TRUE(circles.earliest.has_value());
  const double reach = 0.5 * std::hypot(o.ego_length_m, o.ego_width_m) +
                       0.5 * std::hypot(o.footprints.car_length_m, o.footprints.car_width_m);
  EXPECT_NEAR(*circles.objects[0].ttc_s, (60.0 - reach) / 20.0, 1e-9);
}

// An unknown object as fast as a car is predicted as one: head on at 10 m/s its TTC is the
// box gap's, as a car's; at 5 m/s it stays a circle of unknown_radius_m moving straight.
TEST(RiskAssessmentTest, AnUnknownObjectAsFastAsACarIsPredictedAsOne) {
  const RiskOptions o = NoGrowth();
  EgoInput ego;
  ego.speed_mps = 10.0;
  const ObjectInput fast = Object(ObjectClass::kUnknown, {60.0, 0.0}, {-10.0, 0.0});
  const RiskAssessment as_car = AssessRisk(ego, {fast}, o);
  ASSERT_TRUE(as_car.earliest.has_value());
  EXPECT_NEAR(*as_car.objects[0].ttc_s,
              (60.0 - 0.5 * o.ego_length_m - 0.5 * o.footprints.car_length_m) / 20.0, 1e-9);
  const ObjectInput slow = Object(ObjectClass::kUnknown, {60.0, 0.0}, {-5.0, 0.0});
  const RiskAssessment round = AssessRisk(ego, {slow}, o);
  ASSERT_TRUE(round.earliest.has_value());
  // The circle meets the ego's box at its front: gap 60 - half the ego's length - the radius,
  // closed at 15 m/s, to the 0.1 s step the collision search resolves.
  const double circle_ttc = (60.0 - 0.5 * o.ego_length_m - o.unknown_radius_m) / 15.0;
  EXPECT_NEAR(*round.objects[0].ttc_s, circle_ttc, o.step_s);
  // With the option at infinity the fast one stays round too.
  RiskOptions never = o;
  never.unknown_as_car_speed_mps = std::numeric_limits<double>::infinity();
  const RiskAssessment kept_round = AssessRisk(ego, {fast}, never);
  ASSERT_TRUE(kept_round.earliest.has_value());
  EXPECT_NEAR(*kept_round.objects[0].ttc_s,
              (60.0 - 0.5 * o.ego_length_m - o.unknown_radius_m) / 20.0, o.step_s);
}

// The circles' false alarm: a car passing in the next lane (3.5 m between the lanes' centres,
// 1.65 m between the sides). Boxes see no collision; circles of half the diagonals do.
TEST(RiskAssessmentTest, BoxesLetACarPassInTheNextLane) {
  RiskOptions o = NoGrowth();
  EgoInput ego;
  ego.speed_mps = 10.0;
  const ObjectInput car = Object(ObjectClass::kCar, {60.0, 3.5}, {-20.0, 0.0});
  EXPECT_FALSE(AssessRisk(ego, {car}, o).earliest.has_value());
  o.shape = CollisionShape::kCircles;
  EXPECT_TRUE(AssessRisk(ego, {car}, o).earliest.has_value());
}

// A vehicle too slow for its velocity to give a heading is a circle covering every
// orientation; with a heading known otherwise (a true state) it is its box.
TEST(RiskAssessmentTest, AVehicleWithoutHeadingIsACircle) {
  const RiskOptions o = NoGrowth();
  ObjectInput parked = Object(ObjectClass::kCar, {10.0, 5.0}, {0.2, 0.0});
  const FootprintTrack circle = PredictObject(parked, o);
  EXPECT_EQ(circle[0].half_length_m, 0.0);
  EXPECT_NEAR(circle[0].radius_m, 0.5 * std::hypot(4.5, 1.8), 1e-12);
  parked.yaw_rad = std::numbers::pi / 2.0;
  const FootprintTrack box = PredictObject(parked, o);
  EXPECT_EQ(box[0].half_length_m, 2.25);
  EXPECT_EQ(box[0].yaw_rad, std::numbers::pi / 2.0);
}

// The ego along a route turns with it: its box follows the route's direction.
TEST(RiskAssessmentTest, TheEgoBoxFollowsItsRoute) {
  EgoInput ego;
  ego.speed_mps = 5.0;
  ego.route_m = {{0.0, 0.0}, {10.0, 0.0}, {10.0, -30.0}};
  const FootprintTrack t = PredictEgo(ego, NoGrowth());
  EXPECT_NEAR(t[0].yaw_rad, 0.0, 1e-12);
  EXPECT_NEAR(t.back().yaw_rad, -std::numbers::pi / 2.0, 1e-9);  // 25 m along: southbound
  EXPECT_NEAR(t.back().centre_m.x(), 10.0, 1e-9);
  EXPECT_NEAR(t.back().centre_m.y(), -15.0, 1e-9);
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
  const ObjectInput far_car = Object(ObjectClass::kCar, {80.0, 0.0}, {-10.0, 0.0});
  // Steps into the ego's lane: in it when the ego's front arrives at 1.74 s.
  const ObjectInput near_walker = Object(ObjectClass::kPedestrian, {20.0, 2.0}, {0.0, -1.0});
  // Slower than the ego: never catches up.
  const ObjectInput behind = Object(ObjectClass::kCar, {-30.0, 0.0}, {5.0, 0.0});
  const RiskAssessment a = AssessRisk(ego, {far_car, near_walker, behind}, o);
  ASSERT_EQ(a.objects.size(), 3u);
  ASSERT_TRUE(a.earliest.has_value());
  EXPECT_EQ(*a.earliest, 1u);
  EXPECT_FALSE(a.objects[2].ttc_s.has_value());
}

TEST(RiskAssessmentTest, BadTracksAreDroppedAndCounted) {
  const RiskOptions o;
  ObjectInput nan_position, not_psd, nan_yaw, fine;
  nan_position.position_m = {std::numeric_limits<double>::quiet_NaN(), 0.0};
  not_psd.position_covariance << 1.0, 2.0, 2.0, 1.0;  // eigenvalues 3 and -1
  nan_yaw.yaw_rad = std::numeric_limits<double>::infinity();
  fine.position_m = {10.0, 10.0};
  const RiskAssessment a = AssessRisk(EgoInput{}, {nan_position, not_psd, nan_yaw, fine}, o);
  EXPECT_EQ(a.dropped, 3u);
  EXPECT_EQ(a.objects.size(), 1u);
}

TEST(RiskAssessmentTest, BadOptionsAreRefusedNamingTheField) {
  RiskOptions o;
  o.wheelbase_m = 0.0;
  try {
    o.Validate("test.yaml");
    FAIL() << "a zero wheelbase was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wheelbase_m"), std::string::npos) << e.what();
  }
  o = RiskOptions{};
  o.ego_width_m = -1.0;
  EXPECT_THROW(o.Validate(), InputError);
  o = RiskOptions{};
  o.pedestrian_intent_sigma_mps = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(o.Validate(), InputError);
  EXPECT_EQ(ParseCollisionShape("boxes"), CollisionShape::kBoxes);
  EXPECT_EQ(ParsePedestrianModel("growing-circle"), PedestrianModel::kGrowingCircle);
  EXPECT_FALSE(ParseCollisionShape("spheres").has_value());
}

// Uncertainty widens the footprints: a car passing 3 m to the side (1.15 m between the boxes)
// is no collision with an exact track, and becomes one when its position is uncertain enough.
TEST(RiskAssessmentTest, PositionUncertaintyWidensTheFootprints) {
  RiskOptions o = NoGrowth();
  EgoInput ego;
  ego.speed_mps = 10.0;
  ObjectInput car = Object(ObjectClass::kCar, {60.0, 3.0}, {-10.0, 0.0});
  EXPECT_FALSE(AssessRisk(ego, {car}, o).earliest.has_value());
  o.covariance_sigmas = 2.0;
  car.position_covariance = Eigen::Matrix2d::Identity() * 0.36;  // 0.6 m sigma: 1.2 m margin
  EXPECT_TRUE(AssessRisk(ego, {car}, o).earliest.has_value());
}

// A car whose lateral position is uncertain, passing 2.5 m beside the ego's path: the collision
// probability is the chance its lateral offset brings the boxes together, and it rises with the
// uncertainty; the post-encroachment time of a head-on collision is 0.
TEST(RiskAssessmentTest, ProbabilityRisesWithUncertainty) {
  RiskOptions o = NoGrowth();
  o.seed = 3;
  EgoInput ego;
  ego.speed_mps = 10.0;
  ObjectInput car = Object(ObjectClass::kCar, {60.0, 2.5}, {-10.0, 0.0});
  car.yaw_rad = std::numbers::pi;
  double previous = -1.0;
  for (const double sigma : {0.1, 0.5, 1.0, 2.0}) {
    car.position_covariance = Eigen::Matrix2d::Identity() * sigma * sigma;
    const RiskAssessment a = AssessRisk(ego, {car}, o);
    ASSERT_EQ(a.objects.size(), 1u);
    EXPECT_GT(a.objects[0].collision_probability, previous) << "sigma " << sigma;
    previous = a.objects[0].collision_probability;
  }
  // sigma 2 m, the boxes' half-widths 0.95 + 0.9 m, offset 2.5 m: P(dy < -0.65 m) = Phi(-0.325).
  EXPECT_NEAR(previous, 0.5 * std::erfc(0.325 / std::sqrt(2.0)), 0.05);

  car.position_m = {60.0, 0.0};
  car.position_covariance.setZero();
  const RiskAssessment head_on = AssessRisk(ego, {car}, o);
  ASSERT_TRUE(head_on.objects[0].pet_s.has_value());
  EXPECT_EQ(*head_on.objects[0].pet_s, 0.0);
  EXPECT_EQ(head_on.objects[0].collision_probability, 1.0);
}

// The waiting ego and a walker passing along its side, 1.7 m clear (the crowd scenario's
// sidewalk): the paper's growing circle reaches the ego within 3 s and warns; walking along its
// velocity, the walker's likeliest path never meets the ego and the chance that it turns into
// it is small. A walker heading for the ego's side is warned of under both.
TEST(RiskAssessmentTest, AWalkerPassingAWaitingCarIsNoWarning) {
  const EgoInput ego;  // standing at the origin, facing east
  const WarningOptions w;
  const ObjectInput passing = Object(ObjectClass::kPedestrian, {6.0, -2.95}, {-1.4, 0.0});
  const ObjectInput towards = Object(ObjectClass::kPedestrian, {1.0, -4.2}, {0.0, 1.4});
  RiskOptions paper = NoGrowth();
  paper.pedestrian_model = PedestrianModel::kGrowingCircle;
  EXPECT_EQ(LevelsOf(AssessRisk(ego, {passing}, paper), w).entered, WarningLevel::kWarning);
  EXPECT_EQ(LevelsOf(AssessRisk(ego, {towards}, paper), w).entered, WarningLevel::kWarning);

  const RiskOptions o = NoGrowth();
  const RiskAssessment pass = AssessRisk(ego, {passing}, o);
  EXPECT_FALSE(pass.objects[0].ttc_s.has_value());
  EXPECT_GT(pass.objects[0].collision_probability, 0.0) << "a walker may turn";
  EXPECT_LT(pass.objects[0].collision_probability, w.warning_probability_enter);
  EXPECT_EQ(LevelsOf(pass, w).entered, WarningLevel::kNone);
  const RiskAssessment head = AssessRisk(ego, {towards}, o);
  ASSERT_TRUE(head.objects[0].ttc_s.has_value());
  EXPECT_NEAR(*head.objects[0].ttc_s, (4.2 - 0.95 - 0.3) / 1.4, 1e-9);
  EXPECT_GT(head.objects[0].collision_probability, w.warning_probability_enter);
  EXPECT_EQ(LevelsOf(head, w).entered, WarningLevel::kWarning);
  // Without the walker's own freedom the passing walker's probability is exactly 0.
  RiskOptions rigid = o;
  rigid.pedestrian_intent_sigma_mps = 0.0;
  EXPECT_EQ(AssessRisk(ego, {passing}, rigid).objects[0].collision_probability, 0.0);
}

// A walker on the sidewalk heading into the ego's lane: with the map, its collision
// probability is weighted by the chance that it steps off the kerb; a walker the map puts on
// the road, and a car where the walker is, keep theirs; the TTC (the likeliest future's) is the
// same with the map and without.
TEST(RiskAssessmentTest, AWalkerOnTheSidewalkMayWaitAtTheKerb) {
  const RiskOptions o;  // sampling on, kerb_step_off_probability 0.5
  EgoInput ego;         // at the origin, east at 8 m/s
  ego.speed_mps = 8.0;
  ObjectInput walker = Object(ObjectClass::kPedestrian, {20.0, -4.5}, {0.0, 1.5});
  walker.position_covariance = 0.01 * Eigen::Matrix2d::Identity();
  walker.velocity_covariance = 0.01 * Eigen::Matrix2d::Identity();
  const RiskAssessment free = AssessRisk(ego, {walker}, o);
  ASSERT_EQ(free.objects.size(), 1u);
  ASSERT_TRUE(free.objects[0].ttc_s);
  ASSERT_GT(free.objects[0].collision_probability, 0.5) << "without a map it would warn";

  EgoInput mapped = ego;
  mapped.carriageways_m = {Footprint::Box({0.0, 0.0}, 0.0, 200.0, 7.0)};  // kerbs at y = +-3.5
  const RiskAssessment kerb = AssessRisk(mapped, {walker}, o);
  EXPECT_DOUBLE_EQ(kerb.objects[0].collision_probability,
                   o.kerb_step_off_probability * free.objects[0].collision_probability);
  EXPECT_EQ(kerb.objects[0].ttc_s, free.objects[0].ttc_s);

  EgoInput wide = ego;  // a road 10 m wide: the walker is on it
  wide.carriageways_m = {Footprint::Box({0.0, 0.0}, 0.0, 200.0, 10.0)};
  EXPECT_DOUBLE_EQ(AssessRisk(wide, {walker}, o).objects[0].collision_probability,
                   free.objects[0].collision_probability);

  ObjectInput car = walker;
  car.object_class = ObjectClass::kCar;
  EXPECT_DOUBLE_EQ(AssessRisk(mapped, {car}, o).objects[0].collision_probability,
                   AssessRisk(ego, {car}, o).objects[0].collision_probability);

  RiskOptions bad;
  bad.kerb_step_off_probability = 1.5;
  EXPECT_THROW(bad.Validate(), InputError);
}

// Left turn across the path: the ego drives east in its lane (y = -1.75), an oncoming car
// (west at 8 m/s in y = 1.75, 20 m from the junction) passes it in the next lane when it goes
// straight on, and crosses its path in 1.5-2.4 s if it turns left (the arc of 12.8 m,
// turn_hypotheses_test.cc, reaches the middle of the ego's lane at x = 2.3 after 2.33 s, when
// the ego's centre is at x = 1). With the junction's map the left turn is a hypothesis of weight
// 0.5 (the right turn is too tight at 8 m/s; straight on and left share the third it leaves), and
// the most dangerous: its figures are the object's. Without the map, or at 20 m/s (no turn), only
// straight on: no collision.
TEST(RiskAssessmentTest, AnOncomingCarMayTurnAcrossThePath) {
  const RiskOptions o;
  EgoInput ego;
  ego.position_m = {-22.3, -1.75};
  ego.speed_mps = 10.0;
  ObjectInput car = Object(ObjectClass::kCar, {20.0, 1.75}, {-8.0, 0.0});
  const RiskAssessment straight = AssessRisk(ego, {car}, o);
  EXPECT_FALSE(straight.objects[0].ttc_s.has_value());

  ego.carriageways_m = {Footprint::Box({0.0, 0.0}, 0.0, 120.0, 7.0),
                        Footprint::Box({0.0, 0.0}, 0.5 * std::numbers::pi, 120.0, 7.0)};
  const ObjectRisk turning = AssessRisk(ego, {car}, o).objects.at(0);
  EXPECT_EQ(turning.manoeuvre, Manoeuvre::kLeftTurn);
  EXPECT_NEAR(turning.manoeuvre_weight, 0.5, 1e-12);
  ASSERT_TRUE(turning.ttc_s.has_value());
  EXPECT_GT(*turning.ttc_s, 1.5);
  EXPECT_LT(*turning.ttc_s, 2.4);
  EXPECT_EQ(turning.collision_probability, 1.0) << "no covariance: every sample hits";

  RiskOptions off = o;
  off.turn_hypotheses = false;
  EXPECT_FALSE(AssessRisk(ego, {car}, off).objects[0].ttc_s.has_value());

  ObjectInput fast = Object(ObjectClass::kCar, {40.0, 1.75}, {-20.0, 0.0});
  const ObjectRisk passing = AssessRisk(ego, {fast}, o).objects.at(0);
  EXPECT_EQ(passing.manoeuvre, Manoeuvre::kStraight);
  EXPECT_EQ(passing.manoeuvre_weight, 1.0);
  EXPECT_FALSE(passing.ttc_s.has_value());

  RiskOptions bad;
  bad.turn_right_prior = 0.9;  // with the left's third, over 1
  EXPECT_THROW(bad.Validate(), InputError);
}

}  // namespace
}  // namespace lookout::risk
