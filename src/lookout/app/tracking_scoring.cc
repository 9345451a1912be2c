#include "lookout/app/tracking_scoring.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lookout/sim/shapes.h"

namespace lookout::app {
namespace {

bool InFan(const Pose2& mount, double fov_rad, const Eigen::Vector2d& vehicle_point,
           double max_range_m, bool depth) {
  const Eigen::Vector2d p = mount.Inverse() * vehicle_point;
  if (std::abs(std::atan2(p.y(), p.x())) > 0.5 * fov_rad) return false;
  // The camera's limit is a depth along its axis, the lidar's a range.
  return depth ? (p.x() > 0.0 && p.x() <= max_range_m) : p.norm() <= max_range_m;
}

// The tracks within the sensors' reach, in the world.
std::vector<eval::PointObject> TrackPoints(const std::vector<tracking::Track>& tracks,
                                           const Pose2& world_from_odom,
                                           const Pose2& vehicle_from_world,
                                           const SensorReach& reach) {
  std::vector<eval::PointObject> out;
  out.reserve(tracks.size());
  for (const tracking::Track& t : tracks) {
    const Eigen::Vector2d world = world_from_odom * t.Position();
    const Eigen::Vector2d vehicle = vehicle_from_world * world;
    if (!reach.InLidarReach(vehicle) && !reach.InCameraReach(vehicle)) continue;
    out.push_back({static_cast<std::int64_t>(t.id), world});
  }
  return out;
}

}  // namespace

SensorReach SensorReach::Of(const sim::Sensors& s, double grid_half_width_m) {
  SensorReach r;
  r.lidar_mount = Pose2(s.lidar.x_m, s.lidar.y_m, s.lidar.yaw_rad);
  r.camera_mount = Pose2(s.stereo.x_m, s.stereo.y_m, s.stereo.yaw_rad);
  r.lidar_fov_rad = s.lidar.fov_rad;
  r.lidar_range_m = std::min(s.lidar.max_range_m, grid_half_width_m);
  r.camera_fov_rad = s.stereo.fov_rad;
  r.camera_depth_m = s.stereo.max_depth_m;
  return r;
}

bool SensorReach::InLidarReach(const Eigen::Vector2d& p) const {
  return InFan(lidar_mount, lidar_fov_rad, p, lidar_range_m, false);
}

bool SensorReach::InCameraReach(const Eigen::Vector2d& p) const {
  return InFan(camera_mount, camera_fov_rad, p, camera_depth_m, true);
}

std::vector<bool> CountableActors(const sim::TruthFrame& truth, const SensorReach& reach,
                                  std::vector<bool>& seen) {
  const Pose2 vehicle_from_world = truth.ego.state.pose.Inverse();
  std::vector<bool> out;
  out.reserve(truth.actors.size());
  for (const sim::ActorTruth& a : truth.actors) {
    const Eigen::Vector2d p = vehicle_from_world * a.state.pose.translation;
    const bool lidar = reach.InLidarReach(p), camera = reach.InCameraReach(p);
    const auto i = static_cast<std::size_t>(a.index);
    if (seen.size() <= i) seen.resize(i + 1, false);
    if ((lidar && a.visible_fraction_lidar > 0.0) || (camera && a.visible_fraction_stereo > 0.0)) {
      seen[i] = true;
    }
    out.push_back(seen[i] && (lidar || camera));
  }
  return out;
}

bool AfterContact(const sim::TruthFrame& truth) {
  return std::any_of(truth.actors.begin(), truth.actors.end(), [&](const sim::ActorTruth& a) {
    return a.contact_time_s && ToSeconds(truth.stamp) >= *a.contact_time_s;
  });
}

std::vector<eval::PointObject> WithoutTracksOnUncountedActors(
    const std::vector<eval::PointObject>& tracks, const sim::TruthFrame& truth,
    const std::vector<bool>& countable, double match_distance_m) {
  std::vector<eval::PointObject> out;
  out.reserve(tracks.size());
  for (const eval::PointObject& t : tracks) {
    double nearest = std::numeric_limits<double>::infinity();
    bool nearest_counts = true;
    bool on_uncounted_footprint = false;
    for (std::size_t i = 0; i < truth.actors.size(); ++i) {
      const double d = (truth.actors[i].state.pose.translation - t.position_m).norm();
      if (d < nearest) {
        nearest = d;
        nearest_counts = countable[i];
      }
      if (!countable[i] && sim::Contains(truth.actors[i].footprint, t.position_m)) {
        on_uncounted_footprint = true;
      }
    }
    if ((nearest_counts || nearest > match_distance_m) && !on_uncounted_footprint) {
      out.push_back(t);
    }
  }
  return out;
}

TrackingScorer::TrackingScorer(const Pose2& world_from_odom, const SensorReach& reach)
    : world_from_odom_(world_from_odom), reach_(reach) {}

void TrackingScorer::Observe(const sim::TruthFrame& truth,
                             const std::vector<tracking::Track>& tracks,
                             const std::vector<tracking::Track>* baseline_tracks) {
  if (AfterContact(truth)) return;
  const std::vector<bool> countable = CountableActors(truth, reach_, seen_);
  std::vector<eval::PointObject> truths;
  for (std::size_t i = 0; i < truth.actors.size(); ++i) {
    if (countable[i]) {
      truths.push_back({truth.actors[i].index, truth.actors[i].state.pose.translation});
    }
  }
  const Pose2 vehicle_from_world = truth.ego.state.pose.Inverse();
  const double match_m = tracker_.options().match_distance_m;
  const auto scored = [&](const std::vector<tracking::Track>& t) {
    return WithoutTracksOnUncountedActors(
        TrackPoints(t, world_from_odom_, vehicle_from_world, reach_), truth, countable, match_m);
  };
  tracker_.AddFrame(truths, scored(tracks));
  if (baseline_tracks) {
    has_baseline_ = true;
    baseline_.AddFrame(truths, scored(*baseline_tracks));
  }
}

void TrackingScorer::Report(std::map<std::string, double>& metrics) const {
  for (const auto& [k, v] : tracker_.Values("tracking")) metrics[k] = v;
  if (has_baseline_) {
    for (const auto& [k, v] : baseline_.Values("tracking_baseline")) metrics[k] = v;
  }
}

}  // namespace lookout::app
