#include "lookout/lidar/slam.h"

#include <cmath>
#include <limits>

#include "lookout/lidar/localiser.h"
#include "lookout/lidar/scan_matcher.h"

namespace lookout::lidar {
namespace {

bool Finite(const Pose2& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.yaw);
}

}  // namespace

SlamResult RunSlam(std::span<const SlamRecord> records, const SlamOptions& options,
                   bool odometry_only) {
  options.Validate();
  SlamResult result;
  result.trajectory.reserve(records.size());
  LidarLocaliser localiser(options);
  // Odometry-only mapping uses a map of its own (the localiser's is not fed).
  LocalMap odometry_map(options.map);

  std::optional<Pose2> last_estimate;
  Pose2 last_scan_odometry;
  double last_t = -std::numeric_limits<double>::infinity();
  for (const SlamRecord& r : records) {
    if (!Finite(r.odometry) || !std::isfinite(r.t_s) || r.t_s < last_t) {
      ++result.records_refused;
      continue;
    }
    last_t = r.t_s;
    Pose2 pose = r.odometry;
    if (r.scan) {
      LidarScan scan = *r.scan;
      scan.stamp = FromSeconds(r.t_s);
      if (odometry_only) {
        const ScanPoints points = ExtractScanPoints(scan, options.matcher);
        std::vector<Eigen::Vector2d> hits;
        hits.reserve(points.all.size());
        for (const Eigen::Vector2d& p : points.all) hits.push_back(pose * p);
        odometry_map.RecentreOn(pose.translation);
        odometry_map.InsertScan(pose * scan.mount.translation, hits, {});
        EgoState state;
        state.stamp = scan.stamp;
        state.pose = pose;
        result.scan_states.push_back(state);
        ++result.scans_used;
      } else if (const std::optional<EgoState> state = localiser.AddScan(scan, r.odometry)) {
        pose = state->pose;
        last_estimate = pose;
        last_scan_odometry = r.odometry;
        result.scan_states.push_back(*state);
        ++result.scans_used;
      } else if (last_estimate) {  // a scan the localiser refused: odometry since the last
        pose = *last_estimate * (last_scan_odometry.Inverse() * r.odometry);
      }
    } else if (!odometry_only) {
      localiser.AddOdometry(FromSeconds(r.t_s), r.odometry);
      if (last_estimate) pose = *last_estimate * (last_scan_odometry.Inverse() * r.odometry);
    }
    pose.yaw = WrapAngle(pose.yaw);
    result.trajectory.push_back({r.t_s, pose});
  }
  result.map = odometry_only ? odometry_map.Raster() : localiser.map().Raster();
  return result;
}

}  // namespace lookout::lidar
