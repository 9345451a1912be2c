#pragma once

// The kinematic bicycle model of seed 004 section VIII.B: a vehicle's trajectory predicted from
// its current state with acceleration and steering-rate inputs held constant, integrated with the
// classical 4th-order Runge-Kutta method.
//
// State (x, y, yaw, v, delta) of the point whose velocity lies along the heading (the
// simulator's no-slip point, sim/trajectory.h):
//   x' = v cos(yaw),  y' = v sin(yaw),  yaw' = v tan(delta) / L,  v' = a,  delta' = delta_rate
// with L the wheelbase. The paper holds speed and heading (a = 0, delta = 0); Lookout holds the
// current estimate of acceleration and steering (constant yaw rate) as an option (RiskOptions).

#include <vector>

namespace lookout::risk {

struct BicycleState {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
  double speed_mps = 0.0;
  double steering_rad = 0.0;  // front-wheel angle
};

struct BicycleInputs {
  double acceleration_mps2 = 0.0;
  double steering_rate_radps = 0.0;
};

// The time derivative of `s` (pure).
BicycleState BicycleDerivative(const BicycleState& s, const BicycleInputs& u, double wheelbase_m);

// One RK4 step of dt_s (pure). The speed is not clamped at zero: callers that predict a braking
// vehicle stop it themselves (PredictBicycle does).
BicycleState Rk4Step(const BicycleState& s, const BicycleInputs& u, double wheelbase_m,
                     double dt_s);

// States at t = 0, dt, 2 dt, ..., up to and including the last step <= horizon_s (the first is
// `initial`). A vehicle that brakes to a standstill stays there (no reversing).
// Preconditions (RiskOptions::Validate checks them): wheelbase_m > 0, dt_s > 0, horizon_s >= 0.
std::vector<BicycleState> PredictBicycle(const BicycleState& initial, const BicycleInputs& u,
                                         double wheelbase_m, double horizon_s, double dt_s);

// The front-wheel angle that gives yaw rate `yaw_rate_radps` at `speed_mps` (delta =
// atan(L omega / v)); 0 below 0.1 m/s, where the yaw rate says nothing about the steering.
double SteeringFromYawRate(double yaw_rate_radps, double speed_mps, double wheelbase_m);

}  // namespace lookout::risk
