#include "lookout/risk/risk_options.h"

#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::risk {
namespace {

void Require(bool ok, const std::string& source, const char* field, const char* problem) {
  if (!ok) throw InputError(source, 0, field, problem);
}

bool Positive(double v) { return std::isfinite(v) && v > 0.0; }
bool NonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

void RiskOptions::Validate(const std::string& source) const {
  Require(Positive(horizon_s) && horizon_s <= 60.0, source, "horizon_s", "must be in (0, 60] s");
  Require(Positive(step_s) && step_s <= horizon_s, source, "step_s",
          "must be > 0 and at most the horizon");
  Require(Positive(wheelbase_m), source, "wheelbase_m",
          "must be > 0 (the steering angle is derived from yaw rate, speed and wheelbase)");
  Require(Positive(ego_radius_m), source, "ego_radius_m", "must be > 0");
  Require(Positive(car_radius_m), source, "car_radius_m", "must be > 0");
  Require(Positive(truck_radius_m), source, "truck_radius_m", "must be > 0");
  Require(Positive(cyclist_radius_m), source, "cyclist_radius_m", "must be > 0");
  Require(Positive(pedestrian_radius_m), source, "pedestrian_radius_m", "must be > 0");
  Require(Positive(unknown_radius_m), source, "unknown_radius_m", "must be > 0");
  Require(NonNegative(covariance_sigmas), source, "covariance_sigmas", "must be >= 0");
  Require(NonNegative(growth_per_metre), source, "growth_per_metre", "must be >= 0");
  Require(NonNegative(pedestrian_growth_factor), source, "pedestrian_growth_factor",
          "must be >= 0");
  Require(collision_samples >= 0 && collision_samples <= 1000000, source, "collision_samples",
          "must be in [0, 10^6]");
  Require(Positive(reaction_time_s) && reaction_time_s < horizon_s, source, "reaction_time_s",
          "must be > 0 and below the horizon");
}

}  // namespace lookout::risk
