#pragma once

// The inverse sensor model: docs/extended-grid.md step 1, the measurement term
// P(M_k(x) = 1 | z_k) of the paper's eq. 10 and 12-13, from one lidar scan.
//
// Per beam (REP 117 ranges, docs/conventions.md):
//   - a return r inside max range: the cells the beam crosses from the sensor up to its impact
//     get p_free, the cell holding the impact point gets p_hit, the cells behind it (its
//     shadow) stay 0.5;
//   - no return (+inf, or r >= max range: clamped to no return): the cells crossed up to
//     no_return_free_range_m get the weaker p_free_no_return, no hit (see
//     InverseSensorModelOptions for why weaker);
//   - NaN (an erroneous reading) and r <= 0 (no lidar measures zero): skipped and counted;
//   - two consecutive returns whose impacts lie within surface_gap_m of each other, and within
//     the breakpoint distance or in line with the surface past them, are one surface: the
//     cells along the segment joining them are hits as well (see
//     InverseSensorModelOptions::surface_gap_m for why, surface_incidence_rad for which).
// Cells no beam reaches (outside the field of view, behind impacts, beyond the ranges above)
// stay 0.5: no evidence, so the filter's prediction passes there unchanged (step 3).
//
// Where beams overlap (near the sensor, dozens of beams cross each cell), one scan gives one
// value per cell, by strength of evidence: a hit wins over any free, p_free over
// p_free_no_return. "Hits before misses": a beam grazing the corner of a cell that another beam
// hit must not erase the obstacle, and the result does not depend on the beam order. Several
// beams crossing one cell are not fused as independent evidence: they are correlated views of
// the same space in the same instant, and fusing them would make the cells nearest the sensor
// near-certain within one scan.
//
// Free space from beams only, no filling between them. Adjacent beams diverge by r *
// angle_increment; beyond r = cell_size / angle_increment (34 m at 0.25 deg and 0.15 m) they are
// farther apart than a cell, so some cells between beams get no evidence (0.5) and a far surface's
// hit cells would have gaps, which the surface segments close (up to surface_gap_m). With the
// default 60 m window centred on the ego, only its corners are that far from the lidar.
// Consequence: there the grid learns free space more slowly (a 0.5 cell keeps its prediction, it is
// never wrongly cleared) and a far surface is sampled sparsely in one scan, filled in across scans
// as the ego moves. Filling the wedge between two beams instead would assert free space that no
// beam observed: a pole narrower than the gap could stand there.
//
// The sweep is instantaneous (LidarScan's contract): every beam starts at the one sensor pose.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

#include "lookout/core/ego_state.h"
#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/core/time.h"
#include "lookout/grid/grid_options.h"
#include "lookout/grid/scrolling_grid.h"

namespace lookout::grid {

// The value of a cell no beam says anything about.
inline constexpr float kUnknownProbability = 0.5f;

// Whether the scan says anything of a cell with measurement `p_occupied` (shadows, the space
// beyond the range and outside the field of view stay at kUnknownProbability).
inline bool Observed(float p_occupied) { return p_occupied != kUnknownProbability; }

struct InverseSensorModelStats {
  int beams = 0;                // ranges in the scan
  int hit_beams = 0;            // a return inside max range
  int no_return_beams = 0;      // +inf
  int beyond_max_beams = 0;     // finite, >= max range: treated as no return
  int nan_beams = 0;            // skipped
  int non_positive_beams = 0;   // r <= 0 or -inf: skipped
  int surface_segments = 0;     // consecutive returns joined as one surface
  std::size_t cell_visits = 0;  // cells visited by the traversal, repeats included (cost)
};

// One scan's measurement grid, in the storage layout of the window it was computed in (so
// p_occupied[i] pairs with a GridLayers value [i] of the same window).
struct MeasurementGrid {
  ScrollingGridGeometry geometry{GridOptions{}};  // the window the storage indices refer to
  TimeNs stamp = 0;
  // P(M_k(x) = 1 | z_k) per storage index: p_hit, p_free, p_free_no_return or 0.5.
  std::vector<float> p_occupied;
  // The storage indices whose value is not 0.5, each once, in order of first visit (beam
  // order, then along the beam): the sparse support of the evidence, so that later stages can
  // work on active cells only. Not sorted (sorting 10^5 indices would cost more than the model).
  std::vector<std::size_t> touched;
  InverseSensorModelStats stats;
};

// The lidar's pose in the grid (odometry) frame when `scan` was taken: the ego pose at the
// scan's stamp composed with the scan's mount. nullopt when `ego` has no pose for that time.
std::optional<Pose2> SensorPoseAt(const EgoPoseSource& ego, const LidarScan& scan);

// The model above for `scan` taken by a sensor at `sensor_pose` in the grid's (odometry) frame.
// scan.mount is not applied here: the caller composes ego_pose * scan.mount (SensorPoseAt). A scan
// whose max_range_m is not a positive number has no range limit; a non-finite sensor pose gives an
// all-unknown grid. `options` must pass Validate().
// Pure and deterministic.
MeasurementGrid ComputeInverseSensorModel(const LidarScan& scan, const Pose2& sensor_pose,
                                          const ScrollingGridGeometry& geometry,
                                          const InverseSensorModelOptions& options);

// The same, reusing `out`'s buffers: only the cells the previous call touched are reset to 0.5,
// so a steady pipeline allocates nothing and pays for the evidence, not for the whole window.
// Identical result to the function above.
void ComputeInverseSensorModel(const LidarScan& scan, const Pose2& sensor_pose,
                               const ScrollingGridGeometry& geometry,
                               const InverseSensorModelOptions& options, MeasurementGrid& out);

}  // namespace lookout::grid
