#include "lookout/lidar/segment_motion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lookout/core/input_error.h"
#include "lookout/lidar/dynamic_segments.h"

namespace lookout::lidar {
namespace {

// Whether beam j of `scan` reaches further than `range_m`: a return beyond it, or an empty beam
// when range_m is inside the scanner's range. NaN, negative and too-near beams say nothing.
bool ReachesPast(const LidarScan& scan, std::size_t j, double range_m, double min_range_m) {
  if (IsReturn(scan, j, min_range_m)) return static_cast<double>(scan.ranges_m[j]) > range_m;
  if (!IsEmptyBeam(scan, j)) return false;
  return scan.max_range_m <= 0.0 || range_m < scan.NoReturnRangeM();
}

struct Box {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = Eigen::Vector2d::Constant(-std::numeric_limits<double>::infinity());
  void Add(const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool Within(const Box& o, double d) const {
    return lo.x() - d <= o.hi.x() && o.lo.x() - d <= hi.x() && lo.y() - d <= o.hi.y() &&
           o.lo.y() - d <= hi.y();
  }
};

}  // namespace

void SegmentMotionOptions::Validate(const std::string& source) const {
  const auto non_negative = [&source](double v, const char* field) {
    if (!std::isfinite(v) || v < 0.0) throw InputError(source, 0, field, "must be finite, >= 0");
  };
  const auto share = [&source](double v, const char* field) {
    if (!std::isfinite(v) || v < 0.0 || v > 1.0)
      throw InputError(source, 0, field, "must be in [0, 1]");
  };
  non_negative(seen_through_margin_m, "seen_through_margin_m");
  non_negative(max_step_m, "max_step_m");
  non_negative(max_chord_m, "max_chord_m");
  non_negative(trace_radius_m, "trace_radius_m");
  share(min_vacated_share, "min_vacated_share");
  share(max_static_share, "max_static_share");
  if (min_vacated_returns < 1) throw InputError(source, 0, "min_vacated_returns", "must be >= 1");
  if (max_carried_scans < 0) throw InputError(source, 0, "max_carried_scans", "must be >= 0");
}

std::vector<bool> VacatedReturns(const ScanSegments& previous, const LidarScan& scan,
                                 const Pose2& vehicle_pose, const SegmentMotionOptions& options,
                                 double min_range_m) {
  std::vector<bool> vacated(previous.points.size(), false);
  const std::size_t n = scan.ranges_m.size();
  if (n < 2 || !(scan.angle_increment_rad > 0.0)) return vacated;
  const Pose2 to_sensor = (vehicle_pose * scan.mount).Inverse();
  for (std::size_t k = 0; k < previous.points.size(); ++k) {
    const Eigen::Vector2d q = to_sensor * previous.points[k];
    // Fractional beam index of the bearing; outside the field of view nothing is seen.
    const double f = (std::atan2(q.y(), q.x()) - scan.angle_min_rad) / scan.angle_increment_rad;
    if (!(f >= 0.0) || f >= static_cast<double>(n - 1)) continue;
    const auto j = static_cast<std::size_t>(f);
    const double past = q.norm() + options.seen_through_margin_m;
    vacated[k] =
        ReachesPast(scan, j, past, min_range_m) && ReachesPast(scan, j + 1, past, min_range_m);
  }
  return vacated;
}

void MarkVacatedSegments(const std::vector<bool>& vacated, const SegmentMotionOptions& options,
                         ScanSegments& previous) {
  const std::size_t segments = previous.moving.size();
  std::vector<std::size_t> returns(segments, 0);
  std::vector<std::size_t> seen_through(segments, 0);
  for (std::size_t k = 0; k < previous.points.size(); ++k) {
    ++returns[previous.segment[k]];
    if (k < vacated.size() && vacated[k]) ++seen_through[previous.segment[k]];
  }
  for (std::size_t s = 0; s < segments; ++s) {
    const auto v = static_cast<double>(seen_through[s]);
    if (seen_through[s] >= static_cast<std::size_t>(options.min_vacated_returns) &&
        v >= options.min_vacated_share * static_cast<double>(returns[s])) {
      previous.moving[s] = true;
      previous.carried_scans[s] = 0;
    }
  }
}

std::vector<bool> OwnMotionEvidence(std::span<const ScanCluster> clusters,
                                    std::span<const HitClass> classes,
                                    const SegmentMotionOptions& options) {
  std::vector<bool> own(clusters.size(), false);
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    const auto dynamic =
        std::count_if(clusters[c].beams.begin(), clusters[c].beams.end(),
                      [&](std::size_t i) { return classes[i] == HitClass::kDynamic; });
    own[c] = dynamic >= options.min_vacated_returns;
  }
  return own;
}

std::vector<int> CarrySegmentMotion(const ScanSegments& previous, const LidarScan& scan,
                                    const Pose2& vehicle_pose,
                                    std::span<const ScanCluster> clusters,
                                    const SegmentMotionOptions& options, ScanHitClasses& classes) {
  std::vector<int> carried(clusters.size(), -1);
  if (!options.enabled) return carried;
  // The segments that carry: their returns and boxes.
  const std::size_t segments = previous.moving.size();
  std::vector<std::vector<std::size_t>> returns_of(segments);
  for (std::size_t k = 0; k < previous.points.size(); ++k) {
    const std::size_t s = previous.segment[k];
    if (previous.moving[s] && previous.carried_scans[s] < options.max_carried_scans) {
      returns_of[s].push_back(k);
    }
  }
  std::vector<std::size_t> carriers;
  std::vector<Box> boxes(segments);
  for (std::size_t s = 0; s < segments; ++s) {
    if (returns_of[s].empty()) continue;
    carriers.push_back(s);
    for (std::size_t k : returns_of[s]) boxes[s].Add(previous.points[k]);
  }
  if (carriers.empty()) return carried;

  // Mutual nearest within max_step_m, by the distance between the nearest returns.
  constexpr double kFar = std::numeric_limits<double>::infinity();
  const double step2 = options.max_step_m * options.max_step_m;
  std::vector<double> best_of_segment(segments, kFar);
  std::vector<std::size_t> nearest_of_segment(segments, clusters.size());
  std::vector<std::size_t> nearest_of_cluster(clusters.size(), segments);
  std::vector<Eigen::Vector2d> points;
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    const ScanCluster& cluster = clusters[c];
    if (cluster.beams.empty()) continue;
    const Eigen::Vector2d chord =
        ReturnPoint(scan, cluster.beams.back()) - ReturnPoint(scan, cluster.beams.front());
    if (chord.norm() > options.max_chord_m) continue;
    points.clear();
    Box box;
    std::size_t statics = 0;
    for (std::size_t i : cluster.beams) {
      points.push_back(vehicle_pose * ReturnPoint(scan, i));
      box.Add(points.back());
      if (classes.beam[i] == HitClass::kStatic) ++statics;
    }
    if (static_cast<double>(statics) >
        options.max_static_share * static_cast<double>(cluster.beams.size())) {
      continue;
    }
    double best = kFar;
    for (std::size_t s : carriers) {
      if (!boxes[s].Within(box, options.max_step_m)) continue;
      double d2 = kFar;
      for (std::size_t k : returns_of[s]) {
        for (const Eigen::Vector2d& p : points) {
          d2 = std::min(d2, (p - previous.points[k]).squaredNorm());
        }
      }
      if (d2 > step2) continue;
      if (d2 < best) {
        best = d2;
        nearest_of_cluster[c] = s;
      }
      if (d2 < best_of_segment[s]) {
        best_of_segment[s] = d2;
        nearest_of_segment[s] = c;
      }
    }
  }
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    const std::size_t s = nearest_of_cluster[c];
    if (s == segments || nearest_of_segment[s] != c) continue;
    carried[c] = previous.carried_scans[s] + 1;
    MarkClusterDynamic(clusters[c], classes);
  }
  return carried;
}

