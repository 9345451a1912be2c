#pragma once

// Beyond the paper: each rigid cluster's displacement measured as one body from the scan pair,
// and given to its cells (a stage between the paper's steps 7 and 8, docs/grid.md "A body's
// motion measured whole").
//
// Why: a cell's velocity (eq. 14) is the mean displacement of the mass that reached it. Along a
// surface that slides along itself every displacement fits the scan alike (the aperture
// problem), so a walker's arc or a car's side cannot tell its speed along itself; eq. 14 then
// reads the Gaussian prior of eq. 8 cut by the free space behind the body, a velocity that lags
// the truth and is carried along the body with the mass. The crossing group's walkers read
// 0.5 m/s RMS off their 1.1 m/s. The body's hits together (an arc with its two ends, a side
// with a front) fit the previous scan's hits at one displacement only; a body whose hits are a
// straight line with no end in view fits many, and is left to eq. 14.
//
// The measurement, for the body's hits now H (window-local cells):
//   score(d) = sum over h in H of 1 if the previous scan hit h - d, 1/2 if it hit next to it
//              (a return moves within its cell; the beams sample a moved surface elsewhere);
//   best     = the highest score within +-search_half of the predicted displacement (ties: the
//              shortest displacement, then the first in row order);
//   measured when score(best) >= min_matched_share |H|, |H| >= min_hits, and no displacement
//              farther than ambiguity_radius_cells from best scores ambiguity_share of it
//              (none longer than best counts for a body seen whole, some of its hits inside an
//              area of hits, that left free space behind it: it matches itself moved further
//              into its own extent too);
//   sub-cell by the vertex of the parabola through the scores at best and its two neighbours,
//              along each axis (clamped to half a cell): whole-cell matching alone quantises a
//              walker's 0.6 cell a cycle to 0 or 1.
//
// The stage, per cluster (grid_objects.h's stages 1-2 with cluster_options: dynamic cells
// linked by eq. 15's D):
//   - H: the cluster's cells this scan hits, and the hits within attach_cells of them that the
//     previous scan did not hit (the body arriving: a car's newly seen front; a wall beside a
//     walker, hit scan after scan, is not attached), those on the scan's outline (scan_flow.h);
//   - the baseline: one cycle, or the scan pair's long baseline (scan_flow.h) when the cluster's
//     predicted displacement is under its long_lag_below_cells a cycle, scaled by the stamps;
//   - not measured: a small body over the long baseline whose measurement changes its
//     predicted velocity by more than small_body_max_change_mps;
//   - measured: each cluster cell's velocity <- (1 - blend) V + blend v_body, except a cell this
//     scan hits where the baseline's scan hit too although the body moved a cell or more since,
//     and hit staying_min_hit_scans scans in a row (staying explains it as well: a wall cell
//     that rigidity links joined to a walker, not a car's side sliding along itself); each
//     attached hit with no trusted velocity of its own (confidence under the filter's
//     known_confidence) takes v_body and that confidence, so the next cycle moves it with the
//     body; and, when the body moved at least birth_min_cells a cycle, the occupancy of a hit on
//     unknown space (ClusterMotionOptions::births);
//   - for a slow body moving a cell a cycle or more, its trailing side, the hits behind it that
//     no cluster holds (ClusterMotionOptions::sides);
//   - then the still bodies (ClusterMotionOptions::still_bodies), which no cluster holds.
//
// Deterministic: clusters in window order, one thread.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "lookout/core/grid_geometry.h"
#include "lookout/grid/scan_flow.h"

