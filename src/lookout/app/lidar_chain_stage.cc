#include "lookout/app/lidar_chain_stage.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "lookout/lidar/dynamic_segments.h"

namespace lookout::app {
namespace {

using Clock = std::chrono::steady_clock;

double MsBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

const lidar::SlamOptions& Validated(const lidar::LidarChainOptions& options) {
  options.Validate();
  return options.localiser;
}

}  // namespace

LidarChainStage::LidarChainStage(const lidar::LidarChainOptions& options,
                                 const DeadReckoningOptions& odometry)
    : options_(options), odometry_(odometry), localiser_(Validated(options)) {
  if (options_.far_map_enabled) far_map_.emplace(options_.far_map);
}

void LidarChainStage::OnOdometry(const EgoOdometry& odometry) {
  if (!odometry_.Add(odometry)) return;
  // The localiser composes its latest scan estimate with the odometry since, for poses
  // between scans: it gets the dead-reckoned pose at each reading.
  localiser_.AddOdometry(odometry.stamp, odometry_.At(odometry.stamp).pose);
}

void LidarChainStage::OnLidar(const LidarScan& scan) {
  if (last_stamp_ && scan.stamp <= *last_stamp_) {
    ++refused_scans_;
    return;
  }
  const std::optional<EgoState> odometry = odometry_.PoseAt(scan.stamp);
  if (!odometry) {
    ++skipped_scans_;
    return;
  }
  const Clock::time_point start = Clock::now();
  const std::optional<EgoState> state = localiser_.LocaliseScan(scan, odometry->pose);
  if (!state) {  // the localiser's own refusals: time going back, non-finite odometry
    ++refused_scans_;
    return;
  }
  const Clock::time_point localised = Clock::now();
  hits_ = lidar::ClassifyHits(localiser_.map(), scan, state->pose, options_.hits);
  if (far_map_) {
    lidar::ClassifyFarHits(*far_map_, scan, state->pose, options_.localiser.map.max_insert_range_m,
                           options_.far_static_tolerance_m, options_.hits, hits_);
  }
  no_returns_ += hits_.no_return_count;
  const Clock::time_point classified = Clock::now();
  const std::vector<std::uint8_t> on_moving_trace =
      previous_segments_ ? lidar::StaticOnMovingTrace(*previous_segments_, scan, state->pose,
                                                      hits_.beam, options_.segment_motion)
                         : std::vector<std::uint8_t>{};
  // Returns the map holds that are no mover's trace: they make no trace for the next scan.
  std::vector<std::uint8_t> standing(hits_.beam.size(), 0);
  for (std::size_t i = 0; i < standing.size(); ++i) {
    standing[i] = lidar::IsStanding(hits_.beam, on_moving_trace, i);
  }
  const std::vector<lidar::ScanCluster> clusters = lidar::ClusterScan(
      scan, hits_.beam, options_.segmentation, options_.hits.min_range_m, nullptr, on_moving_trace);
  // Motion the map cannot see (lidar/segment_motion.h), before the objects take the classes.
  const std::vector<bool> own_motion =
      lidar::OwnMotionEvidence(clusters, hits_.beam, options_.segment_motion);
  std::vector<int> carried(clusters.size(), -1);
  if (previous_segments_ && options_.segment_motion.enabled) {
    lidar::MarkVacatedSegments(
        lidar::VacatedReturns(*previous_segments_, scan, state->pose, options_.segment_motion,
                              options_.hits.min_range_m),
        options_.segment_motion, *previous_segments_);
    carried = lidar::CarrySegmentMotion(*previous_segments_, scan, state->pose, clusters,
                                        options_.segment_motion, hits_);
  }
  last_objects_ = lidar::DescribeClusters(scan, clusters, hits_.beam, state->pose,
                                          options_.segmentation);
  // The map takes the propagated classes: a slow actor's returns that land on its own trace
  // (static) stay out of it, so the trace does not follow the actor. The rule's thresholds
  // keep a wall with a stray dynamic return in the map (docs/lidar-chain.md).
  lidar::PropagateDynamicSegments(scan, clusters, options_.dynamic_segments, hits_);
  previous_segments_ =
      lidar::DescribeSegments(scan, state->pose, clusters, own_motion, carried, standing);
  const Clock::time_point segmented = Clock::now();
  std::vector<bool> unmapped;
  if (options_.map_static_only && options_.unmap_dynamic_segments) {
    unmapped.assign(scan.ranges_m.size(), false);
    for (const lidar::ScanCluster& c : clusters) {
      if (!lidar::HasDynamicBeam(c, hits_.beam)) continue;
      for (std::size_t i : c.beams) unmapped[i] = true;
    }
  }
  MapScan(scan, state->pose, unmapped);
  const Clock::time_point mapped = Clock::now();
  localise_ms_.push_back(MsBetween(start, localised));
  hits_ms_.push_back(MsBetween(localised, classified) + MsBetween(segmented, mapped));
  segment_ms_.push_back(MsBetween(classified, segmented));
  last_stamp_ = scan.stamp;
  last_state_ = state;
}

void LidarChainStage::MapScan(const LidarScan& scan, const Pose2& pose,
                              const std::vector<bool>& unmapped) {
  const std::size_t n = scan.ranges_m.size();
  const double min_range = options_.hits.min_range_m;
  // How far each beam may clear: up to the nearer of its neighbours' returns, less the margin
  // (LidarChainOptions::neighbour_clear_margin_m), when that is nearer than its own.
  std::vector<double> clear_to(n, std::numeric_limits<double>::infinity());
  if (options_.neighbour_clear_margin_m >= 0.0) {
    for (std::size_t i = 0; i < n; ++i) {
      for (const std::size_t j : {i - 1, i + 1}) {  // i - 1 wraps past n at i = 0
        if (j >= n || !lidar::IsReturn(scan, j, min_range)) continue;
        const double r = static_cast<double>(scan.ranges_m[j]) - options_.neighbour_clear_margin_m;
        clear_to[i] = std::min(clear_to[i], std::max(r, 0.0));
      }
    }
  }
  const auto along = [&scan](std::size_t i, double r) {
    const double a = scan.BeamAngle(i);
    return scan.mount * Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
  };
  std::vector<Eigen::Vector2d> hits;
  std::vector<Eigen::Vector2d> bare_hits;
  std::vector<Eigen::Vector2d> free_ends;
  std::vector<Eigen::Vector2d> empty_ends;
  std::vector<Eigen::Vector2d> far_empty_ends;  // the far map's reach, not no_return_clear_m
  hits.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const lidar::HitClass k = hits_.beam[i];
    if (k == lidar::HitClass::kNoReturn) {
      if (options_.no_return_clear_m > 0.0 && lidar::IsEmptyBeam(scan, i)) {
        // An empty beam's ray up to `reach`, its neighbours' returns and the scanner's range.
        const auto add_empty = [&](double reach, std::vector<Eigen::Vector2d>& ends) {
          double r = std::min(reach, clear_to[i]);
          if (scan.max_range_m > 0.0) r = std::min(r, scan.max_range_m);
          if (r > 0.0) ends.push_back(along(i, r));
        };
        add_empty(options_.no_return_clear_m, empty_ends);
        if (far_map_) add_empty(options_.far_map.max_insert_range_m, far_empty_ends);
      }
      continue;
    }
    const double range = static_cast<double>(scan.ranges_m[i]);
    const bool clears_only = options_.map_static_only &&
                             (k == lidar::HitClass::kDynamic || (!unmapped.empty() && unmapped[i]));
    if (clears_only) {
      const double r = std::min(range - options_.dynamic_ray_margin_m, clear_to[i]);
      if (r > 0.0) free_ends.push_back(along(i, r));
    } else if (clear_to[i] < range) {
      bare_hits.push_back(along(i, range));
      if (clear_to[i] > 0.0) free_ends.push_back(along(i, clear_to[i]));
    } else {
      hits.push_back(along(i, range));
    }
  }
  localiser_.MapScan(scan, hits, free_ends, empty_ends, bare_hits);
  if (!far_map_) return;
  const auto to_map = [&pose](std::vector<Eigen::Vector2d>& points) {
    for (Eigen::Vector2d& p : points) p = pose * p;
  };
  for (auto* points : {&hits, &free_ends, &far_empty_ends, &bare_hits}) to_map(*points);
  far_map_->RecentreOn(pose.translation);
  far_map_->InsertScan(pose * scan.mount.translation, hits, free_ends, far_empty_ends, bare_hits);
}

}  // namespace lookout::app
