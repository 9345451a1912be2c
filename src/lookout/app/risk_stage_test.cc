#include "lookout/app/risk_stage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lookout/core/input_error.h"

namespace lookout::app {
namespace {

// Odometry at 50 Hz of an ego accelerating at 1.5 m/s^2 from 4 m/s: the window's line gives
// the acceleration and the speed at the stamp exactly (no noise), from the readings up to it.
TEST(InterpretEgoTest, AccelerationIsTheSlopeOfTheOdometrySpeed) {
  std::deque<EgoOdometry> odometry;
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.02 * k;
    odometry.push_back({FromSeconds(t), 4.0 + 1.5 * t, 0.1});
  }
  const risk::EgoInput ego = InterpretEgo(FromSeconds(1.0), Pose2(3.0, 4.0, 0.5), odometry, 0.5);
  EXPECT_NEAR(ego.acceleration_mps2, 1.5, 1e-9);
  EXPECT_NEAR(ego.speed_mps, 5.5, 1e-9);
  EXPECT_NEAR(ego.yaw_rate_radps, 0.1, 1e-12);
  EXPECT_EQ(ego.position_m, Eigen::Vector2d(3.0, 4.0));
  EXPECT_EQ(ego.yaw_rad, 0.5);
  // Without odometry the ego is known by its pose only.
  const risk::EgoInput still = InterpretEgo(FromSeconds(1.0), Pose2(), {}, 0.5);
  EXPECT_EQ(still.speed_mps, 0.0);
}

tracking::Track TrackAt(std::uint32_t id, ObjectClass c, Eigen::Vector2d p, Eigen::Vector2d v) {
  tracking::Track t;
  t.id = id;
  t.status = tracking::TrackStatus::kConfirmed;
  t.object_class = c;
  t.state.mean = Eigen::Vector4d(p.x(), p.y(), v.x(), v.y());
  t.state.cov = 0.01 * Eigen::MatrixXd::Identity(4, 4);
  return t;
}

// Head-on in the ego's lane: the gap between the boxes' fronts (2.3 + 2.25 m from the centres,
// 40 m apart) closes at 20 m/s, TTC 1.7725 s, under the reaction time: a warning naming the car
// at once; a car that turned away lets it fall after the hold time. A NaN track is dropped and
// counted.
TEST(RiskStageTest, WarnsOfAHeadOnCarAndNamesIt) {
  RiskStageOptions options;
  options.risk.growth_per_metre = 0.0;
  options.risk.covariance_sigmas = 0.0;
  options.risk.collision_samples = 0;
  options.ego_prediction = EgoPrediction::kHeading;
  RiskStage stage(options);
  for (int k = 0; k <= 25; ++k) stage.OnOdometry({FromSeconds(0.02 * k), 10.0, 0.0});
  tracking::Track nan = TrackAt(9, ObjectClass::kCar, {5.0, 5.0}, {0.0, 0.0});
  nan.state.mean(0) = std::numeric_limits<double>::quiet_NaN();
  stage.Step(FromSeconds(0.5), Pose2(),
             {TrackAt(4, ObjectClass::kCar, {40.0, 0.0}, {-10.0, 0.0}), nan});
  EXPECT_EQ(stage.dropped_tracks(), 1);
  ASSERT_EQ(stage.events().size(), 1u);
  const risk::WarningEvent& e = stage.events()[0];
  EXPECT_EQ(e.level, risk::WarningLevel::kWarning);
  EXPECT_EQ(e.object_id, 4u);
  ASSERT_TRUE(e.ttc_s.has_value());
  EXPECT_NEAR(*e.ttc_s, (40.0 - 2.3 - 2.25) / 20.0, 1e-9);
  EXPECT_NEAR(stage.last_ego().speed_mps, 10.0, 1e-9);

  const tracking::Track away = TrackAt(4, ObjectClass::kCar, {40.0, 30.0}, {0.0, 10.0});
  stage.Step(FromSeconds(0.6), Pose2(), {away});
  EXPECT_EQ(stage.level(), risk::WarningLevel::kWarning) << "held through the hold time";
  stage.Step(FromSeconds(0.4), Pose2(), {away});  // time going backwards: ignored
  EXPECT_EQ(stage.refused_steps(), 1);
  stage.Step(FromSeconds(1.2), Pose2(), {away});
  EXPECT_EQ(stage.level(), risk::WarningLevel::kNone);
  EXPECT_EQ(stage.events().size(), 2u);
}

// The right hook: the ego at 6 m/s, 15 m before a corner where its route turns right; a cyclist
// 4 m to its right rides on straight at 6 m/s (its box 2.75 m from the ego's side by side).
// From the ego's heading there is no collision; along the route there is, about 2.5 s ahead.
TEST(RiskStageTest, TheRouteShowsTheTurnThatTheHeadingCannot) {
  const std::vector<tracking::Track> cyclist = {
      TrackAt(1, ObjectClass::kCyclist, {0.0, -4.0}, {6.0, 0.0})};
  auto ttc = [&](EgoPrediction prediction) -> std::optional<double> {
    RiskStageOptions options;
    options.ego_prediction = prediction;
    options.risk.collision_samples = 0;
    options.risk.growth_per_metre = 0.0;
    options.risk.covariance_sigmas = 0.0;
    RiskStage stage(options);
    stage.SetRoute({{-20.0, 0.0}, {15.0, 0.0}, {15.0, -30.0}});
    for (int k = 0; k <= 25; ++k) stage.OnOdometry({FromSeconds(0.02 * k), 6.0, 0.0});
    stage.Step(FromSeconds(0.5), Pose2(), cyclist);
    return stage.last_assessment().objects.at(0).ttc_s;
  };
  EXPECT_FALSE(ttc(EgoPrediction::kHeading).has_value());
  const auto along_route = ttc(EgoPrediction::kRoute);
  ASSERT_TRUE(along_route.has_value());
  EXPECT_GT(*along_route, 2.0);
  EXPECT_LT(*along_route, 3.2);
}

TEST(RiskStageTest, RefusesBadOptionsAndRoutes) {
  RiskStageOptions options;
  options.risk.wheelbase_m = 0.0;
  EXPECT_THROW(RiskStage{options}, InputError);
  RiskStage stage;
  EXPECT_THROW(stage.SetRoute({{0.0, std::numeric_limits<double>::infinity()}}), InputError);
  EXPECT_EQ(ParseEgoPrediction("yaw-rate"), EgoPrediction::kYawRate);
  EXPECT_FALSE(ParseEgoPrediction("sideways").has_value());
}

}  // namespace
}  // namespace lookout::app
