#pragma once

// The grid.* metric keys of cli-contract.md: the extended grid's belief scored against the
// simulator's truth raster. Pure per-frame functions return sums and counts; small accumulator
// classes add them over frames and give the metric value.
//
// Frames: the belief and the truth must be rasterised on the SAME GridGeometry (same origin,
// cell size and size) in the SAME frame. The grid lives in the odometry frame; in the simulator
// odometry and world coincide when the grid is fed the true pose. When they do not, the caller
// must express the truth in the odometry frame first (TruthFrameIn, ShapesIn below).

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "lookout/core/grid_geometry.h"
#include "lookout/core/pose2.h"
#include "lookout/core/time.h"
#include "lookout/sim/shapes.h"
#include "lookout/sim/truth.h"

namespace lookout::eval {

// A snapshot of the grid's belief, cells in window order (index = iy * width + ix over
// `geometry`, as ScrollingGridGeometry::WindowGeometry and GridLayers::CopyInWindowOrder give).
// Every layer holds geometry.CellCount() values.
struct GridBelief {
  GridGeometry geometry;
  std::vector<float> occupancy;            // O(x), probability in [0, 1]
  std::vector<float> velocity_x_mps;       // V(x), along the frame's x
  std::vector<float> velocity_y_mps;       // V(x), along the frame's y
  std::vector<float> velocity_confidence;  // conf(x) in [0, 1]
};

// Thresholds of the definitions below. The defaults are those of cli-contract.md.
struct GridMetricOptions {
  // Believed occupied: O > occupied_probability (contract: O > 0.5).
  double occupied_probability = 0.5;
  // Truly moving: true cell speed > moving_speed_mps; estimated dynamic: estimated speed >
  // moving_speed_mps (contract: 0.5 m/s for both).
  double moving_speed_mps = 0.5;
  // "With confidence": velocity_confidence >= confident_velocity. 0.5: the grid holds the
  // velocity more likely than not (a newly born cell has confidence 0).
  double confident_velocity = 0.5;
  // Retention: the region around an actor whose belief counts as the actor's (contract: 1 m).
  double retention_radius_m = 1.0;
  // Retention: the actor is kept while its evidence mass is at least this share of the largest
  // mass it had over its last visible run...
  double retention_mass_fraction = 0.5;
  // ...and at least this many cell-equivalents (so an actor the grid never built up is not
  // "kept" by noise). One fully occupied cell is 1.
  double retention_min_mass_cells = 1.0;

  // Throws std::invalid_argument naming the first field out of range.
  void Validate() const;
};

// The truth expressed in another frame, for a grid that does not live in the world frame:
// every pose and footprint mapped by target_from_world (velocities follow, as they derive from
// the headings; yaw rates are unchanged). For a grid in the odometry frame fed a pose estimate:
// target_from_world = odom_from_base(estimate) * world_from_base(truth).Inverse(). Rasterise the
// result (with ShapesIn(static world)) on the belief's geometry.
sim::TruthFrame TruthFrameIn(const sim::TruthFrame& frame, const Pose2& target_from_world);
std::vector<sim::Shape> ShapesIn(const std::vector<sim::Shape>& shapes,
                                 const Pose2& target_from_world);

// Euclidean distance from p to the closed shape (0 inside or on it), m.
double DistanceToShape(const sim::Shape& shape, const Eigen::Vector2d& p);

// --- per-frame sums (pure functions). Each throws std::invalid_argument when the belief's
// layers do not match its geometry, or the truth (mask) is on another geometry.

struct SquaredErrorSum {
  double sum_squared = 0.0;
  std::int64_t count = 0;
};

// Which actors (by truth owner index) a velocity error may be counted for.
using OwnerFilter = std::function<bool(int owner)>;

// grid.velocity_rmse_mps, one frame: sum over cells truly occupied by an actor whose true cell
// speed exceeds moving_speed_mps and believed occupied, of |V_est - V_true|^2 (m^2/s^2).
// Confidence does not enter: the contract scores the velocity the grid reports. An empty
// `counting_allowed` counts every actor.
SquaredErrorSum VelocitySquaredErrors(const GridBelief& belief, const sim::TruthRaster& truth,
                                      const GridMetricOptions& options = {},
                                      const OwnerFilter& counting_allowed = {});

struct FalseDynamicCount {
  std::int64_t static_cells = 0;         // truly static world, occupied and believed occupied
  std::int64_t false_dynamic_cells = 0;  // of those, estimated speed > moving_speed_mps with
                                         // confidence >= confident_velocity
};

// grid.static_false_dynamic_rate, one frame. "Truly static" is the static world (truth owner
// sim::kStaticOwner): actors standing still are scored by neither this nor the RMSE.
FalseDynamicCount CountFalseDynamic(const GridBelief& belief, const sim::TruthRaster& truth,
                                    const GridMetricOptions& options = {});

// grid.occupancy_brier, one frame: sum over cells with in_range[i] != 0 of (O - truth)^2, truth
// 1 for occupied cells and 0 otherwise. Unobserved cells inside the range count (a grid that
// says 0.5 there pays 0.25 a cell): the contract scores "within the lidar's range".
SquaredErrorSum OccupancySquaredErrors(const GridBelief& belief, const sim::TruthRaster& truth,
                                       std::span<const std::uint8_t> in_range);

// The in-range mask for OccupancySquaredErrors: 1 for cells whose centre lies within
// max_range_m of the sensor (<=), 0 otherwise. Window order over `geometry`.
std::vector<std::uint8_t> WithinRangeMask(const GridGeometry& geometry,
                                          const Eigen::Vector2d& sensor_position_m,
                                          double max_range_m);

// Evidence mass: how many fully occupied cells' worth of occupancy above "unknown" the belief
// holds around an actor. Each cell contributes max(0, 2 O - 1) in [0, 1], so unknown (0.5) and
// free cells add nothing: an occluded region is 0.5 everywhere, and a plain sum of O over it
// would "keep" any actor. Cells counted: those whose centre lies within radius_m of the
// footprint (distance to the shape, 0 inside it) and that the truth does not give to another
// owner (the static world or another actor), so that the occluder's own occupancy is not
// credited to the hidden actor.
double ActorEvidenceMass(const GridBelief& belief, const sim::TruthRaster& truth,
                         const sim::Shape& footprint, int owner, double radius_m);

// --- accumulators over frames

// grid.velocity_rmse_mps over a run: sqrt(sum of squared errors / count) over every counted
// cell of every frame (cells, not frames, are weighted equally).
class VelocityRmseAccumulator {
 public:
  explicit VelocityRmseAccumulator(const GridMetricOptions& options = {}) : options_(options) {}
  void AddFrame(const GridBelief& belief, const sim::TruthRaster& truth,
                const OwnerFilter& counting_allowed = {});
  // nullopt before any cell was counted.
  std::optional<double> Value() const;
  std::int64_t cells() const { return total_.count; }

