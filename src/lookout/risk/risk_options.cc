#include "lookout/risk/risk_options.h"

#include <cmath>
#include <numbers>

#include "lookout/core/input_error.h"

namespace lookout::risk {
namespace {

void Require(bool ok, const std::string& source, const char* field, const char* problem) {
  if (!ok) throw InputError(source, 0, field, problem);
}

bool Positive(double v) { return std::isfinite(v) && v > 0.0; }
bool NonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

std::optional<CollisionShape> ParseCollisionShape(const std::string& name) {
  if (name == "circles") return CollisionShape::kCircles;
  if (name == "boxes") return CollisionShape::kBoxes;
  return std::nullopt;
}

const char* ToString(CollisionShape shape) {
  switch (shape) {
    case CollisionShape::kCircles: return "circles";
    case CollisionShape::kBoxes: return "boxes";
  }
  return "boxes";
}

std::optional<PedestrianModel> ParsePedestrianModel(const std::string& name) {
  if (name == "growing-circle") return PedestrianModel::kGrowingCircle;
  if (name == "constant-velocity") return PedestrianModel::kConstantVelocity;
  return std::nullopt;
}

const char* ToString(PedestrianModel model) {
  switch (model) {
    case PedestrianModel::kGrowingCircle: return "growing-circle";
    case PedestrianModel::kConstantVelocity: return "constant-velocity";
  }
  return "constant-velocity";
}

void RiskOptions::Validate(const std::string& source) const {
  Require(Positive(horizon_s) && horizon_s <= 60.0, source, "horizon_s", "must be in (0, 60] s");
  Require(Positive(step_s) && step_s <= horizon_s, source, "step_s",
          "must be > 0 and at most the horizon");
  Require(Positive(wheelbase_m), source, "wheelbase_m",
          "must be > 0 (the steering angle is derived from yaw rate, speed and wheelbase)");
  Require(Positive(ego_length_m), source, "ego_length_m", "must be > 0");
  Require(Positive(ego_width_m), source, "ego_width_m", "must be > 0");
  const auto footprint = footprints.FirstInvalidField();
  Require(!footprint, source, footprint.value_or(""), "must be > 0");
  Require(Positive(unknown_radius_m), source, "unknown_radius_m", "must be > 0");
  Require(!std::isnan(unknown_as_car_speed_mps) && unknown_as_car_speed_mps >= 0.0, source,
          "unknown_as_car_speed_mps", "must be >= 0 (infinity: never)");
  Require(NonNegative(min_heading_speed_mps), source, "min_heading_speed_mps", "must be >= 0");
  Require(NonNegative(covariance_sigmas), source, "covariance_sigmas", "must be >= 0");
  Require(NonNegative(growth_per_metre), source, "growth_per_metre", "must be >= 0");
  Require(NonNegative(pedestrian_growth_factor), source, "pedestrian_growth_factor",
          "must be >= 0");
  Require(NonNegative(pedestrian_intent_sigma_mps), source, "pedestrian_intent_sigma_mps",
          "must be >= 0");
  Require(kerb_step_off_probability >= 0.0 && kerb_step_off_probability <= 1.0, source,
          "kerb_step_off_probability", "must be in [0, 1]");
  Require(turn_left_prior >= 0.0 && turn_left_prior <= 1.0, source, "turn_left_prior",
          "must be in [0, 1]");
  Require(turn_right_prior >= 0.0 && turn_right_prior <= 1.0 - turn_left_prior, source,
          "turn_right_prior", "must be in [0, 1 - turn_left_prior]");
  Require(min_manoeuvre_weight > 0.0 && min_manoeuvre_weight <= 1.0, source,
          "min_manoeuvre_weight", "must be in (0, 1]");
  Require(Positive(max_turn_lateral_acceleration_mps2), source,
          "max_turn_lateral_acceleration_mps2", "must be > 0");
  Require(turn_heading_tolerance_rad > 0.0 &&
              turn_heading_tolerance_rad < 0.25 * std::numbers::pi,
          source, "turn_heading_tolerance_rad", "must be in (0, pi/4)");
  Require(collision_samples >= 0 && collision_samples <= 1000000, source, "collision_samples",
          "must be in [0, 10^6]");
  Require(Positive(reaction_time_s) && reaction_time_s < horizon_s, source, "reaction_time_s",
          "must be > 0 and below the horizon");
}

}  // namespace lookout::risk
