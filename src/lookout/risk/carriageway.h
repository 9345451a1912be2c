#pragma once

// The carriageways of the ego's map: where the vehicles drive, and where a walker is on the
// road rather than beside it.
//
// Why: seed 004 predicts a pedestrian from its state alone. A walker on the sidewalk heading for
// the road, predicted at constant velocity, walks on into the ego's lane; but at the kerb it may
// as well stop (waiting for a gap, or for the car to stop, is common), and nothing in its track
// (position, velocity) says which. In pushchair-group the straight-line future warns 0.6 s
// before the driver brakes, while the group is still on the sidewalk (docs/risk.md). So the
// risk assessment weighs the collision probability of a pedestrian off every carriageway by the
// chance that it steps off (RiskOptions::kerb_step_off_probability); its TTC, the likeliest
// future's, is kept (the information level still shows it).

#include <Eigen/Core>
#include <vector>

#include "lookout/risk/footprint.h"

namespace lookout::risk {

// Rectangles (Footprint::Box) in the risk assessment's ground-fixed frame; empty: no map.
using Carriageways = std::vector<Footprint>;

// Whether `p` lies on one of `roads` (their border included). Pure.
bool OnCarriageway(const Carriageways& roads, const Eigen::Vector2d& p);

}  // namespace lookout::risk
