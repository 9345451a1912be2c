#pragma once

// The ego's trajectory along its intended route: the driver's plan as a navigation system (or a
// turn signal and the map) gives it, a polyline in the same ground-fixed frame as the ego.
//
// Why: seed 004 predicts every vehicle, the ego included, from its current state (constant
// speed and heading), and notes that the future driver behaviour is unknown. For the ego it need
// not be: a right turn starts about a second before the corner, so a prediction from the
// current state sees it only then, too late for a warning 2 s ahead of a right-hook collision
// (docs/scenarios.md, right-turn-cyclist). Along the route the turn is known from the start.
//
// Model: the ego's nearest point on the route, then along the route's arc length at the current
// speed with the current acceleration held, stopping where the speed reaches zero (no
// reversing) and at the route's end (where the drive ends). The ego's offset from the route
// (a driver cuts corners) fades out as exp(-t / 1 s).

#include <Eigen/Core>
#include <vector>

namespace lookout::risk {

// The arc length of the point of `route` nearest to `p` (0 for a route of one point). Pure.
// Precondition: route not empty.
double ProjectOntoRoute(const std::vector<Eigen::Vector2d>& route, const Eigen::Vector2d& p);

// The point at arc length `s_m`, clamped to the route's ends. Pure. Precondition: not empty.
Eigen::Vector2d RoutePointAt(const std::vector<Eigen::Vector2d>& route, double s_m);

// Positions at t = 0, dt, ..., up to and including the last step <= horizon_s, starting at the
// projection of `position_m`. Pure. Preconditions: route not empty, dt_s > 0, horizon_s >= 0.
std::vector<Eigen::Vector2d> PredictAlongRoute(const std::vector<Eigen::Vector2d>& route,
                                               const Eigen::Vector2d& position_m,
                                               double speed_mps, double acceleration_mps2,
                                               double horizon_s, double dt_s);

}  // namespace lookout::risk
