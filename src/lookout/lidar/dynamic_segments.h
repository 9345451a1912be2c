#pragma once

// The paper's object rule (seed 004 IV.C, "an object is marked as dynamic if at least one of
// its constituting laser points is classified as dynamic") carried back to the points: every
// return of a dynamic segment is a dynamic hit. It recovers the returns of a moving actor
// that land beside its own earlier, mapped returns (static) or in space the map never saw
// (unknown), once some of its returns are in free space.
//
// Deviation from the paper: "at least one point" is refined. A cluster is propagated only
// when at least min_dynamic_returns of its returns and at least min_dynamic_share of them are
// dynamic, and when its first and last returns are at most max_chord_m apart. A single false
// dynamic return on a wall (0.1-0.3 % of the static world's) would otherwise make the whole
// wall dynamic, and a segment that bridges an actor and the wall it passes would carry the
// actor's class onto the wall.

#include <cstdint>
#include <span>
#include <string>

#include "lookout/core/messages.h"
#include "lookout/lidar/hit_classification.h"
#include "lookout/lidar/scan_segmentation.h"

namespace lookout::lidar {

struct DynamicSegmentOptions {
  bool enabled = true;
  int min_dynamic_returns = 2;
  double min_dynamic_share = 0.15;
  // Longer than any road user seen across (a car's diagonal is about 5 m).
  double max_chord_m = 6.0;

  void Validate(const std::string& source = "lidar dynamic segment options") const;
};

// Marks every static and unknown return of `cluster` dynamic, the counts of `classes` in step;
// returns how many changed.
std::int64_t MarkClusterDynamic(const ScanCluster& cluster, ScanHitClasses& classes);

// Marks every return of each qualifying cluster of `scan` dynamic (static and unknown ones;
// kNoReturn beams are not in clusters) and keeps the counts of `classes` in step; returns how
// many returns changed class.
std::int64_t PropagateDynamicSegments(const LidarScan& scan, std::span<const ScanCluster> clusters,
                                      const DynamicSegmentOptions& options,
                                      ScanHitClasses& classes);

}  // namespace lookout::lidar
