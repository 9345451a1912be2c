#pragma once

// Manoeuvre hypotheses of a vehicle approaching a junction: straight on, or a turn onto the
// crossing road, each a path at the vehicle's constant speed (seed 004's assumption).
//
// Why: in left-turn-across-path the oncoming car drives straight until half a second before
// the contact; no prediction from its state (position, velocity, yaw rate: the IMM's turn
// models see a turn only once it has begun) can see the turn 2 s ahead (docs/risk.md). What
// can is the map: a car on a road that another road crosses ahead may leave by either, and the
// few turns it can still take at its speed are known from the geometry. So each vehicle is
// predicted under the manoeuvres the map and its speed allow, weighted by a prior
// (WeighManoeuvres), and the risk assessment acts on the most dangerous plausible one
// (risk_assessment.h).
//
// The turn (PlanTurn): the vehicle keeps its line, then drives a circular arc tangent to its
// line and to the exit lane (the crossing road's axis offset by the vehicle's own lane offset,
// on the right of the exit direction: right-hand traffic, the same lane it drives in), then
// the exit lane. The radius is the smallest whose lateral acceleration v^2 / R stays within
// max_lateral_acceleration_mps2 (a driver keeps speed and line until it must turn), no smaller
// than the corner allows (the vehicle's inner side clears the kerb corner on the inside of the
// turn) and no larger than the corner allows or the distance left before the junction. No
// such radius: the turn is not possible at this speed (a car at 20 m/s does not take a
// junction's corner).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "lookout/risk/carriageway.h"

namespace lookout::risk {

enum class Manoeuvre { kStraight = 0, kLeftTurn = 1, kRightTurn = 2 };
const char* ToString(Manoeuvre manoeuvre);

// A pose along a predicted path, in the assessment's ground-fixed frame.
struct PathPose {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;
};

// Straight on for turn_in_m, an arc of radius_m through turn_angle_rad (> 0 left), then
// straight on in the new direction; `centre_m` is the arc's centre (for tests and drawing).
struct TurnPath {
  double turn_in_m = 0.0;
  double radius_m = 0.0;
  double turn_angle_rad = 0.0;
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
};

struct TurnLimits {
  // The lateral acceleration a driver takes a junction's corner at, at most (0.5 g).
  double max_lateral_acceleration_mps2 = 5.0;
  // The vehicle drives along a road when its heading is within this of the road's axis.
  double heading_tolerance_rad = 0.35;
  // Half the vehicle's width: its inner side must clear the kerb corner.
  double half_width_m = 0.9;
};

// The left or right turn (kStraight: nullopt) that a vehicle at `position_m`, heading `yaw_rad`
// at `speed_mps`, can take onto the nearest road of `roads` crossing its own ahead. nullopt
// when it is on no road or not along one, already on the crossing road (in the junction), no
// road crosses ahead, or no radius meets the limits. Pure.
std::optional<TurnPath> PlanTurn(const Carriageways& roads, const Eigen::Vector2d& position_m,
                                 double yaw_rad, double speed_mps, Manoeuvre turn,
                                 const TurnLimits& limits);

// Poses at t = 0, dt, 2 dt, ... up to and including the last step <= horizon_s, at constant
// `speed_mps` along `path` from `position_m` heading `yaw_rad`. Pure.
std::vector<PathPose> AlongTurn(const Eigen::Vector2d& position_m, double yaw_rad,
                                double speed_mps, const TurnPath& path, double horizon_s,
                                double dt_s);

struct ManoeuvreWeights {
  double straight = 1.0, left = 0.0, right = 0.0;
};

// The prior (left_prior, right_prior, straight the rest; priors in [0, 1], summing to at most
// 1) conditioned on which turns are possible: an impossible turn gets 0, the others share its
// mass in proportion to their priors (Bayes on "the vehicle can take it"). Sums to 1. Pure.
ManoeuvreWeights WeighManoeuvres(double left_prior, double right_prior, bool left_possible,
                                 bool right_possible);

}  // namespace lookout::risk