 private:
  GridMetricOptions options_;
  SquaredErrorSum total_;
};

// grid.static_false_dynamic_rate over a run: false dynamic cells / static cells, all frames.
class FalseDynamicAccumulator {
 public:
  explicit FalseDynamicAccumulator(const GridMetricOptions& options = {}) : options_(options) {}
  void AddFrame(const GridBelief& belief, const sim::TruthRaster& truth);
  std::optional<double> Value() const;  // nullopt before any static cell was counted
  const FalseDynamicCount& counts() const { return total_; }

 private:
  GridMetricOptions options_;
  FalseDynamicCount total_;
};

// grid.occupancy_brier over a run: the mean over every in-range cell of every frame.
class OccupancyBrierAccumulator {
 public:
  void AddFrame(const GridBelief& belief, const sim::TruthRaster& truth,
                std::span<const std::uint8_t> in_range);
  std::optional<double> Value() const;  // nullopt before any cell was counted

 private:
  SquaredErrorSum total_;
};

// When each actor was first seen by the lidar inside the grid's window (visible_fraction_lidar
// > 0 with its footprint centre in the window), for the velocity RMSE "after the first second
// of visibility": feed it every truth frame in time order, then ask with the stamp of the frame
// being scored. Inside the window: the grid measures nothing of an actor before it enters, however
// long the lidar has seen it beyond (a 20 m/s car in view from 120 m crosses the 60 m window in
// 1.2 s; counted from its first sight by the lidar, its whole passage is "after the first
// second", its first cells in the grid included).
class ActorVisibilityClock {
 public:
  void Observe(const sim::TruthFrame& frame, const GridGeometry& window);
  std::optional<TimeNs> FirstVisible(int owner) const;
  // True when the actor was first visible at least min_visible_s before `now`.
  bool VisibleForAtLeast(int owner, double min_visible_s, TimeNs now) const;
  // An OwnerFilter for VelocityRmseAccumulator::AddFrame; valid while the clock lives.
  OwnerFilter AfterFirstVisible(double min_visible_s, TimeNs now) const;

 private:
  std::map<int, TimeNs> first_visible_;
};

// grid.occluded_retention_s: the longest time an occluded actor keeps believed occupancy mass
// within retention_radius_m of its true position. Definitions, per actor:
//   - occluded: present in the truth frame with visible_fraction_lidar == 0, its footprint
//     centre inside the grid, after having been visible at least once (a grid cannot retain
//     what it never saw). Consecutive occluded frames form one occlusion episode; leaving the
//     grid, leaving the scene or becoming visible again ends it.
//   - reference mass: the largest ActorEvidenceMass over the visible frames just before the
//     episode (the run of frames with visible_fraction_lidar > 0 that precedes it), so that a
//     brief partial occlusion before full occlusion does not lower the bar.
//   - kept (at an occluded frame): ActorEvidenceMass >= max(retention_mass_fraction *
//     reference, retention_min_mass_cells).
//   - retention of an episode: from the stamp of its first occluded frame to the stamp of the
//     first frame that breaks the run of kept frames (not kept, visible again, gone, or out of
//     the grid). If the run lasts to the last frame given, it ends at that frame's stamp. An
//     episode whose first occluded frame is not kept retains 0 s.
// The value is the longest retention over all episodes of all actors.
class OccludedRetentionAccumulator {
 public:
  explicit OccludedRetentionAccumulator(const GridMetricOptions& options = {})
      : options_(options) {}
  // Frames in increasing stamp order, in the belief's frame (TruthFrameIn); `truth` rasterised
  // from `frame` on belief.geometry.
  void AddFrame(const sim::TruthFrame& frame, const GridBelief& belief,
                const sim::TruthRaster& truth);
  // nullopt when no actor was ever occluded after being seen.
  std::optional<double> Value() const;
  // Longest retention per actor index (only actors that had an occlusion episode).
  std::map<int, double> PerActorSeconds() const;

 private:
  struct ActorState {
    bool seen = false;              // visible at least once
    bool visible_last = false;      // visible in the last frame it was present in
    double visible_run_mass = 0.0;  // max evidence mass over the current/last visible run
    bool in_episode = false;
    bool run_kept = false;  // the episode's run of kept frames still goes on
    double reference_mass = 0.0;
    TimeNs episode_start = 0;
    std::optional<double> longest_s;
  };
  void CloseRun(ActorState& state, TimeNs end) const;

  GridMetricOptions options_;
  std::map<int, ActorState> actors_;
  TimeNs last_frame_stamp_ = 0;
};

}  // namespace lookout::eval
