#pragma once

// Collision detection and time to collision (seed 004 section VIII.C-D): every object is a
// footprint per prediction step (footprint.h: the paper's circle, or an oriented box), the ego
// too; the first step at which the ego's footprint meets another's is a potential collision,
// and its time the TTC.
//
// The time is refined inside the step: between the last step with the footprints apart and the
// first with them touching, their separation (footprint.h: the distance, negative when they
// overlap) is interpolated linearly to its zero. For circles at constant velocities along a
// line (head-on, rear-end) the separation is linear in time and the TTC exact; otherwise the
// error is second order in the step (0.1 s by default).

#include <optional>

#include "lookout/risk/footprint.h"

namespace lookout::risk {

struct Collision {
  double ttc_s = 0.0;    // from t = 0 to the first contact
  std::size_t step = 0;  // the first step at which the footprints overlap
};

// The first contact of `ego` and `other` on their common steps, or nullopt. Pure.
std::optional<Collision> FirstCollision(const FootprintTrack& ego, const FootprintTrack& other,
                                        double dt_s);

}  // namespace lookout::risk
