#include "lookout/lidar/hit_classification.h"

#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::lidar {

void HitClassificationOptions::Validate(const std::string& source) const {
  if (!std::isfinite(free_log_odds) || free_log_odds >= 0.0f) {
    throw InputError(source, 0, "free_log_odds", "must be negative (a cell seen free)");
  }
  if (!std::isfinite(static_tolerance_m) || static_tolerance_m < 0.0) {
    throw InputError(source, 0, "static_tolerance_m", "must be finite and >= 0");
  }
  if (!std::isfinite(min_range_m) || min_range_m < 0.0) {
    throw InputError(source, 0, "min_range_m", "must be finite and >= 0");
  }
  if (!std::isfinite(static_min_log_odds)) {
    throw InputError(source, 0, "static_min_log_odds", "must be finite");
  }
}

bool IsReturn(const LidarScan& scan, std::size_t i, double min_range_m) {
  const double r = static_cast<double>(scan.ranges_m[i]);
  return std::isfinite(r) && r >= min_range_m && r < scan.NoReturnRangeM();
}

bool IsEmptyBeam(const LidarScan& scan, std::size_t i) {
  const double r = static_cast<double>(scan.ranges_m[i]);
  if (std::isnan(r) || r < 0.0) return false;
  if (std::isinf(r)) return true;
  return scan.max_range_m > 0.0 && r >= scan.NoReturnRangeM();
}

Eigen::Vector2d ReturnPoint(const LidarScan& scan, std::size_t i) {
  const double r = static_cast<double>(scan.ranges_m[i]);
  const double a = scan.BeamAngle(i);
  return scan.mount * Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
}

namespace {

// The rule of the header for one return whose map cell is c. The field stores distances
// between cell centres: a tolerance of t metres is "an occupied cell centre within t", compared
// with a hair of slack for the float distances.
HitClass ClassOfCell(const LocalMap& map, const CellIndex& c, double static_tolerance_m,
                     float free_log_odds, float static_min_log_odds) {
  const auto tolerance = static_cast<float>(static_tolerance_m + 1e-6);
  if (map.FieldDistance(c) <= tolerance || map.Occupied(c)) {
    if (static_min_log_odds <= map.options().occupied_log_odds) return HitClass::kStatic;
    const double cell = map.options().cell_size_m;
    const int reach = static_cast<int>(std::floor(static_tolerance_m / cell + 1e-6));
    const float reach2 = tolerance * tolerance;
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        const auto d2 = static_cast<float>(cell * cell * (dx * dx + dy * dy));
        if (d2 > reach2) continue;
        if (map.LogOdds({c.ix + dx, c.iy + dy}) > static_min_log_odds) return HitClass::kStatic;
      }
    }
    return HitClass::kUnknown;
  }
  if (map.LogOdds(c) <= free_log_odds) return HitClass::kDynamic;
  return HitClass::kUnknown;
}

}  // namespace

ScanHitClasses ClassifyHits(const LocalMap& map, const LidarScan& scan, const Pose2& vehicle_pose,
                            const HitClassificationOptions& options) {
  ScanHitClasses out;
  out.beam.assign(scan.ranges_m.size(), HitClass::kNoReturn);
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    if (!IsReturn(scan, i, options.min_range_m)) {
      ++out.no_return_count;
      continue;
    }
    const CellIndex c = map.CellOf(vehicle_pose * ReturnPoint(scan, i));
    const HitClass k = ClassOfCell(map, c, options.static_tolerance_m, options.free_log_odds,
                                   options.static_min_log_odds);
    out.beam[i] = k;
    switch (k) {
      case HitClass::kStatic: ++out.static_count; break;
      case HitClass::kDynamic: ++out.dynamic_count; break;
      default: ++out.unknown_count; break;
    }
  }
  return out;
}

void ClassifyFarHits(const LocalMap& far_map, const LidarScan& scan, const Pose2& vehicle_pose,
                     double from_range_m, double static_tolerance_m,
                     const HitClassificationOptions& options, ScanHitClasses& classes) {
  for (std::size_t i = 0; i < classes.beam.size() && i < scan.ranges_m.size(); ++i) {
    if (classes.beam[i] != HitClass::kUnknown) continue;
    if (static_cast<double>(scan.ranges_m[i]) <= from_range_m) continue;
    const CellIndex c = far_map.CellOf(vehicle_pose * ReturnPoint(scan, i));
    const HitClass k = ClassOfCell(far_map, c, static_tolerance_m, options.free_log_odds,
                                   options.static_min_log_odds);
    if (k == HitClass::kUnknown) continue;
    classes.beam[i] = k;
    --classes.unknown_count;
    ++(k == HitClass::kStatic ? classes.static_count : classes.dynamic_count);
  }
}

}  // namespace lookout::lidar
