#pragma once

// Beyond the paper (the grid issue's item 4, "a wider search for newly seen occupancy"): the
// displacement of occupancy that has no trusted velocity yet, measured from the scan pair.
//
// Why: eq. 8 gives such occupancy a wide window, and eq. 10 then spreads its mass over every
// sample of it that the scan does not see free: a 20 m/s car's over the road around it, a walker's
// over the wall beside her (docs/grid.md, known faults 1 and 2), and a static wall newly seen
// over its own length. The scan pair says where the occupancy went: the previous scan's hits
// around the cell, shifted by the right displacement, land on this scan's hits. Where one
// displacement clearly explains them best, the cell's window is the tracked cells' fine M x M
// window centred on it (association_prediction.h); a cell that the pair shows staying gets the
// fine window at zero. Where the pair cannot tell (too few hits, a surface sliding along itself,
// something newly revealed), the wide window stays.
//
// The measurement, for the patch of (2 patch_half + 1)^2 cells around the cell:
//   score(d) = sum over the previous scan's hits h in the patch of
//              1 if h + d is a hit now, 1/2 if a hit now is next to h + d (8-neighbourhood: a
//              return moves within its cell, and the beams sample a moved surface elsewhere);
//   best     = the displacement of highest score within +-search_half cells (ties: the
//              shortest, then the first in row order);
//   stays    when score(0) >= stay_share * score(best): staying explains the hits as well;
//   moves    by best when score(best) >= min_matched_share * hits and no displacement farther
//              than ambiguity_radius_cells from best scores ambiguity_share * score(best) or
//              more (a straight surface moving along itself: the aperture problem);
//   unknown  otherwise, and when the patch holds fewer than min_patch_hits previous hits.
// Where this scan sees free at least shortest_min_vacated_share of the patch's previous hits (the
// occupancy left them), or score(0) is under shortest_below_stay_share * score(best) (staying
// explains little), displacements longer than best are no rivals: a solid body matches itself
// moved further into its own extent too, and the shortest displacement is its motion. Hits that
// slide along a wall seen at a grazing angle leave nothing seen through and keep their rivals.
//
// Two baselines. One cycle resolves fast motion (a car's 10 cells) but not a walker's 0.6 cell
// a cycle, which whole-cell matching calls staying; so a displacement under long_lag_below_cells
// over one cycle is measured again against the scan long_lag_scans back (2.4 cells for the
// walker over four), and that displacement, scaled to this cycle by the stamps, is the mean.
//
// A body's motion (cluster_motion.h) is measured on the scans' outlines (OnOutline): a hit
// whose eight neighbours were all hit is inside an area of hits, where every small displacement
// matches, so it says nothing of the body's motion and only flattens the scores. A lidar's hits
// are surfaces, all outline; a body seen whole (a dense sensor, or a multi-layer lidar's returns
// from a roof) is otherwise its own rival: a 1.8 m x 0.9 m box at 20 m/s matched itself two
// cells off 88 % as well as at its motion, which the clusters' stage called ambiguous, and the
// box was lost.

#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <vector>

#include "lookout/core/grid_geometry.h"
#include "lookout/core/time.h"
#include "lookout/grid/inverse_sensor_model.h"
#include "lookout/grid/scrolling_grid.h"

namespace lookout::grid {

class WindowIndexer;

// The widest patch, cells either side of the cell (ScanFlowOptions::patch_half_cells).
inline constexpr int kMaxPatchHalfCells = 8;
static_assert(2 * (2 * kMaxPatchHalfCells + 1) * (2 * kMaxPatchHalfCells + 1) <= 32767,
              "PatchScoreCache's 16-bit scores");

struct ScanFlowOptions {
  // Off: every cell without a trusted velocity gets the wide window (the grid before
  // 2026-12-03; --grid-scan-flow off). On by default since 2026-12-03: the velocity RMSE better
  // in every catalogue scenario with movers, the static world read moving 0.007 of the time at
  // 10 m/s against 0.025 (docs/grid.md, "The scan pair's displacement").
  bool enabled = true;
  // Displacements searched, cells per cycle: +-12 cells is 22.5 m/s at 0.15 m and 12.5 Hz, the
  // wide window's reach.
  int search_half_cells = 12;
  // The patch: +-3 cells (1.05 m at 0.15 m), about a walker's width, a third of a car's side.
  int patch_half_cells = 3;
  int min_patch_hits = 3;
  double stay_share = 0.9;
  double min_matched_share = 0.6;
  double ambiguity_radius_cells = 1.5;
  double ambiguity_share = 0.8;
  // Where at least this share of the patch's previous hits is seen free now (vacated),
  // displacements longer than best are no rivals of it: the shortest motion that explains the
  // hits is taken (a solid body matches itself moved further into its own extent too).
  double shortest_min_vacated_share = 0.25;
  // ... or where score(0) is under this share of score(best) (staying explains little).
  double shortest_below_stay_share = 0.5;
  // The second baseline (1: none) and the one-cycle displacement (cells, Chebyshev) under which
  // it is used; it searches +-long_lag_below_cells * long_lag_scans cells.
  int long_lag_scans = 6;
  int long_lag_below_cells = 2;

