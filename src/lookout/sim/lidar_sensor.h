#pragma once

// The simulated 2D lidar of the seed 004 vehicle: a fan of beams in the sensor frame, cast
// against the static world and the actors' footprints (never the ego's own), with Gaussian
// range noise and random dropouts.
//
// The sweep is instantaneous: every beam is cast from the sensor pose at the scan stamp, and
// the ego's (and the actors') motion during a real sweep is not modelled. Why: a scan then
// matches LidarScan's contract exactly ("the sweep is treated as instantaneous"), consumers
// need no de-skewing, and the ground truth at the stamp is consistent with every beam. At the
// default 12.5 Hz and 11 m/s, a real rolling sweep would smear the far end of the scan by at
// most ~0.9 m; Lookout's lidar processing assumes that has been compensated upstream.
//
// Frame geometry: beams are spaced by resolution_rad, symmetric about the sensor's x axis,
// as many as fit in fov_rad with both ends included (160 deg at 0.25 deg: 641 beams, the
// first at -80 deg and the last at +80 deg).
//
// Noise: each beam draws one uniform (dropout) and one standard normal (range noise), in
// beam order, whether or not it hits, so a beam's noise never depends on the other beams.
// A noisy range below 0 is clamped to 0 (only possible for a hit within a few sigma of the
// sensor, i.e. centimetres with the default sigma); one beyond max range becomes +infinity,
// as does a dropout (REP 117: no return).

#include <span>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/core/random.h"
#include "lookout/core/time.h"
#include "lookout/sim/raycast.h"
#include "lookout/sim/scenario.h"
#include "lookout/sim/shapes.h"

namespace lookout::sim {

int LidarBeamCount(const LidarOptions& options);
// The sensor frame in the vehicle frame.
Pose2 LidarMount(const LidarOptions& options);
// The beams of one sweep in the world frame, for a vehicle at `ego_pose` (world frame).
Fan LidarFan(const LidarOptions& options, const Pose2& ego_pose);

// The scan from geometric hits of LidarFan(options, ego pose): noise and dropouts applied,
// drawn from `rng`. Split from the casting so that one cast can serve both the scan and the
// ground truth's visible fractions.
LidarScan MakeLidarScan(const LidarOptions& options, TimeNs stamp, const FanHits& hits,
                        Rng& rng);

// Casts and makes the scan in one call. `actor_footprints` are owned by actor indices in
// [0, actor_count).
LidarScan SimulateLidarScan(const LidarOptions& options, TimeNs stamp, const Pose2& ego_pose,
                            std::span<const Shape> static_world,
                            std::span<const Shape> actor_footprints, int actor_count,
                            Rng& rng);

}  // namespace lookout::sim
