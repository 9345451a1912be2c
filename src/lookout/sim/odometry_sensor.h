#pragma once

// The ego's wheel odometry and yaw-rate sensor: the true speed and yaw rate with independent
// zero-mean Gaussian noise (no bias, no scale error), one draw each per frame.

#include "lookout/core/messages.h"
#include "lookout/core/random.h"
#include "lookout/core/time.h"
#include "lookout/sim/scenario.h"
#include "lookout/sim/trajectory.h"

namespace lookout::sim {

// Draws the speed noise first, then the yaw-rate noise, from `rng`.
EgoOdometry MakeOdometry(const OdometryOptions& options, TimeNs stamp,
                         const KinematicState& ego, Rng& rng);

}  // namespace lookout::sim