  // Throws lookout::InputError naming the first field out of range.
  void Validate(const std::string& source = "scan flow options") const;
};

enum class FlowKind : std::uint8_t { kUnknown = 0, kStays, kMoves };

struct FlowMeasurement {
  FlowKind kind = FlowKind::kUnknown;
  CellIndex displacement;  // cells over the baseline; {0, 0} unless kMoves
  // The displacement over this cycle, cells (kMoves: displacement scaled from its baseline).
  double mean_x_cells = 0.0;
  double mean_y_cells = 0.0;
  int lag_scans = 1;  // the baseline the measurement used
  // kStays although a displacement far from zero explains the hits nearly as well.
  bool ambiguous = false;
  int patch_hits = 0;  // previous hits in the patch
  double score = 0.0;  // score(best)
};

// Two scans' hits on one window, row-major over the window's local cells (index iy * width +
// ix): `before` 1 where the previous scan hit, `now` 2 where this scan hit and 1 next to such
// a cell (the score of h + d above, doubled to stay integral), `free_now` 1 where this scan sees
// free space.
struct HitMaps {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> before;
  // 1 where a hit of the previous scan lies at the cell or next to it (its 3 x 3 block): what
  // the clusters' stage asks of every hit moved by every candidate displacement
  // (cluster_motion.h), one lookup where it took up to nine.
  std::vector<std::uint8_t> before_near;
  std::vector<std::uint8_t> now;
  std::vector<std::uint8_t> free_now;
  // The cells AddBefore and AddNow marked (row-major indices), for ClearHits.
  std::vector<std::uint32_t> hit_cells;

  // Whether window-local (ix, iy) is on the maps, and its row-major index (precondition:
  // Inside).
  bool Inside(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < width && iy < height; }
  std::size_t At(int ix, int iy) const {
    return static_cast<std::size_t>(iy) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(ix);
  }

  // Empty maps of the given size.
  void Reset(int width_cells, int height_cells);
  // before, before_near and now empty again, free_now left as it is: the undoing of AddBefore and
  // AddNow, block by block. Why: a scan pair marks a few thousand of the window's 160,000 cells,
  // and Reset's pass over the four maps was half the pair's preparation; free_now is rewritten
  // whole by the one who lays a scan out (ScanFlow::Prepare).
  void ClearHits();
  // Marks a hit of the previous / this scan at window-local (ix, iy); outside is ignored.
  void AddBefore(int ix, int iy);
  void AddNow(int ix, int iy);
  void AddFreeNow(int ix, int iy);
};

// Whether z's hit at window-local (ix, iy) (p_occupied > 0.5, a precondition) lies on its
// scan's outline: one of its eight neighbours is no hit, or off the window. Eight, not four:
// a lidar's surface seen at close range or with range noise is a band two or three cells
// thick, which four neighbours would hollow (the catalogue's straight-crossing-path: velocity
// RMSE after the first second 0.505 -> 0.612 m/s with four; unchanged with eight).
bool OnOutline(const MeasurementGrid& z, const WindowIndexer& indexer, int ix, int iy);

// The scores of the patch MeasureFlow last scored on one pair of maps, kept so that the next
// cell is scored from them. Why: a previous hit adds to the scores independently of the others,
// so moving the patch by a cell adds the hits of the column it enters and takes away those of the
// one it leaves (14 cells of the patch's 49), and the cells measured come in runs along rows.
struct PatchScoreCache {
  const HitMaps* maps = nullptr;
  CellIndex cell;
  int half = -1;
  // Doubled scores of the (2 half + 1)^2 displacements, row-major. 16 bits: a score is at most
  // 2 (2 kMaxPatchHalfCells + 1)^2 = 578, and a row of them is summed eight to an SSE2
  // instruction where 32-bit sums took four, each after two widenings of the map's bytes.
  std::vector<std::int16_t> scores;
};

// The measurement above, over one baseline, for the window-local cell `cell`, displacements
// within +-search_half_cells. Pure.
FlowMeasurement MeasureFlow(const HitMaps& maps, const CellIndex& cell, int search_half_cells,
                            const ScanFlowOptions& options);
// The same, scored from `cache` where it holds a patch nearby on the same maps (the same result
// as without), and leaving this cell's scores in it.
FlowMeasurement MeasureFlow(const HitMaps& maps, const CellIndex& cell, int search_half_cells,
                            const ScanFlowOptions& options, PatchScoreCache& cache);

// The slow literal form of MeasureFlow (every displacement, every patch cell, the definitions
// as written above); for tests only.
FlowMeasurement MeasureFlowReference(const HitMaps& maps, const CellIndex& cell,
                                     int search_half_cells, const ScanFlowOptions& options);

// The scan pairs of a scrolling grid: remembers the last long_lag_scans scans' hits by global cell
// (so that they survive the window's moves) and lays the previous one and the oldest out, each
// with this scan's, on the current window.
class ScanFlow {
 public:
  explicit ScanFlow(const ScanFlowOptions& options = {});
  const ScanFlowOptions& options() const { return options_; }

