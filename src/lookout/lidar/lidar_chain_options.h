#pragma once

// Options of the lidar chain as the vehicle pipeline runs it (seed 004 section IV): the
// localiser in a car's setting, the moving/static classification of the hits and the scan
// segmentation. docs/lidar-chain.md explains the values.

#include <string>

#include "lookout/lidar/dynamic_segments.h"
#include "lookout/lidar/hit_classification.h"
#include "lookout/lidar/scan_segmentation.h"
#include "lookout/lidar/segment_motion.h"
#include "lookout/lidar/slam_options.h"

namespace lookout::lidar {

// The localiser for a road vehicle at 12.5 Hz: the bicycle motion model, a 205 m map window of
// 0.05 m cells taking returns up to 80 m (the scanner sees 150 m; a car closing at 20 m/s must
// be seen moving 2 s before it arrives, so the map must have seen the road free out there:
// docs/lidar-chain.md), and a search window sized for a car's wheel odometry over one scan
// period (0.9 m at 11 m/s): a few centimetres and a fraction of a degree, against the robot
// logs' metre and half radian.
SlamOptions VehicleLocaliserOptions();

// The far map: the same scans in 0.2 m cells from 70 m out to the scanner's 150 m, over a 410 m
// window that recentres every 51 m (so 154 m and more are always mapped ahead). Only the
// classification of returns beyond the localiser's map reads it: a car at 20 m/s closing on
// the ego is 100 m away 3 s before it arrives. 42 MB, against the fine map's 168 MB that 150 m
// at 0.05 m would take four times over.
MapOptions FarMapOptions();

struct LidarChainOptions {
  SlamOptions localiser = VehicleLocaliserOptions();
  HitClassificationOptions hits;
  SegmentationOptions segmentation;
  DynamicSegmentOptions dynamic_segments;
  SegmentMotionOptions segment_motion;
  // Moving actors must not enter the map of the static world: returns classified dynamic only
  // clear the space in front of them (their rays), ending short of the return by
  // dynamic_ray_margin_m; static and unknown returns are mapped as hits. False maps every
  // return, as `lookout slam` does.
  bool map_static_only = true;
  double dynamic_ray_margin_m = 0.2;
  // With map_static_only: every return of a segment with a dynamic return (a moving object by
  // the paper's rule, IV.C) only clears space, whatever its own class. Meant for an actor's
  // surface that slides along itself (a cyclist seen from the side), whose returns land mostly
  // in cells its earlier returns filled and would be mapped again. A wall segment with one
  // false dynamic return then stays out of the map that scan; measured on the catalogue
  // (docs/lidar-chain.md), with the segment motion, it costs no precision and brings the
  // crowd's moving-hit recall from 0.915 to 0.926 (0.907 -> 0.920 before the segment motion).
  bool unmap_dynamic_segments = true;
  // A beam with no return within the scanner's range (+inf, or at max_range_m) says the space
  // along it is empty: it clears its ray up to this range (and the map's insert range), so
  // that the open road an actor drives into has been seen free before the actor is on it.
  // 0: no-return beams clear nothing, as in `lookout slam` (the CARMEN lasers' saturated codes
  // and the glass of buildings). NaN, negative and too-near beams never clear.
  double no_return_clear_m = 80.0;
  // A beam clears its ray only up to where its two neighbouring beams found a surface, less
  // this margin, when that is nearer than its own return. A beam is as wide as the gap between
  // beams: one that passes a surface at a grazing angle (the side of a parked car seen from
  // 60 m, 2 degrees off its face) runs within centimetres of the cells its neighbour hit, and
  // over many scans wiped the face out of the map, so that the car read as moving when the
  // ego came near (docs/lidar-chain.md). Negative: rays clear up to their own return.
  double neighbour_clear_margin_m = 0.2;
  // Returns beyond the localiser's map (its max_insert_range_m) are classified against the far
  // map (FarMapOptions), with this static tolerance: the coarser cell's (0.2 m) diagonal
  // half-width and the same margin as the fine map's 0.15 m. Off: far returns stay unknown.
  bool far_map_enabled = true;
  MapOptions far_map = FarMapOptions();
  double far_static_tolerance_m = 0.3;

  void Validate(const std::string& source = "lidar chain options") const;
};

}  // namespace lookout::lidar
