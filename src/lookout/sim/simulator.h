#pragma once

// The scenario simulator: world, actors, ego, and the sensors of the seed 004 vehicle (lidar,
// stereo objects, odometry), with ground truth for everything. Deterministic: every random
// draw comes from an Rng seeded by (scenario seed, sensor, frame index), so a frame does not
// depend on which thread simulates it.

#include <vector>

#include "lookout/core/messages.h"
#include "lookout/sim/scenario.h"
#include "lookout/sim/shapes.h"
#include "lookout/sim/trajectory.h"
#include "lookout/sim/truth.h"

namespace lookout::sim {

// Everything the sensors produced over the scenario, each stream in time order. Frame k of a
// sensor is taken at k / rate_hz for every such time within [0, duration].
struct SensorLog {
  std::vector<LidarScan> lidar;
  std::vector<StereoFrame> stereo;
  std::vector<EgoOdometry> odometry;
  std::vector<TruthFrame> truth;  // one per lidar frame, same stamps
};

class Simulator {
 public:
  explicit Simulator(Scenario scenario);

  const Scenario& scenario() const { return scenario_; }
  const std::vector<Shape>& static_world() const { return static_world_; }
  const Trajectory& ego_trajectory() const { return ego_; }
  const std::vector<Trajectory>& actor_trajectories() const { return actors_; }
  // Per actor (Scenario::actors order): when its footprint first touches the ego's, if ever.
  const std::vector<std::optional<double>>& contact_times_s() const { return contact_time_s_; }

  // Ground truth at time t, visible fractions included. Pure and thread-safe.
  TruthFrame Truth(TimeNs t) const;
  // Frame k of each sensor. Pure and thread-safe (the stereo history count is filled by Run).
  LidarScan SimulateLidar(int k) const;
  StereoFrame SimulateStereo(int k) const;
  EgoOdometry SimulateOdometry(int k) const;

  // All frames of all sensors; the same bytes for any `threads` >= 1.
  SensorLog Run(int threads) const;

 private:
  Scenario scenario_;
  std::vector<Shape> static_world_;
  Trajectory ego_;
  std::vector<Trajectory> actors_;
  std::vector<std::optional<double>> contact_time_s_;  // per actor
};

}  // namespace lookout::sim
