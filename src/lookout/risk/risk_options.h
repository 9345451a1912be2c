#pragma once

// Options of the risk stage (seed 004 section VIII), one plain struct with units in the names.

#include <cstdint>
#include <optional>
#include <string>

#include "lookout/core/class_footprint.h"

namespace lookout::risk {

// How a road user's footprint is modelled for collision detection (footprint.h).
enum class CollisionShape {
  kCircles,  // the paper: a circle per object, of half the default footprint's diagonal
  kBoxes,    // vehicles (the ego included) as oriented boxes, pedestrians as circles
};

// How a pedestrian (and an object of unknown kind) is predicted.
enum class PedestrianModel {
  // The paper: a circle at the detected position whose radius grows in proportion to the
  // estimated speed, r0 + factor * speed * t, no direction assumed.
  kGrowingCircle,
  // Along its estimated velocity; where it may be instead is the spread of its position, which
  // grows with time by the velocity's uncertainty (the track's covariance and the walker's own
  // freedom to change course, pedestrian_intent_sigma_mps): sampled for the collision
  // probability.
  kConstantVelocity,
};

// "circles", "boxes"; "growing-circle", "constant-velocity"; nullopt for another name.
std::optional<CollisionShape> ParseCollisionShape(const std::string& name);
const char* ToString(CollisionShape shape);
std::optional<PedestrianModel> ParsePedestrianModel(const std::string& name);
const char* ToString(PedestrianModel model);

struct RiskOptions {
  // Prediction: the horizon h and the integration step (the paper's 0.1 s steps to 5 s).
  double horizon_s = 5.0;
  double step_s = 0.1;
  // The ego's wheelbase, for the steering angle derived from yaw rate and speed.
  double wheelbase_m = 2.7;
  // The paper holds speed and heading; true also holds the current yaw rate (the steering
  // derived from it) and acceleration: better on a bend, worse when a turn is ending.
  bool hold_yaw_rate = false;

  CollisionShape shape = CollisionShape::kBoxes;
  PedestrianModel pedestrian_model = PedestrianModel::kConstantVelocity;

  // Footprints: the ego's own, and the default footprints of the scenario format for the other
  // road users (boxes of length x width; the circles' radius is half the diagonal, so that a
  // circle covers its box: car 4.5 x 1.8 m -> 2.42 m).
  double ego_length_m = 4.6, ego_width_m = 1.9;
  ClassFootprints footprints;  // core/class_footprint.h
  double unknown_radius_m = 1.0;
  // An object of unknown class moving faster than this is predicted as a car (its box, the
  // bicycle model, the turns at junctions): no walker and few cyclists keep 8 m/s (29 km/h),
  // and a lidar-only track has no class until the camera sees it, 35 m away at most, where a
  // car closing at 19 m/s is under 2 s from the ego. Infinity: unknown objects stay round.
  double unknown_as_car_speed_mps = 8.0;
  // Below this speed a track's velocity gives no heading: a vehicle is then a circle of half
  // its box's diagonal (every orientation covered).
  double min_heading_speed_mps = 1.0;
  // Position uncertainty: the footprint grows by n_sigma standard deviations of the track's
  // position (largest eigenvalue of its covariance), and by this much per metre travelled. The
  // paper grows its circles with the distance; here the uncertainty of the future is sampled
  // for the collision probability instead (the track's velocity covariance, the walkers'
  // freedom), and a footprint grown by 5 % of 100 m would make any car passing in the next lane
  // a potential collision: 0 by default.
  double covariance_sigmas = 2.0;
  double growth_per_metre = 0.0;
  // kGrowingCircle: r0 + factor * speed * t.
  double pedestrian_growth_factor = 1.0;
  // kConstantVelocity: the spread of velocities a walker may choose over the horizon (its
  // speed and its direction: a fifth of a typical 1.4 m/s walking speed), added to the track's
  // velocity covariance when sampling; pedestrians and unknown objects.
  double pedestrian_intent_sigma_mps = 0.3;
  // A pedestrian off every carriageway of the ego's map (carriageway.h) steps onto the road in
  // this share of its futures and waits at the kerb in the others: its collision probability is
  // weighted by it (the collision is on the road). 0.5: nothing in a walker's track says which,
  // so a walker still on the sidewalk reaches the warning's probability (0.5) only if every
  // sampled crossing future hits. 1 leaves the walker to its state, as the paper does.
  double kerb_step_off_probability = 0.5;

  // Manoeuvre hypotheses at junctions (turn_hypotheses.h): a car or truck on a carriageway of
  // the ego's map that another crosses ahead may turn onto it. Each turn that its speed and the
  // corner allow gets its prior, straight on the rest (turn_left_prior and turn_right_prior:
  // a third each, three exits none favoured: nothing in a track says which a driver takes),
  // renormalised over the possible ones; the risk is that of the most dangerous manoeuvre
  // whose weight reaches min_manoeuvre_weight (risk_assessment.h: a turn across the ego's path
  // gives no time to react once it begins). false: straight on only, as the paper.
  bool turn_hypotheses = true;
  double turn_left_prior = 1.0 / 3.0;
  double turn_right_prior = 1.0 / 3.0;
  double min_manoeuvre_weight = 0.25;
  // The lateral acceleration a driver takes a junction's corner at, at most (0.5 g): it picks
  // the turn's radius (v^2 / a, within what the corner allows) and rules out a turn too fast
  // for the corner.
  double max_turn_lateral_acceleration_mps2 = 5.0;
  // A vehicle drives along a road when its heading is within this of the road's axis.
  double turn_heading_tolerance_rad = 0.35;

  // Collision probability (risk_indicators.h): samples per object, 0 to skip, and the seed of
  // the draws (one set per step, shared by the objects: the same tracks give the same
  // probabilities, whatever their order).
  int collision_samples = 1000;
  std::uint64_t seed = 0;

  // Risk: the total reaction time (driver 1 s + vehicle 1 s) against which the TTC is weighed.
  double reaction_time_s = 2.0;

  // Throws lookout::InputError naming the first field out of range.
  void Validate(const std::string& source = "risk options") const;
};

}  // namespace lookout::risk