namespace lookout::grid {

class GridLayers;
struct FilterLayerIds;
struct MeasurementGrid;

struct ClusterMotionOptions {
  // On by default since 2026-12-04: velocity RMSE better in 9 of the catalogue's 11 scenarios
  // with movers, the crossing group's 0.86 -> 0.74 m/s (docs/grid.md). --grid-cluster-motion off.
  bool enabled = true;
  // The body's measured velocity against the cell's own: a half keeps one cycle's quantisation
  // (a cell's worth, 1.9 m/s at 0.15 m and 12.5 Hz over one cycle) from jolting the cells.
  double blend = 0.5;
  // Displacements searched around the cluster's predicted one, cells (over the long baseline:
  // twice this).
  int search_half_cells = 3;
  // Hits this close to a cluster cell (Chebyshev, cells) join its body: a car's front face seen
  // for the first time lies a few cells ahead of the cells it already moved. 8 (1.2 m) since
  // the births below: a 3 m/s car's face runs 4-5 cells ahead of the side cells the grid holds
  // (3 let the face go unseen; 10 joins the crowd's walkers to each other's bodies: the crowd's
  // velocity RMSE 0.33 -> 0.54 m/s, docs/grid.md).
  int attach_cells = 8;
  // Births (docs/grid.md, "A moving face is born"): a face that moves into space the grid saw
  // free is hit once per cell (a 3 m/s car's front crosses 1.6 cells a cycle), and a hit takes
  // a cell believed free (O = 0.02) only to 0.045: the face never holds occupancy, only the
  // side sliding along itself does, and a side alone cannot tell its motion (the aperture
  // problem: the crossing group's car read at half its 3 m/s). The scan pair explains such a
  // hit as the body's arrival; the free belief was of the space before the body came. So when
  // the body is measured moving at least birth_min_cells a cycle, each attached hit whose
  // occupancy is under its measurement m takes m (what a hit gives to unknown space) and the
  // seen share 1 (its content is the body's: the next cycle moves it with its velocity). Slower
  // bodies are left out: a walker's neighbours' new hits lie within attach_cells too.
  bool births = true;
  // The exclusion above ("staying fits") only for cells hit at least this many scans in a row
  // (the layer FilterLayerIds::hit_scans, counted at the start of the stage): a wall beside a
  // walker has been hit where it stands for seconds; a car's side sliding along itself covers
  // a cell for its length over its speed (1.5 s for a 4.5 m car at 3 m/s), and its first cells
  // are new. Without the count, the crossing group's car, measured whole at 2.9-3.1 m/s, kept
  // its side cells at 2.5-2.7 (docs/grid.md, "A car's side is not a wall"). 12: one second.
  // For a body moving a cell a cycle or more, at least its extent along its motion over its
  // displacement a cycle, two scans spare: a wall is hit for longer than a body takes to pass
  // it, and the crossing group's car, 4.5 m at 3 m/s, covers a cell of its side for 19 scans.
  // 0: every such cell, as before.
  int staying_min_hit_scans = 12;
  double birth_min_cells = 1.0;
  // A slow body's trailing side (docs/grid.md, "A slow car's side"): a car's side seen at a
  // grazing angle slides along itself, hit in some scans and seen through in others, and eq. 14
  // reads its cells' motion along it from whatever the windows give (the crossing group's 3 m/s
  // car: 0.6 to 11 m/s from one cycle to the next); their confidence stays under the clusters'
  // threshold, so the body's cluster holds its front and not the rear of its side. A slow body
  // (measured over the long baseline) covers a cell of its side for many cycles (19 for a 4.5 m
  // car at 3 m/s), a fast one for a few, which the windows follow. So for a body measured over
  // the long baseline moving a cell a cycle or more, whose hits are not one line sliding along
  // itself, this scan's hits connected to its cluster through hits no cluster holds, within the
  // cluster's band across its motion (a cell either side), behind its rear, at most
  // side_max_cells behind its front and hit for fewer scans than a wall (the count above), take
  // the body's velocity as its cells do (blend), and at least the known confidence: where they
  // read it within side_min_disagreement of its speed, they keep their own (the body's
  // measurement has its own error: one cycle's share of a whole-cell match).
  bool sides = true;
  double side_max_cells = 40.0;  // 6 m at 0.15 m: a car's length and more
  double side_min_disagreement = 0.3;
  int min_hits = 4;
  // A small body measured over the long baseline (fewer than small_body_max_hits hits: a
  // walker's arc is 4-7) is measured only when it changes the velocity its cells predicted by
  // at most small_body_max_change_mps (docs/grid.md, "A few hits among other walkers"): in a
  // crowd a few hits find the other walkers' older hits within the +-6-cell search, all of them
  // matched, at 2-3.5 m/s in another direction (known fault 8), and a walker changes her
  // velocity by less than that within the baseline's half second. 0 hits: every body measured.
  int small_body_max_hits = 8;
  double small_body_max_change_mps = 1.0;
  double min_matched_share = 0.6;
  double ambiguity_radius_cells = 1.5;
  double ambiguity_share = 0.8;
  // The clusters (grid_objects.h, GridObjectOptions): cells above min_occupancy that move faster
  // than min_speed_mps with at least min_velocity_confidence (the filter's known_confidence:
  // tracked cells), linked by D above min_link, at least min_cells of them.
  double min_occupancy = 0.6;
  double min_speed_mps = 0.5;
  double min_velocity_confidence = 0.25;
  double min_link = 0.05;
  int min_cells = 3;

