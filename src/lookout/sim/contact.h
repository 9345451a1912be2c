#pragma once

// The true contact time: when an actor's footprint first touches the ego's. Ground truth
// reports it, and time-to-collision estimates are scored against it.

#include <optional>

#include "lookout/sim/footprint.h"
#include "lookout/sim/trajectory.h"

namespace lookout::sim {

// The first scenario time in [t_begin_s, t_end_s], while both are present, at which the ego's
// box (ego_length_m x ego_width_m, centred on its trajectory's pose) and `actor_footprint` at
// the actor's pose overlap (shapes are closed: touching counts); nullopt if they never do.
//
// The window is sampled every step_s from its start; the first overlapping sample is refined
// by bisection against the last clear one until the bracket is under 1e-4 s, and the result
// is the bracket's overlapping end: the footprints do touch at the returned time, at most
// 1e-4 s after the exact first contact. Footprints already overlapping when the window opens
// (an actor that appears on the ego) give the window's start.
//
// Limit: a graze that begins and ends between two samples is missed. At step_s = 0.01 s and
// a closing speed of 30 m/s that is a corner clipped by less than 0.3 m of relative travel.
std::optional<double> FirstContactTime(const Trajectory& ego, double ego_length_m,
                                       double ego_width_m, const Trajectory& actor,
                                       const Footprint& actor_footprint, double t_begin_s,
                                       double t_end_s, double step_s = 0.01);

}  // namespace lookout::sim
