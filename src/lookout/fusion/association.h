#pragma once

// Seed 004 VI.A, object association, made one-to-one. The paper pairs each stereo object with
// the nearest lidar object in its gate; two stereo objects can then take the same lidar
// object. Lookout solves the global nearest neighbour instead: the one-to-one pairing of least
// total d^2, where leaving a stereo object unpaired costs the gate threshold gamma (so a pair
// is only made when it is better than no pair, and a pair outside the gate never). An optimal
// assignment (assignment/linear_assignment.h), not a greedy one: greedy nearest pairs is
// optimal when gates do not overlap, but at a crossing two pedestrians side by side at 30 m
// share most of their gates, and greedy then can take the wrong pair and leave the other
// stereo object out.

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "lookout/fusion/gate.h"
#include "lookout/stereo/range_bearing.h"

namespace lookout::fusion {

struct AssociationPair {
  std::size_t stereo = 0;  // index into the stereo points
  std::size_t lidar = 0;   // index into the lidar points
  double distance_squared = 0.0;
};

// Where a camera track's previous pair puts its body now (pair_memory.h), and the track's
// stereo point in this frame, if the camera reported it.
struct PairPrior {
  std::optional<std::size_t> stereo;  // index into the stereo points
  stereo::CartesianPoint point;
};

// Each of `stereo_count` stereo points' own camera track's prior: its index into `priors`, or
// nullopt where the track has none (priors naming no stereo point, or one out of range, own
// nothing). Pure.
std::vector<std::optional<std::size_t>> OwnPriors(std::span<const PairPrior> priors,
                                                  std::size_t stereo_count);

// Pairs in increasing stereo index. Pure. `priors`: a stereo point whose own prior's gate does
// not hold a lidar point does not pair with it when another camera track's prior holds it
// (that body's own, its camera object missed or elsewhere); a lidar point no other prior holds
// may pair (the prior may be the one that was wrong).
std::vector<AssociationPair> AssociateStereoToLidar(
    const std::vector<stereo::CartesianPoint>& stereo_points,
    const std::vector<stereo::CartesianPoint>& lidar_points, const AssociationGate& gate,
    std::span<const PairPrior> priors = {});

}  // namespace lookout::fusion