  // Still bodies (docs/grid.md, "A walker held still", "A truck read still"): a body the grid
  // believes still but the scan pair sees moving. A walker's 0.6 cell a cycle is staying to the
  // one-cycle pair, so a walker newly in view (or in view before six scans exist) is read still,
  // its stillness becomes trusted, and a trusted cell never asks the scan pair again; nor is it a
  // dynamic cell any cluster above holds. Each 8-connected body of cells this scan hits, above
  // min_occupancy, that no dynamic cluster holds, is measured against the long pair's older
  // scan (MeasureClusterMotion, +-2 search_half_cells around staying) when it is at most
  // still_max_extent_cells across (a walker, a pushchair, a cyclist, a pole; not a wall), or
  // at most new_body_max_extent_cells with at least still_min_arrived_share of its hits on
  // cells the grid believed free (a vehicle new in view, its face and the side the scan sees;
  // births on); it moved when
  //   - the displacement is at least still_min_displacement_cells over the baseline, and not at
  //     the edge of the search (there the best is the search's edge, not the body's: a car's
  //     side sliding along itself aliases to it); when the long pair finds none within its
  //     search (+-6 cells over six scans: a body faster than a cell a cycle, a 3 m/s car's face
  //     at 1.6), the one-cycle pair is asked the same (+-2 search_half_cells: intersafe-fig8's
  //     5 m/s truck moves 2.7 cells a cycle), unless the body's hits are one line and the
  //     displacement runs along it (a line's motion along itself is not in the scan: a wall's
  //     hits sliding along it as the ego drives). Without it the
  //     crossing group's car, its face new each scan and its side read still, was measured by
  //     nothing for its first 1.5 s in view (docs/grid.md, "A face too fast for the long pair");
  //   - the body left where it was: of the older scan's hits around the body that this scan
  //     does not hit, at least still_min_vacated_share are seen free now (a wall's hits
  //     sliding along it as the ego drives leave nothing seen through);
  //   - the last cycle agrees: the body's hits moved back by one cycle's share of the
  //     displacement land on the previous scan's hits (min_matched_share);
  //   - the grid believed it slower: its cells' mean speed at most still_believed_share of the
  //     measured one (a fast body's piece the long pair aliases is not held still).
  // Its cells then take the measured velocity with the filter's known_confidence: the next
  // cycle moves them with it, a dynamic cluster above.
  // With births on, the bodies are of all this scan's hits, whatever their occupancy: a walker
  // far away walking into space the grid saw free (occluded-pedestrian's, at 17 m) never
  // reaches min_occupancy under one hit a cell; and a body moved may instead have arrived: at
  // least still_min_arrived_share of its hits on cells the grid believed free (O < 1/2). Where
  // its older hits lie in an occluder's shadow now, nothing can be seen vacated. A moved body's
  // hits are born as the attached ones above.
  bool still_bodies = true;
  int still_max_extent_cells = 8;  // 1.2 m at 0.15 m
  // 12 m at 0.15 m. Until 2026-12-05 still_max_extent_cells bounded every body: intersafe-fig8's
  // truck, its face 17 cells across and its side behind, was never measured, its face never
  // born and its side read still for its whole 3 s in view (docs/grid.md, "A truck read
  // still").
  int new_body_max_extent_cells = 80;
  double still_min_displacement_cells = 1.5;
  double still_min_vacated_share = 0.5;
  double still_believed_share = 0.5;
  double still_min_arrived_share = 0.5;

