#include "lookout/risk/bicycle_model.h"

#include <cmath>
#include <cstddef>

namespace lookout::risk {

BicycleState BicycleDerivative(const BicycleState& s, const BicycleInputs& u, double wheelbase_m) {
  return {s.speed_mps * std::cos(s.yaw_rad), s.speed_mps * std::sin(s.yaw_rad),
          s.speed_mps * std::tan(s.steering_rad) / wheelbase_m, u.acceleration_mps2,
          u.steering_rate_radps};
}

namespace {

BicycleState Add(const BicycleState& s, const BicycleState& d, double h) {
  return {s.x_m + h * d.x_m, s.y_m + h * d.y_m, s.yaw_rad + h * d.yaw_rad,
          s.speed_mps + h * d.speed_mps, s.steering_rad + h * d.steering_rad};
}

}  // namespace

BicycleState Rk4Step(const BicycleState& s, const BicycleInputs& u, double wheelbase_m,
                     double dt_s) {
  const BicycleState k1 = BicycleDerivative(s, u, wheelbase_m);
  const BicycleState k2 = BicycleDerivative(Add(s, k1, dt_s / 2.0), u, wheelbase_m);
  const BicycleState k3 = BicycleDerivative(Add(s, k2, dt_s / 2.0), u, wheelbase_m);
  const BicycleState k4 = BicycleDerivative(Add(s, k3, dt_s), u, wheelbase_m);
  BicycleState out = s;
  out = Add(out, k1, dt_s / 6.0);
  out = Add(out, k2, dt_s / 3.0);
  out = Add(out, k3, dt_s / 3.0);
  out = Add(out, k4, dt_s / 6.0);
  return out;
}

std::vector<BicycleState> PredictBicycle(const BicycleState& initial, const BicycleInputs& u,
                                         double wheelbase_m, double horizon_s, double dt_s) {
  // Steps counted in integers so that 5 s at 0.1 s is exactly 51 states, whatever the rounding.
  const auto steps = static_cast<std::size_t>(std::floor(horizon_s / dt_s + 1e-9));
  std::vector<BicycleState> out;
  out.reserve(steps + 1);
  out.push_back(initial);
  BicycleInputs inputs = u;
  for (std::size_t k = 0; k < steps; ++k) {
    BicycleState next = Rk4Step(out.back(), inputs, wheelbase_m, dt_s);
    // A braking vehicle stops; it does not reverse (the model has no gear).
    if (initial.speed_mps >= 0.0 && next.speed_mps < 0.0) {
      next.speed_mps = 0.0;
      inputs.acceleration_mps2 = 0.0;
    }
    out.push_back(next);
  }
  return out;
}

double SteeringFromYawRate(double yaw_rate_radps, double speed_mps, double wheelbase_m) {
  if (std::abs(speed_mps) < 0.1) return 0.0;
  return std::atan(wheelbase_m * yaw_rate_radps / speed_mps);
}

}  // namespace lookout::risk