std::vector<std::uint8_t> StaticOnMovingTrace(const ScanSegments& previous, const LidarScan& scan,
                                              const Pose2& vehicle_pose,
                                              std::span<const HitClass> classes,
                                              const SegmentMotionOptions& options) {
  std::vector<std::uint8_t> out(classes.size(), 0);
  std::vector<Eigen::Vector2d> moving_points;
  for (std::size_t k = 0; k < previous.points.size(); ++k) {
    if (previous.moving[previous.segment[k]] && previous.own[k]) {
      moving_points.push_back(previous.points[k]);
    }
  }
  if (moving_points.empty()) return out;
  const double r2 = options.trace_radius_m * options.trace_radius_m;
  for (std::size_t i = 0; i < classes.size() && i < scan.ranges_m.size(); ++i) {
    if (classes[i] != HitClass::kStatic) continue;
    const Eigen::Vector2d p = vehicle_pose * ReturnPoint(scan, i);
    for (const Eigen::Vector2d& q : moving_points) {
      if ((p - q).squaredNorm() <= r2) {
        out[i] = 1;
        break;
      }
    }
  }
  return out;
}

ScanSegments DescribeSegments(const LidarScan& scan, const Pose2& vehicle_pose,
                              std::span<const ScanCluster> clusters, const std::vector<bool>& own,
                              std::span<const int> carried,
                              std::span<const std::uint8_t> standing) {
  ScanSegments out;
  out.moving.assign(clusters.size(), false);
  out.carried_scans.assign(clusters.size(), 0);
  for (std::size_t s = 0; s < clusters.size(); ++s) {
    for (std::size_t i : clusters[s].beams) {
      out.points.push_back(vehicle_pose * ReturnPoint(scan, i));
      out.segment.push_back(s);
      out.own.push_back(i >= standing.size() || standing[i] == 0);
    }
    const bool is_carried = s < carried.size() && carried[s] >= 0;
    out.moving[s] = (s < own.size() && own[s]) || is_carried;
    if (!(s < own.size() && own[s]) && is_carried) out.carried_scans[s] = carried[s];
  }
  return out;
}

}  // namespace lookout::lidar
