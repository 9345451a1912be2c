#pragma once

// Motion of a segment from one scan to the next, where the map cannot tell. Seed 004 IV.B
// classifies a return against the map alone: in free space dynamic, in occupied space static,
// otherwise unknown. A car driving away into space its own body hid, or a walker stepping out
// from behind another, returns from cells the map never saw: unknown, then mapped as occupied,
// then static on the next scan, held there by its own trace. Two cues of the scan pair settle
// it:
//   vacated  a return of the previous scan that this scan sees through: both beams either side
//            of its bearing now reach at least seen_through_margin_m past it. A static surface
//            does not vanish; what was there moved. Both beams must agree, so a wall at grazing
//            incidence (whose range changes fast with bearing) or a pole's edge is not taken
//            for one. A previous segment with at least min_vacated_returns vacated returns,
//            and at least min_vacated_share of its returns, moved;
//   carried  a previous segment that moved, by the map's own evidence (at least
//            min_vacated_returns dynamic returns) or by being vacated, went to the current
//            segment nearest to it, if that segment is nearest to it in turn (mutual nearest,
//            the distance between their nearest returns at most max_step_m). That segment's
//            static and unknown returns become dynamic. A segment carried so, and not moving by
//            its own evidence, carries on for at most max_carried_scans scans.
// Guards: a segment longer than max_chord_m (a wall a walker passes) is never carried onto,
// nor one with more than max_static_share of its returns static against the map (a pole the
// walker passes).
//
// Pure functions, in the order the lidar chain stage calls them on every scan.

#include <span>
#include <string>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/lidar/hit_classification.h"
#include "lookout/lidar/scan_segmentation.h"

namespace lookout::lidar {

struct SegmentMotionOptions {
  bool enabled = true;
  // Five range sigmas (0.03 m): a walker's 0.1 m a scan does not pass it, a car's 0.7 m does;
  // a walker crossing the beams is vacated at its trailing edge.
  double seen_through_margin_m = 0.15;
  int min_vacated_returns = 2;
  double min_vacated_share = 0.15;
  // A car at 12.5 m/s moves 1 m a scan; its sides overlap the previous scan's, so only a car
  // seen from straight behind or ahead needs the whole step.
  double max_step_m = 1.0;
  // Longer than any road user seen across (a car's diagonal is about 5 m).
  double max_chord_m = 6.0;
  double max_static_share = 0.6;
  int max_carried_scans = 3;
  // A return the map calls static this close to a return of a moving segment of the previous
  // scan lies on the mover's own trace (a car's side sliding along itself), not on something
  // standing: the segmentation's class break leaves it with the mover (StaticOnMovingTrace).
  double trace_radius_m = 0.3;

  void Validate(const std::string& source = "lidar segment motion options") const;
};

// The segments of one scan in the map frame, as the next scan needs them.
struct ScanSegments {
  std::vector<Eigen::Vector2d> points;  // every return of every segment, map frame
  std::vector<std::size_t> segment;     // the segment of each point
  // Per point: not a return the map called static, unless it lay on a mover's trace itself.
  // Only these make a trace: a pole that joined a walker's segment (both within the class
  // break) would otherwise be on the trace of its own returns of the scan before, scan after
  // scan, and stay with the walker once it had gone 0.3 m past it (the crowd's lamp posts).
  std::vector<bool> own;
  std::vector<bool> moving;             // per segment
  std::vector<int> carried_scans;       // per segment: scans since its own evidence of motion
};

// Which of `previous.points` the scan at `vehicle_pose` (the vehicle in the map frame) sees
// through.
std::vector<bool> VacatedReturns(const ScanSegments& previous, const LidarScan& scan,
                                 const Pose2& vehicle_pose, const SegmentMotionOptions& options,
                                 double min_range_m);

// Marks moving the segments of `previous` that `vacated` (VacatedReturns) shows moved; their
// carried_scans restart at 0.
void MarkVacatedSegments(const std::vector<bool>& vacated, const SegmentMotionOptions& options,
                         ScanSegments& previous);

// Per cluster of the current scan, whether its returns as the map classified them show it
// moving: at least min_vacated_returns dynamic.
std::vector<bool> OwnMotionEvidence(std::span<const ScanCluster> clusters,
                                    std::span<const HitClass> classes,
                                    const SegmentMotionOptions& options);

// Marks dynamic the static and unknown returns of each cluster of `scan` carried from a moving
// segment of `previous`; the counts of `classes` follow. Returns, per cluster, the carrying
// segment's carried_scans + 1, or -1 where none carried.
std::vector<int> CarrySegmentMotion(const ScanSegments& previous, const LidarScan& scan,
                                    const Pose2& vehicle_pose,
                                    std::span<const ScanCluster> clusters,
                                    const SegmentMotionOptions& options, ScanHitClasses& classes);

// Per beam of `scan`, 1 where `classes` calls the return static and it lies within
// options.trace_radius_m of a return of a moving segment of `previous` that is the mover's own
// (ScanSegments::own): the mover's own trace, which the map holds, not a standing object
// (SegmentationOptions::class_break_m).
std::vector<std::uint8_t> StaticOnMovingTrace(const ScanSegments& previous, const LidarScan& scan,
                                              const Pose2& vehicle_pose,
                                              std::span<const HitClass> classes,
                                              const SegmentMotionOptions& options);

// The segments of `scan` for the next scan: `clusters` in the map frame, moving when `own`
// (OwnMotionEvidence) or carried (CarrySegmentMotion's result). `standing`, per beam (empty:
// none), is 1 where the map called the return static and StaticOnMovingTrace did not flag it.
ScanSegments DescribeSegments(const LidarScan& scan, const Pose2& vehicle_pose,
                              std::span<const ScanCluster> clusters, const std::vector<bool>& own,
                              std::span<const int> carried,
                              std::span<const std::uint8_t> standing = {});

}  // namespace lookout::lidar