  // Throws lookout::InputError naming the first field out of range
  // (grid.filter.cluster_motion.<field>).
  void Validate(const std::string& source = "cluster motion options") const;
};

struct ClusterMotion {
  bool measured = false;
  // The displacement over the baseline of the maps measured, cells (sub-cell).
  double dx_cells = 0.0;
  double dy_cells = 0.0;
  int hits = 0;        // |H|
  double score = 0.0;  // score(best)
};

// The doubled scores the measurement ranks, score(predicted + o) for the offsets o within
// +-search_half, row-major from (-search_half, -search_half): each hit now explained by the
// baseline's scan at hit - predicted - o, 2 for a hit there, 1 for a hit next to it. Pure.
std::vector<int> ClusterMotionScores(const HitMaps& maps, std::span<const CellIndex> hits_now,
                                     const CellIndex& predicted, int search_half);

// The measurement above: `hits_now` against `maps.before` (HitMaps' window-local cells),
// displacements within +-search_half of `predicted`. With `left_free_space` (the body left
// free space behind it, LeftFreeSpace), a displacement longer than a best that is no staying
// is no rival: a body seen whole also matches itself moved further into its own extent, and
// the shortest displacement that explains its hits is its motion (the scan flow's rule,
// scan_flow.h). Pure.
ClusterMotion MeasureClusterMotion(const HitMaps& maps, std::span<const CellIndex> hits_now,
                                   const CellIndex& predicted, int search_half,
                                   const ClusterMotionOptions& options,
                                   bool left_free_space = false);

// Whether this scan sees free at least `min_share` of the baseline scan's hits where a body
// was: the box of its hits now moved back by `predicted`, a cell wider on each side. A body
// that moved leaves free space; a wall or a side sliding along itself is hit again. Pure.
bool LeftFreeSpace(const HitMaps& maps, std::span<const CellIndex> hits_now,
                   const CellIndex& predicted, double min_share);

// FilterLayerIds::hit_scans after the scan `z`: one more where it hits, 0 where it sees free,
// unchanged where it says nothing. Returns the scan's hits (storage indices) in z.touched's
// order, found on the way: the still bodies start from them (one walk over z.touched, whose
// cells come in the rays' order, a cache miss each, where there were two). Pure on its
// arguments.
std::vector<std::size_t> CountHitScans(const MeasurementGrid& z, std::span<float> hit_scans);

// A body the stage measured moving this cycle (a cluster or a still body): its cells (storage
// indices) and its measured velocity.
struct MeasuredBody {
  std::vector<std::size_t> cells;
  double velocity_x_mps = 0.0;
  double velocity_y_mps = 0.0;
};

// What the stage found in a cycle, for the hidden bodies' stage (hidden_bodies.h): the rigid
// clusters it worked on (storage indices; found on the state before its own changes), and the
// bodies it measured moving at least min_speed_mps (clusters and still bodies), in the order it
// measured them.
struct ClusterStageOutput {
  std::vector<std::vector<std::size_t>> clusters;
  std::vector<MeasuredBody> measured;
};

// The stage above on `layers` (velocity and confidence; the hit count always), with `flow`
// prepared for `z` (before ScanFlow::Remember), dt_s after the previous cycle. Nothing else
// without a scan pair (then nothing found).
ClusterStageOutput ApplyClusterMotion(GridLayers& layers, const FilterLayerIds& ids,
                                      const MeasurementGrid& z, const ScanFlow& flow, double dt_s,
                                      double known_confidence, const ClusterMotionOptions& options);
// The stage's dynamic cells: DynamicCellMask (grid_objects.h) with the stage's thresholds; empty
// when the stage does nothing this cycle (off, or no scan pair in `flow`). It reads only the
// occupancy, velocity and confidence layers.
std::vector<std::uint8_t> ClusterMotionMask(const GridLayers& layers, const FilterLayerIds& ids,
                                            const ScanFlow& flow,
                                            const ClusterMotionOptions& options);
// The same with its two serial passes over the window already taken, each beside a stage that
// does not touch what it reads: `hits_now` is CountHitScans of z on the layers' hit_scans (the
// update takes them beside the scan pair's preparation), `dynamic` ClusterMotionMask of the
// layers as the stage finds them (beside the rigidity links).
ClusterStageOutput ApplyClusterMotion(GridLayers& layers, const FilterLayerIds& ids,
                                      const MeasurementGrid& z, const ScanFlow& flow, double dt_s,
                                      double known_confidence, const ClusterMotionOptions& options,
                                      std::span<const std::size_t> hits_now,
                                      const std::vector<std::uint8_t>& dynamic);

}  // namespace lookout::grid
