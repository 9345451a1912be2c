#pragma once

// Detection precision and recall of objects against the simulator's actors, per frame and over
// a run: the lidar_objects.* keys of docs/cli-contract.md ("dynamic lidar objects matched to
// moving actors within 1 m"), generic over where the objects come from.
//
// Definitions (the contract leaves them open; docs/grid.md "Objects out of the grid"):
//   - a moving actor: true speed > moving_speed_mps (0.5 m/s, the grid metrics' "moving");
//   - an object and an actor may match when the object's point lies within gate_m of the
//     actor's footprint (distance to the shape, 0 inside it): a cluster's centroid sits on the
//     visible part of a car, not at its centre, so the footprint, not its centre, is compared;
//   - matching is one-to-one, greedy by increasing distance (ties by object, then actor index):
//     with a 1 m gate, objects rarely compete, and greedy is deterministic and needs no
//     assignment solver; an actor split into two objects has one match and one false object;
//   - precision = matched objects / objects; recall = countable matched actors / countable
//     moving actors, where the caller says which actors count (those the sensor could see):
//     an actor that does not count may still be matched, and its object is then no false one.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "lookout/sim/truth.h"

namespace lookout::eval {

struct DetectionMatchOptions {
  double gate_m = 1.0;            // contract: within 1 m
  double moving_speed_mps = 0.5;  // truly moving: speed > this
};

struct DetectionCounts {
  std::int64_t objects = 0;          // every object given
  std::int64_t matched_objects = 0;  // matched to a moving actor
  std::int64_t actors = 0;           // countable moving actors
  std::int64_t matched_actors = 0;   // of those, matched to an object

  DetectionCounts& operator+=(const DetectionCounts& o);
};

// One frame. `object_points` and the actors' footprints in the same frame; `countable[k]` says
// whether actors[k] counts for recall (empty: every actor counts). Throws std::invalid_argument
// when countable is neither empty nor of the actors' size.
DetectionCounts MatchObjectsToMovingActors(const std::vector<Eigen::Vector2d>& object_points,
                                           const std::vector<sim::ActorTruth>& actors,
                                           const std::vector<bool>& countable,
                                           const DetectionMatchOptions& options = {});

// Counts over the frames of a run: precision and recall of all the frames' objects and actors
// (each object and each actor-frame weighs the same).
class DetectionAccumulator {
 public:
  void AddFrame(const DetectionCounts& counts) { total_ += counts; }
  std::optional<double> Precision() const;  // nullopt before any object
  std::optional<double> Recall() const;     // nullopt before any countable moving actor
  const DetectionCounts& counts() const { return total_; }

 private:
  DetectionCounts total_;
};

}  // namespace lookout::eval
