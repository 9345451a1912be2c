#include "lookout/lidar/dynamic_segments.h"

#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::lidar {

void DynamicSegmentOptions::Validate(const std::string& source) const {
  if (min_dynamic_returns < 1) {
    throw InputError(source, 0, "min_dynamic_returns", "must be >= 1");
  }
  if (!std::isfinite(min_dynamic_share) || min_dynamic_share < 0.0 || min_dynamic_share > 1.0) {
    throw InputError(source, 0, "min_dynamic_share", "must be in [0, 1]");
  }
  if (!std::isfinite(max_chord_m) || max_chord_m <= 0.0) {
    throw InputError(source, 0, "max_chord_m", "must be finite and > 0");
  }
}

std::int64_t MarkClusterDynamic(const ScanCluster& cluster, ScanHitClasses& classes) {
  std::int64_t changed = 0;
  for (std::size_t i : cluster.beams) {
    HitClass& k = classes.beam[i];
    if (k == HitClass::kStatic) {
      --classes.static_count;
    } else if (k == HitClass::kUnknown) {
      --classes.unknown_count;
    } else {
      continue;
    }
    k = HitClass::kDynamic;
    ++classes.dynamic_count;
    ++changed;
  }
  return changed;
}

std::int64_t PropagateDynamicSegments(const LidarScan& scan, std::span<const ScanCluster> clusters,
                                      const DynamicSegmentOptions& options,
                                      ScanHitClasses& classes) {
  if (!options.enabled) return 0;
  std::int64_t changed = 0;
  for (const ScanCluster& c : clusters) {
    if (c.beams.empty()) continue;
    std::size_t dynamic = 0;
    for (std::size_t i : c.beams) {
      if (classes.beam[i] == HitClass::kDynamic) ++dynamic;
    }
    const double n = static_cast<double>(c.beams.size());
    if (dynamic < static_cast<std::size_t>(options.min_dynamic_returns) ||
        static_cast<double>(dynamic) < options.min_dynamic_share * n) {
      continue;
    }
    const double chord =
        (ReturnPoint(scan, c.beams.back()) - ReturnPoint(scan, c.beams.front())).norm();
    if (chord > options.max_chord_m) continue;
    changed += MarkClusterDynamic(c, classes);
  }
  return changed;
}

}  // namespace lookout::lidar
