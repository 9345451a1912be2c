#include "lookout/risk/bicycle_model.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lookout::risk {
namespace {

// At constant speed and steering the model moves on a circle of radius R = L / tan(delta):
// the bound is 1e-6 m over 5 s at 0.1 s steps.
TEST(BicycleModelTest, ConstantSteeringFollowsTheClosedFormCircle) {
  constexpr double kWheelbase = 2.7, kSpeed = 8.0, kSteer = 0.12;
  const BicycleState start{1.0, -2.0, 0.3, kSpeed, kSteer};
  const auto states = PredictBicycle(start, {}, kWheelbase, 5.0, 0.1);
  ASSERT_EQ(states.size(), 51u);
  const double radius = kWheelbase / std::tan(kSteer);
  const double omega = kSpeed / radius;
  // Centre of the circle: to the left of the heading.
  const double cx = start.x_m - radius * std::sin(start.yaw_rad);
  const double cy = start.y_m + radius * std::cos(start.yaw_rad);
  double worst = 0.0;
  for (std::size_t k = 0; k < states.size(); ++k) {
    const double t = 0.1 * static_cast<double>(k);
    const double yaw = start.yaw_rad + omega * t;
    const double x = cx + radius * std::sin(yaw);
    const double y = cy - radius * std::cos(yaw);
    worst = std::max(worst, std::hypot(states[k].x_m - x, states[k].y_m - y));
    EXPECT_NEAR(states[k].yaw_rad, yaw, 1e-9);
  }
  EXPECT_LT(worst, 1e-6) << "worst position error " << worst << " m";
}

TEST(BicycleModelTest, StraightAtConstantAccelerationMatchesKinematics) {
  const auto states = PredictBicycle({0.0, 0.0, 0.0, 5.0, 0.0}, {1.5, 0.0}, 2.7, 4.0, 0.1);
  const BicycleState& last = states.back();
  EXPECT_NEAR(last.x_m, 5.0 * 4.0 + 0.5 * 1.5 * 16.0, 1e-9);
  EXPECT_NEAR(last.y_m, 0.0, 1e-12);
  EXPECT_NEAR(last.speed_mps, 11.0, 1e-9);
}

TEST(BicycleModelTest, BrakingVehicleStopsAndStays) {
  const auto states = PredictBicycle({0.0, 0.0, 0.0, 4.0, 0.0}, {-2.0, 0.0}, 2.7, 5.0, 0.1);
  EXPECT_EQ(states.back().speed_mps, 0.0);
  // Stopping distance v^2 / 2a = 4 m, within one step's travel of the RK4 clamp.
  EXPECT_NEAR(states.back().x_m, 4.0, 0.05);
  for (std::size_t k = 1; k < states.size(); ++k) EXPECT_GE(states[k].x_m, states[k - 1].x_m);
}

TEST(BicycleModelTest, SteeringFromYawRateInvertsTheModel) {
  constexpr double kWheelbase = 2.7;
  const double delta = SteeringFromYawRate(0.3, 10.0, kWheelbase);
  const BicycleState d = BicycleDerivative({0.0, 0.0, 0.0, 10.0, delta}, {}, kWheelbase);
  EXPECT_NEAR(d.yaw_rad, 0.3, 1e-12);
  EXPECT_EQ(SteeringFromYawRate(0.3, 0.05, kWheelbase), 0.0);
}

}  // namespace
}  // namespace lookout::risk
