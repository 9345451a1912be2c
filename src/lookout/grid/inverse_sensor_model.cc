#include "lookout/grid/inverse_sensor_model.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "lookout/core/breakpoint_distance.h"
#include "lookout/grid/ray_traversal.h"

namespace lookout::grid {

void ComputeInverseSensorModel(const LidarScan& scan, const Pose2& sensor_pose,
                               const ScrollingGridGeometry& geometry,
                               const InverseSensorModelOptions& options, MeasurementGrid& out) {
  assert(options.p_hit > 0.5 && options.p_hit < 1.0 && options.p_free > 0.0 &&
         options.p_free <= options.p_free_no_return && options.p_free_no_return < 0.5 &&
         "InverseSensorModelOptions::Validate() first");
  // Reset only what the previous call wrote: every non-0.5 cell is in `touched`.
  if (out.p_occupied.size() != geometry.CellCount()) {
    out.p_occupied.assign(geometry.CellCount(), kUnknownProbability);
  } else {
    for (const std::size_t i : out.touched) out.p_occupied[i] = kUnknownProbability;
  }
  out.touched.clear();
  out.geometry = geometry;
  out.stamp = scan.stamp;
  out.stats = InverseSensorModelStats{};
  out.stats.beams = static_cast<int>(scan.ranges_m.size());
  // A pose that is not a pose (a localisation bug) places no beam: everything stays unknown.
  if (!sensor_pose.translation.allFinite() || !std::isfinite(sensor_pose.yaw)) return;

  const double max_range_m = std::isfinite(scan.max_range_m) && scan.max_range_m > 0.0
                                 ? scan.max_range_m
                                 : std::numeric_limits<double>::infinity();
  const double no_return_length_m = std::min(options.no_return_free_range_m, max_range_m);
  const auto p_hit = static_cast<float>(options.p_hit);
  const auto p_free = static_cast<float>(options.p_free);
  const auto p_free_no_return = static_cast<float>(options.p_free_no_return);

  // A beam without return between two neighbours that both returned from nearly the same
  // place is a dropout in front of a surface, not a view into open space: its free space stops
  // a cell short of the nearer neighbour's impact, so it cannot punch through the wall the
  // neighbours see (over many scans such beams would wear streaks through buildings).
  // "Nearly the same place": the neighbours' impacts less than surface_gap_m apart.
  const double surface_gap_m = options.surface_gap_m;
  auto returned = [&](std::size_t i) {
    const auto r = static_cast<double>(scan.ranges_m[i]);
    return r > 0.0 && r < max_range_m;  // false for NaN and +inf too
  };
  auto dropout_limit_m = [&](std::size_t beam) -> double {
    if (beam == 0 || beam + 1 >= scan.ranges_m.size()) return no_return_length_m;
    if (!returned(beam - 1) || !returned(beam + 1)) return no_return_length_m;
    const auto r_before = static_cast<double>(scan.ranges_m[beam - 1]);
    const auto r_after = static_cast<double>(scan.ranges_m[beam + 1]);
    const double lateral_gap_m =
        std::max(r_before, r_after) * 2.0 * std::abs(scan.angle_increment_rad);
    if (lateral_gap_m >= surface_gap_m || std::abs(r_before - r_after) >= surface_gap_m) {
      return no_return_length_m;
    }
    return std::min(no_return_length_m, std::min(r_before, r_after) - geometry.cell_size_m());
  };

  std::vector<float>& p = out.p_occupied;
  std::vector<std::size_t>& touched = out.touched;
  std::size_t visits = 0;
  const Eigen::Vector2d origin_m = sensor_pose.translation;

  for (std::size_t beam = 0; beam < scan.ranges_m.size(); ++beam) {
    const auto range_m = static_cast<double>(scan.ranges_m[beam]);
    if (std::isnan(range_m)) {
      ++out.stats.nan_beams;
      continue;
    }
    if (range_m <= 0.0) {
      ++out.stats.non_positive_beams;
      continue;
    }
    const bool hit = range_m < max_range_m;  // +inf and r >= max: no return
    if (hit) {
      ++out.stats.hit_beams;
    } else if (std::isinf(range_m)) {
      ++out.stats.no_return_beams;
    } else {
      ++out.stats.beyond_max_beams;
    }
    const double length_m = hit ? range_m : dropout_limit_m(beam);
    if (!(length_m > 0.0)) continue;
    const float p_crossed = hit ? p_free : p_free_no_return;

    const double angle_rad = sensor_pose.yaw + scan.BeamAngle(beam);
    const Eigen::Vector2d end_m =
        origin_m + length_m * Eigen::Vector2d(std::cos(angle_rad), std::sin(angle_rad));
    TraverseSegment(geometry, origin_m, end_m, [&](std::size_t i, bool is_end) {
      ++visits;
      float& value = p[i];
      if (value == kUnknownProbability) touched.push_back(i);
      if (hit && is_end) {
        value = p_hit;  // a hit wins over anything (see the header)
      } else if (value <= kUnknownProbability) {
        value = std::min(value, p_crossed);  // the stronger free evidence; never over a hit
      }
    });
  }

  // Surfaces between consecutive returns (after every beam: a hit wins wherever it lands).
  if (surface_gap_m > 0.0) {
    auto impact = [&](std::size_t beam) {
      const double angle_rad = sensor_pose.yaw + scan.BeamAngle(beam);
      return Eigen::Vector2d(origin_m +
                             static_cast<double>(scan.ranges_m[beam]) *
                                 Eigen::Vector2d(std::cos(angle_rad), std::sin(angle_rad)));
    };
    // One surface (InverseSensorModelOptions::surface_incidence_rad): within the breakpoint
    // distance at the nearer impact's range, or in line with an impact past either end.
    const std::size_t beams = scan.ranges_m.size();
    const double dphi_rad = std::abs(scan.angle_increment_rad);
    const double min_cos_turn = std::cos(options.surface_max_turn_rad);
    auto goes_on = [&](const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                       const Eigen::Vector2d& along) {
      const Eigen::Vector2d step = to - from;
      const double length = step.norm();
      return length > 0.0 && length <= surface_gap_m && step.dot(along) >= min_cos_turn * length;
    };
    for (std::size_t beam = 0; beam + 1 < beams; ++beam) {
      if (!returned(beam) || !returned(beam + 1)) continue;
      const Eigen::Vector2d a = impact(beam);
      const Eigen::Vector2d b = impact(beam + 1);
      const double length = (b - a).norm();
      if (length > surface_gap_m) continue;
      const double nearer_m =
          static_cast<double>(std::min(scan.ranges_m[beam], scan.ranges_m[beam + 1]));
      if (length > BreakpointDistance(nearer_m, dphi_rad, options.surface_incidence_rad,
                                      options.surface_range_noise_m)) {
        const Eigen::Vector2d along = (b - a) / length;
        const bool before = beam > 0 && returned(beam - 1) && goes_on(impact(beam - 1), a, along);
        const bool after =
            beam + 2 < beams && returned(beam + 2) && goes_on(b, impact(beam + 2), along);
        if (!before && !after) continue;
      }
      ++out.stats.surface_segments;
      TraverseSegment(geometry, a, b, [&](std::size_t i, bool /*is_end*/) {
        ++visits;
        if (p[i] == kUnknownProbability) touched.push_back(i);
        p[i] = p_hit;
      });
    }
  }
  out.stats.cell_visits = visits;
}

std::optional<Pose2> SensorPoseAt(const EgoPoseSource& ego, const LidarScan& scan) {
  const std::optional<EgoState> state = ego.PoseAt(scan.stamp);
  if (!state) return std::nullopt;
  return state->pose * scan.mount;
}

MeasurementGrid ComputeInverseSensorModel(const LidarScan& scan, const Pose2& sensor_pose,
                                          const ScrollingGridGeometry& geometry,
                                          const InverseSensorModelOptions& options) {
  MeasurementGrid out{geometry, scan.stamp, {}, {}, {}};
  ComputeInverseSensorModel(scan, sensor_pose, geometry, options, out);
  return out;
}

}  // namespace lookout::grid
