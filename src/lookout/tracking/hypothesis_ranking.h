#pragma once

// Hypothesis generation of Reid's MHT for one scan and one parent hypothesis, ranked: the m
// least-cost ways of explaining every detection as the continuation of one of the parent's
// tracks (inside its gate), a false alarm, or a new track (Reid 1979, section III; ranked by
// Murty's method as Cox and Hingorani 1996 do instead of enumerating them all).
//
// The gated pairs split the problem into independent clusters (connected components of the
// detection-track gating graph, Reid's "clusters"). Murty's method runs on each cluster's small
// matrix, rows its detections, columns its tracks plus one false-alarm and one new-track column
// per detection; the m best global associations are then the m least sums of one choice per
// cluster, taken from the clusters' ranked lists. A cluster of one detection (the common case)
// has its choices sorted instead of solved. Tracks that gate nothing are missed
// in every association and appear in no cluster.

#include <cstddef>
#include <vector>

namespace lookout::tracking {

inline constexpr int kFalseAlarm = -1;
inline constexpr int kNewTrack = -2;

struct GatedPair {
  int track = 0;
  int detection = 0;
  double cost = 0.0;  // finite
};

// Costs are negative log-likelihood ratios (mht_tracker.h says which); every detection must be
// explained, every track takes at most one detection, a track not taking one is missed at no
// cost of its own (its miss term is a constant of the parent).
struct AssociationProblem {
  int tracks = 0;
  int detections = 0;
  std::vector<GatedPair> pairs;  // at most one per (track, detection)
  double false_alarm_cost = 0.0;
  double new_track_cost = 0.0;
};

struct RankedAssociation {
  double cost = 0.0;
  std::vector<int> track_of_detection;  // per detection: a track, kFalseAlarm or kNewTrack
};

// The min(m, all) least-cost associations, cheapest first. Equal costs come out in a fixed
// order (clusters by their first detection; within a cluster, Murty's order, or for a single
// detection its tracks in order, then false alarm, then new track), so the result is the same on
// every run. No detections: one empty association.
std::vector<RankedAssociation> BestAssociations(const AssociationProblem& problem, std::size_t m);

}  // namespace lookout::tracking
