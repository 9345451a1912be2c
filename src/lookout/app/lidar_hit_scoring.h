#pragma once

// Scores the lidar chain's moving/static classification of every return
// (lidar/hit_classification.h) against the simulator's truth per beam
// (sim::TruthFrame::lidar_beam_owner). A beam is on a moving actor when the shape it hit is an
// actor whose true speed exceeds 0.5 m/s (the contract's "moving", as lidar_objects.* has it).
//   lidar_hits.moving_precision  dynamic returns on moving actors / dynamic returns counted,
//                                where a dynamic return on an actor slower than 0.5 m/s (one
//                                stopping, starting, standing) counts neither way: it is on a
//                                mover of the scene, not on the static world;
//   lidar_hits.moving_recall     dynamic returns on moving actors / returns on moving actors;
//   lidar_hits.moving_as_static, .moving_as_unknown  returns on moving actors called static,
//                                unknown (the misses of the recall, by kind);
//   lidar_hits.static_false_dynamic  dynamic returns on the static world / its returns;
//   lidar_hits.unknown_share     unknown returns / returns;
//   lidar_hits.no_returns_per_frame  beams that were not returns (NaN, inf, dropouts), mean;
//   lidar_hits.moving_precision_after_1s, .moving_recall_after_1s  the same over the scans
//                                from 1 s after the first one scored: the map starts empty,
//                                so the first scan's returns are all unknown and a mover's
//                                next few land on its own trace, seen once (the grid's
//                                grid.velocity_rmse_after_1s_mps leaves out its start alike).

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "lookout/lidar/hit_classification.h"
#include "lookout/sim/truth.h"

namespace lookout::app {

struct HitCounts {
  std::int64_t returns = 0;
  std::int64_t no_returns = 0;
  std::int64_t unknown = 0;
  std::int64_t moving = 0;              // returns on moving actors
  std::int64_t moving_dynamic = 0;      // ... classified dynamic
  std::int64_t moving_static = 0;       // ... classified static
  std::int64_t moving_unknown = 0;      // ... classified unknown
  std::int64_t static_world = 0;        // returns on the static world
  std::int64_t static_dynamic = 0;      // ... classified dynamic
  std::int64_t slow_actor_dynamic = 0;  // dynamic returns on actors at most 0.5 m/s

  HitCounts& operator+=(const HitCounts& o);
};

class LidarHitScorer {
 public:
  static constexpr double kWarmUpS = 1.0;

  // `classes` and `truth` of the same scan. Beams beyond the truth's owners are ignored.
  void Observe(const lidar::ScanHitClasses& classes, const sim::TruthFrame& truth);
  void Report(std::map<std::string, double>& metrics) const;
  const HitCounts& counts() const { return counts_; }
  const HitCounts& counts_after_warm_up() const { return after_warm_up_; }

 private:
  HitCounts counts_;
  HitCounts after_warm_up_;
  std::optional<TimeNs> first_stamp_;
  std::int64_t frames_ = 0;
};

}  // namespace lookout::app
