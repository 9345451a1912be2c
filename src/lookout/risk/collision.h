#pragma once

// Collision detection and time to collision (seed 004 section VIII.C-D): every object is a
// circle per prediction step, the ego too; the first step at which the ego's circle meets
// another's is a potential collision, and its time the TTC.
//
// The time is refined inside the step: between the last step with the circles apart and the
// first with them touching, the separation (centre distance minus the radii's sum) is
// interpolated linearly to its zero. For constant velocities along a line (head-on, rear-end)
// the separation is linear in time and the TTC exact; otherwise the error is second order in
// the step (0.1 s by default).

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace lookout::risk {

// One object's predicted footprint: a circle per step, steps dt_s apart from t = 0.
struct CircleTrack {
  std::vector<Eigen::Vector2d> centre_m;
  std::vector<double> radius_m;
};

struct Collision {
  double ttc_s = 0.0;    // from t = 0 to the first contact
  std::size_t step = 0;  // the first step at which the circles overlap
};

// The first contact of `ego` and `other` on their common steps, or nullopt. Pure.
std::optional<Collision> FirstCollision(const CircleTrack& ego, const CircleTrack& other,
                                        double dt_s);

}  // namespace lookout::risk
