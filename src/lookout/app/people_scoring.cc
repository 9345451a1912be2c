#include "lookout/app/people_scoring.h"

#include <cmath>
#include <limits>
#include <utility>

namespace lookout::app {

PeopleScorer::PeopleScorer(std::string prefix, const PeopleScoringOptions& options)
    : prefix_(std::move(prefix)), options_(options) {}

void PeopleScorer::Observe(const io::PeopleFrame& people, const Pose2& lidar_mount,
                           const LidarObjectFrame* objects) {
  const Pose2 lidar_from_vehicle = lidar_mount.Inverse();
  for (const io::AnnotatedPerson& p : people.people) {
    double nearest_dynamic = std::numeric_limits<double>::infinity();
    double nearest_any = std::numeric_limits<double>::infinity();
    if (objects) {
      for (const LidarObject& o : objects->objects) {
        const double d = (o.centroid_m - p.position_m).norm();
        nearest_any = std::min(nearest_any, d);
        if (o.dynamic) nearest_dynamic = std::min(nearest_dynamic, d);
      }
    }
    const Eigen::Vector2d in_lidar = lidar_from_vehicle * p.position_m;
    const double bearing = std::atan2(in_lidar.y(), in_lidar.x());
    const bool in_sector = bearing >= options_.sector_min_rad && bearing <= options_.sector_max_rad;
    for (Counts* c : {&all_, in_sector ? &sector_ : nullptr}) {
      if (!c) continue;
      ++c->positions;
      if (nearest_dynamic <= options_.match_distance_m) ++c->near_dynamic;
      if (nearest_any <= options_.match_distance_m) ++c->near_any;
    }
  }
}

void PeopleScorer::Report(std::map<std::string, double>& metrics) const {
  const auto report = [&](const Counts& c, const std::string& stem) {
    if (c.positions == 0) return;
    const double n = static_cast<double>(c.positions);
    metrics[prefix_ + "." + stem + "positions"] = n;
    metrics[prefix_ + "." + stem + "dynamic_share"] = static_cast<double>(c.near_dynamic) / n;
    metrics[prefix_ + "." + stem + "any_share"] = static_cast<double>(c.near_any) / n;
  };
  report(all_, "");
  report(sector_, "sector_");
}

PeopleTrackingScorer::PeopleTrackingScorer(std::string prefix,
                                           const PeopleScoringOptions& options)
    : prefix_(std::move(prefix)),
      options_(options),
      accumulator_(eval::TrackingMetricOptions{options.track_match_distance_m, {}}) {}

bool PeopleTrackingScorer::InSector(const Pose2& lidar_from_vehicle,
                                    const Eigen::Vector2d& vehicle_point) const {
  const Eigen::Vector2d p = lidar_from_vehicle * vehicle_point;
  const double bearing = std::atan2(p.y(), p.x());
  return bearing >= options_.sector_min_rad && bearing <= options_.sector_max_rad;
}

void PeopleTrackingScorer::Observe(const io::PeopleFrame* people, const Pose2& lidar_mount,
                                   const Pose2& ego_pose,
                                   const std::vector<tracking::Track>& tracks) {
  const Pose2 lidar_from_vehicle = lidar_mount.Inverse();
  const Pose2 vehicle_from_odom = ego_pose.Inverse();
  std::vector<eval::PointObject> truths, hypotheses;
  if (people) {
    for (const io::AnnotatedPerson& p : people->people) {
      if (InSector(lidar_from_vehicle, p.position_m)) {
        truths.push_back({static_cast<std::int64_t>(p.id), p.position_m});
      }
    }
  }
  for (const tracking::Track& t : tracks) {
    const Eigen::Vector2d in_vehicle = vehicle_from_odom * t.Position();
    if (InSector(lidar_from_vehicle, in_vehicle)) {
      hypotheses.push_back({static_cast<std::int64_t>(t.id), in_vehicle});
    }
  }
  accumulator_.AddFrame(truths, hypotheses);
  ++frames_;
}

void PeopleTrackingScorer::Report(std::map<std::string, double>& metrics) const {
  if (frames_ == 0) return;
  for (const auto& [key, value] : accumulator_.Values(prefix_)) metrics[key] = value;
}

}  // namespace lookout::app