  // Lays the remembered hits and z's hits (p_occupied > 0.5) on z's window. Call once per
  // cycle, before Measure.
  void Prepare(const MeasurementGrid& z);
  // The flow of window-local `cell` for the prepared pairs, both baselines as above (kUnknown
  // before a pair exists).
  FlowMeasurement Measure(const CellIndex& cell) const;
  // The same, each baseline scored from its cache (PatchScoreCache).
  FlowMeasurement Measure(const CellIndex& cell, PatchScoreCache& short_cache,
                          PatchScoreCache& long_cache) const;
  // Measure for every cells[i] with wanted[i] != 0 (kUnknown for the others), then: an
  // ambiguous kStays connected to a kMoves cell through measured cells that are kUnknown or
  // ambiguous kStays, each within two cells of the next, becomes kUnknown (a car's long side
  // matches itself unshifted as it drives along it; a wall seen along itself has no motion on
  // it). Window-local cells, inside the window. Deterministic (a breadth-first search in the
  // cells' order), the measurements in parallel.
  std::vector<FlowMeasurement> MeasureCells(std::span<const CellIndex> cells,
                                            std::span<const std::uint8_t> wanted) const;
  // Whether Prepare found a previous scan to compare with.
  bool HasPair() const { return has_pair_; }
  // Remembers z's hits for the next cycle.
  void Remember(const MeasurementGrid& z);
  // The prepared pairs: the previous scan and this one, and the oldest remembered scan and this
  // one (nullptr without it); this cycle's dt is long_lag_scale() times the long pair's baseline.
  const HitMaps& short_pair() const { return maps_; }
  const HitMaps* long_pair() const { return has_long_pair_ ? &long_maps_ : nullptr; }
  double long_lag_scale() const { return long_lag_scale_; }
  // The same pairs' previous scans by their outlines only (OnOutline; `before` and
  // `before_near`, the maps a body's measurement reads, cluster_motion.h): the pair itself when
  // the previous scan is outline whole, as a lidar's is. The per-cell flow above keeps every
  // hit: a static solid body's inside shows it staying, which its outline alone, a few cells
  // away, does not (ExtendedGridTest.StaticWorldStaysStaticWhileTheWindowScrolls).
  const HitMaps& short_outline_pair() const {
    return outline_maps_.width != 0 ? outline_maps_ : maps_;
  }
  const HitMaps* long_outline_pair() const {
    if (!has_long_pair_) return nullptr;
    return long_outline_maps_.width != 0 ? &long_outline_maps_ : &long_maps_;
  }

 private:
  ScanFlowOptions options_;
  struct Scan {
    TimeNs stamp = 0;
    std::vector<CellIndex> hits_global;
    // The hits on the scan's outline, empty when that is all of them.
    std::vector<CellIndex> outline_global;
  };
  std::deque<Scan> history_;  // newest last, at most long_lag_scans
  bool has_pair_ = false;
  bool has_long_pair_ = false;
  double long_lag_scale_ = 1.0;                   // this cycle's dt over the long baseline's
  HitMaps maps_;                                  // the previous scan and this one
  HitMaps long_maps_;                             // the oldest remembered scan and this one
  // The previous and the oldest scan's outlines, laid (width > 0) only when the scan has hits
  // off its outline.
  HitMaps outline_maps_;
  HitMaps long_outline_maps_;
  mutable std::vector<std::int32_t> cell_index_;  // MeasureCells' workspace
};

}  // namespace lookout::grid
