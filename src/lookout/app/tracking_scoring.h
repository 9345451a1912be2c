#pragma once

// Scores the tracks against the simulator's ground truth after every cycle: the tracking.*
// keys of docs/cli-contract.md (eval/tracking_metrics.h), and the same for the GNN baseline
// beside the tracker as tracking_baseline.*.
//
// Which true actors count, at a frame: those within the sensors' reach (the camera's field of
// view and depth, or the lidar's field of view within the grid's window, where lidar objects can
// come from), from the first frame at which a sensor saw them (visible fraction > 0 within that
// sensor's reach) on. Once seen, an actor counts whether it is visible or not: an occluded road
// user is still there, and the tracker is meant to coast through the occlusion. One never seen
// yet cannot be tracked by anyone, and is left out until it is. Tracks are scored over the same
// region: a track outside the sensors' reach (one coasting on behind the ego, say) is neither a
// match nor a false track, as the truth there is not counted either. Nor is a track on an actor
// that does not count (its nearest actor, within the match distance, or one whose footprint
// holds the track): a car whose centre has just left the lidar's fan while its front, where the
// track is, has not; a truck 33 m off, its centre beyond the camera's depth and the lidar's
// window, tracked on its front 2.9 m from its centre. The lidar objects' scoring treats an
// object on an actor that does not count by its nearest actor (docs/grid.md).
//
// Which frames count: those before the first contact of any actor with the ego (the truth's
// contact time). After it the simulator's actors drive on through the ego, which no real scene
// does: the lidar sees a car inside the ego's box, and the trackers follow what it makes of it.
//
// What is compared: the actor's footprint centre and the track's position (the tracking stage
// tracks centres, app/tracking_stage.h), in the world: the track through the odometry frame's
// true pose, so that dead-reckoning drift counts as track error, as it would on a real car.

#include <map>
#include <string>
#include <vector>

#include "lookout/core/pose2.h"
#include "lookout/eval/tracking_metrics.h"
#include "lookout/sim/scenario.h"
#include "lookout/sim/truth.h"
#include "lookout/tracking/tracker.h"

namespace lookout::app {

struct SensorReach {
  Pose2 lidar_mount, camera_mount;  // in the vehicle frame
  double lidar_fov_rad = 0.0, lidar_range_m = 0.0;
  double camera_fov_rad = 0.0, camera_depth_m = 0.0;

  // The scenario's sensors, the lidar's range cut to the grid's window (half its side).
  static SensorReach Of(const sim::Sensors& sensors, double grid_half_width_m);
  bool InLidarReach(const Eigen::Vector2d& vehicle_point) const;
  bool InCameraReach(const Eigen::Vector2d& vehicle_point) const;
};

// Which actors of `truth` count (indexed as truth.actors), updating `seen` (indexed by the
// actor's scenario index; grown as needed). Uses the true ego pose.
std::vector<bool> CountableActors(const sim::TruthFrame& truth, const SensorReach& reach,
                                  std::vector<bool>& seen);

// `tracks` (world) without those whose nearest actor of `truth` does not count (`countable`,
// indexed as truth.actors) and lies within `match_distance_m` of them, and those inside the
// footprint of an actor that does not count. Pure.
// Whether an actor of `truth` has touched the ego by its stamp. Pure.
bool AfterContact(const sim::TruthFrame& truth);

std::vector<eval::PointObject> WithoutTracksOnUncountedActors(
    const std::vector<eval::PointObject>& tracks, const sim::TruthFrame& truth,
    const std::vector<bool>& countable, double match_distance_m);

class TrackingScorer {
 public:
  TrackingScorer(const Pose2& world_from_odom, const SensorReach& reach);

  // After a cycle in which the trackers ran: the truth at the same stamp, the tracker's
  // confirmed tracks and the baseline's (nullptr: no baseline). A frame at or after a contact
  // is not scored.
  void Observe(const sim::TruthFrame& truth, const std::vector<tracking::Track>& tracks,
               const std::vector<tracking::Track>* baseline_tracks);

  void Report(std::map<std::string, double>& metrics) const;

 private:
  Pose2 world_from_odom_;
  SensorReach reach_;
  std::vector<bool> seen_;
  eval::TrackingMetricsAccumulator tracker_, baseline_;
  bool has_baseline_ = false;
};

}  // namespace lookout::app
