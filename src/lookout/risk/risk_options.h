#pragma once

// Options of the risk stage (seed 004 section VIII), one plain struct with units in the names.

#include <cstdint>
#include <string>

namespace lookout::risk {

struct RiskOptions {
  // Prediction: the horizon h and the integration step (the paper's 0.1 s steps to 5 s).
  double horizon_s = 5.0;
  double step_s = 0.1;
  // The ego's wheelbase, for the steering angle derived from yaw rate and speed.
  double wheelbase_m = 2.7;
  // The paper holds speed and heading; true also holds the current yaw rate (the steering
  // derived from it) and acceleration: better on a bend, worse when a turn is ending.
  bool hold_yaw_rate = false;

  // Collision circles: a radius per kind of road user (half the diagonal of the simulator's
  // default footprints, so that a circle covers its box: car 4.5 x 1.8 m -> 2.42 m).
  double ego_radius_m = 2.42;
  double car_radius_m = 2.42;
  double truck_radius_m = 4.19;
  double cyclist_radius_m = 0.95;
  double pedestrian_radius_m = 0.3;
  double unknown_radius_m = 1.0;
  // Position uncertainty: the circle grows by n_sigma standard deviations of the track's
  // position (largest eigenvalue of its covariance) and by this much per metre travelled.
  double covariance_sigmas = 2.0;
  double growth_per_metre = 0.05;
  // Pedestrians (seed 004): no direction assumed; the circle stays at the detected position
  // and its radius grows in proportion to the estimated speed: r0 + factor * speed * t.
  double pedestrian_growth_factor = 1.0;

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
