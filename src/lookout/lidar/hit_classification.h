#pragma once

// Moving and static hits (seed 004 section IV.B): "Laser hits observed in free space are
// classified as dynamic whereas the ones observed in previously occupied place are static the
// rest are marked as unknown." Each return of a scan is looked up in the local map as it was
// before the scan was added, at the scan's localised pose.
//
// The rule, per return (its end point p in the map frame):
//   static   the map holds an occupied cell within static_tolerance_m of p (the likelihood
//            field's distance; 0 when p's own cell is occupied);
//   dynamic  otherwise, when p's cell is free: log-odds at most free_log_odds;
//   unknown  otherwise (never seen, or seen too rarely to be sure either way).
// Deviation from the paper: the tolerance. With it a return that lands a cell beside a mapped
// wall (range noise, a localisation error of a few centimetres, a cell boundary) is static,
// not a moving object; without it every grazing wall return would be a candidate. It costs
// the detection of a mover closer than the tolerance to a mapped obstacle.
//
// Beams that are not returns (NaN, negative, below min_range_m, infinite, at the scanner's
// maximum) are kNoReturn and counted apart, never classified.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/lidar/local_map.h"

namespace lookout::lidar {

enum class HitClass : std::uint8_t { kNoReturn = 0, kStatic = 1, kDynamic = 2, kUnknown = 3 };

struct HitClassificationOptions {
  // A cell counts as seen free when its log-odds are at most this (the map's miss is -0.3 a
  // scan: -0.5 takes two clear views net of hits).
  float free_log_odds = -0.5f;
  // Above the map's occupied_log_odds: a return near occupied cells is static only when one of
  // them within static_tolerance_m holds more than this, e.g. 1.5: seen occupied in more than
  // one scan (a hit adds 0.9). A mover's return on its own trace of the scan before (cells hit
  // once) is then unknown, not static, and lidar/segment_motion.h may find it moving. At or
  // below occupied_log_odds (the default): any occupied cell, the paper's rule. Not the
  // default: on the catalogue 1.5 lifts the crowd's moving-hit recall from 0.926 to 0.938 at
  // no precision, but on the leg-tracker bag (real range noise: a surface's returns spread
  // over cells each hit less often) it leaves clutter unknown for the segment motion to carry
  // onto: 96 false tracks against 35 (docs/lidar-chain.md).
  float static_min_log_odds = 0.0f;
  // A return this close to an occupied cell of the map is static. About 2.5 sigma of what
  // separates a return on a mapped surface from the surface's cells: the localisation error
  // (a few centimetres), the range noise (0.03 m) and the cell's half width (0.025 m), some
  // 0.06 m together. At most the map's field_max_distance_m (the field knows no further).
  double static_tolerance_m = 0.15;
  // Returns nearer than this are not returns (the scanner's own housing, REP 117's minimum).
  double min_range_m = 0.1;

  void Validate(const std::string& source = "lidar hit classification options") const;
};

// Whether beam i of `scan` is a return: finite, at least min_range_m, and below the scanner's
// maximum range (a range at max_range_m is the "no return" code of many scanners).
bool IsReturn(const LidarScan& scan, std::size_t i, double min_range_m);

// Whether beam i of `scan` saw nothing within the scanner's range: +infinity, or a range at
// max_range_m (the same "no return" code IsReturn leaves out). NaN (no measurement) and
// negative ranges are not empty beams: they say nothing of the space along them.
bool IsEmptyBeam(const LidarScan& scan, std::size_t i);

// The return of beam i in the vehicle frame (through scan.mount). Only for IsReturn beams.
Eigen::Vector2d ReturnPoint(const LidarScan& scan, std::size_t i);

struct ScanHitClasses {
  std::vector<HitClass> beam;  // one per beam of the scan
  std::int64_t static_count = 0;
  std::int64_t dynamic_count = 0;
  std::int64_t unknown_count = 0;
  // NaN, infinite, negative, too near or at maximum range.
  std::int64_t no_return_count = 0;
};

// Classifies every beam of `scan` taken at `vehicle_pose` (the vehicle frame in the map's
// frame) against `map`. Pure; O(beams) map lookups. The map's own occupied threshold decides
// "occupied" (MapOptions::occupied_log_odds), so the classification and the likelihood field
// the localiser matches against agree.
ScanHitClasses ClassifyHits(const LocalMap& map, const LidarScan& scan, const Pose2& vehicle_pose,
                            const HitClassificationOptions& options);

// Returns of `classes` still unknown whose range is beyond `from_range_m` are classified again
// against `far_map` (a coarser map of the same scans that reaches further), by the same rule
// with `static_tolerance_m`; the counts follow. Pure apart from `classes`.
void ClassifyFarHits(const LocalMap& far_map, const LidarScan& scan, const Pose2& vehicle_pose,
                     double from_range_m, double static_tolerance_m,
                     const HitClassificationOptions& options, ScanHitClasses& classes);

}  // namespace lookout::lidar
