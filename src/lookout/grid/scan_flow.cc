#include "lookout/grid/scan_flow.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <type_traits>

#include "lookout/core/input_error.h"
#include "lookout/grid/filter_state.h"

namespace lookout::grid {
namespace {

void Require(bool ok, const std::string& source, const std::string& field, const char* problem) {
  if (!ok) throw InputError(source, 0, "grid.filter.scan_flow." + field, problem);
}

bool InUnit(double v) { return v >= 0.0 && v <= 1.0; }  // NaN: false

// The doubled score of a target outside the window: 1 when a hit inside lies next to it (the
// dilated map holds only the window's cells).
int OutsideScore(const HitMaps& m, int x, int y) {
  for (int ny = y - 1; ny <= y + 1; ++ny) {
    for (int nx = x - 1; nx <= x + 1; ++nx) {
      if (m.Inside(nx, ny) && m.now[m.At(nx, ny)] == 2) return 1;
    }
  }
  return 0;
}

// The decision of scan_flow.h from the scores (doubled: integral), shared by both paths.
// `score_at(d)` gives the doubled score of displacement d.
template <typename ScoreAt>
FlowMeasurement Decide(int hits, int vacated, int search_half, const ScoreAt& score_at,
                       const ScanFlowOptions& options) {
  FlowMeasurement out;
  out.patch_hits = hits;
  if (hits < options.min_patch_hits) return out;
  // The best: the highest score, then the shortest displacement, then the first in row order;
  // in two passes, the highest score (without a branch), then the shortest of the displacements
  // that reach it. (One pass comparing all three at every displacement took most of
  // MeasureFlow's time.)
  int best_score = score_at({0, 0});
  for (int dy = -search_half; dy <= search_half; ++dy) {
    for (int dx = -search_half; dx <= search_half; ++dx) {
      best_score = std::max(best_score, score_at({dx, dy}));
    }
  }
  // Whether row dy holds a score >= at_least: one pass without a branch (it vectorises), so
  // that the passes below look displacement by displacement only at the few rows near the best.
  const auto row_reaches = [&](int dy, int at_least) {
    int reached = 0;
    for (int dx = -search_half; dx <= search_half; ++dx) {
      reached |= score_at({dx, dy}) >= at_least ? 1 : 0;
    }
    return reached != 0;
  };
  CellIndex best{0, 0};
  if (score_at(best) != best_score) {
    int best_length2 = std::numeric_limits<int>::max();
    for (int dy = -search_half; dy <= search_half; ++dy) {
      if (!row_reaches(dy, best_score)) continue;
      for (int dx = -search_half; dx <= search_half; ++dx) {
        if (score_at({dx, dy}) != best_score || dx * dx + dy * dy >= best_length2) continue;
        best = {dx, dy};
        best_length2 = dx * dx + dy * dy;
      }
    }
  }
  out.score = 0.5 * best_score;
  const int stay_score = score_at({0, 0});
  const bool stays = stay_score > 0 && stay_score >= options.stay_share * best_score;
  if (!stays && out.score < options.min_matched_share * hits) return out;
  // Unambiguous: no displacement far from the chosen one scores nearly as well.
  const CellIndex chosen = stays ? CellIndex{0, 0} : best;
  const bool shortest = !stays && (vacated >= options.shortest_min_vacated_share * hits ||
                                   stay_score < options.shortest_below_stay_share * best_score);
  const double radius2 = options.ambiguity_radius_cells * options.ambiguity_radius_cells;
  const double rival_score = options.ambiguity_share * best_score;
  // An integer score s is below rival_score exactly when s < ceil(rival_score).
  const int rival_at_least = static_cast<int>(std::ceil(rival_score));
  for (int dy = -search_half; dy <= search_half; ++dy) {
    if (!row_reaches(dy, rival_at_least)) continue;
    for (int dx = -search_half; dx <= search_half; ++dx) {
      // The score first: it rules out nearly every displacement at the cost of one comparison.
      if (score_at({dx, dy}) < rival_score) continue;
      const double ex = dx - chosen.ix;
      const double ey = dy - chosen.iy;
      if (ex * ex + ey * ey <= radius2) continue;
      // Where the scan sees through the patch's previous hits, the occupancy left them, and a
      // longer displacement is no rival: a solid body also matches itself moved further into its
      // own extent; the shortest displacement that explains the hits is its motion. (Hits
      // sliding along a wall seen at a grazing angle leave nothing seen through: every shift
      // along it stays a rival.)
      if (shortest && dx * dx + dy * dy > best.ix * best.ix + best.iy * best.iy) continue;
      // Staying but ambiguous: a surface longer than the patch, or the inside of a solid body.
      // Left to the caller (ScanFlow::MeasureCells), which knows the cells around.
      if (stays) {
        out.kind = FlowKind::kStays;
        out.ambiguous = true;
      }
      return out;
    }
  }
  if (stays) {
    out.kind = FlowKind::kStays;
    return out;
  }
  out.kind = FlowKind::kMoves;
  out.displacement = best;
  out.mean_x_cells = best.ix;
  out.mean_y_cells = best.iy;
  return out;
}

// z's hits (p > 0.5) into maps.now (dilated, AddNow) and its free cells (p < 0.5) into
// maps.free_now, window row by window row. Why not a walk over z.touched: it visits the cells in
// the rays' order, a cache miss a cell (0.3 ms a cycle for the junction's 23,000); a window row
// is one run of storage, rotated by the scroll, so this pass is sequential and vectorises.
void LayNow(const MeasurementGrid& z, HitMaps& maps) {
  const WindowIndexer indexer(z.geometry);
  const int width = indexer.width();
  // A row's storage run holds its local cells in two pieces: storage columns [split, width) are
  // local x [0, width - split), columns [0, split) local x [width - split, width).
  const auto split = static_cast<int>(indexer.Storage(0, 0) - indexer.RowStorage(0));
  const auto lay_piece = [&](const float* p, int n, int x0, int y) {
    std::uint8_t* free = &maps.free_now[maps.At(x0, y)];
    for (int i = 0; i < n; ++i) free[i] = p[i] < 0.5f ? 1 : 0;
    // A few hundred hits in 160,000 cells.
    ForEachWhere(
        static_cast<std::size_t>(n), [&](std::size_t i) { return p[i] > 0.5f; },
        [&](std::size_t i) { maps.AddNow(x0 + static_cast<int>(i), y); });
  };
  for (int y = 0; y < indexer.height(); ++y) {
    const float* row = &z.p_occupied[indexer.RowStorage(y)];
    lay_piece(row + split, width - split, 0, y);
    lay_piece(row, split, width - split, y);
  }
}

}  // namespace

bool OnOutline(const MeasurementGrid& z, const WindowIndexer& indexer, int ix, int iy) {
  const auto hit = [&](int x, int y) {
    return indexer.Inside(x, y) && z.p_occupied[indexer.Storage(x, y)] > 0.5f;
  };
  for (int y = iy - 1; y <= iy + 1; ++y) {
    for (int x = ix - 1; x <= ix + 1; ++x) {
      if (!hit(x, y)) return true;
    }
  }
  return false;
}

void ScanFlowOptions::Validate(const std::string& source) const {
  Require(search_half_cells >= 0 && search_half_cells <= 32, source, "search_half_cells",
          "must be in [0, 32]");
  Require(patch_half_cells >= 0 && patch_half_cells <= kMaxPatchHalfCells, source,
          "patch_half_cells", "must be in [0, 8]");
  static_assert(kMaxPatchHalfCells == 8, "the message above");
  Require(min_patch_hits >= 1, source, "min_patch_hits", "must be >= 1");
  Require(InUnit(stay_share), source, "stay_share", "must be in [0, 1]");
  Require(InUnit(min_matched_share), source, "min_matched_share", "must be in [0, 1]");
  Require(std::isfinite(ambiguity_radius_cells) && ambiguity_radius_cells >= 0.0, source,
          "ambiguity_radius_cells", "must be finite and >= 0");
  Require(InUnit(ambiguity_share), source, "ambiguity_share", "must be in [0, 1]");
  Require(InUnit(shortest_min_vacated_share), source, "shortest_min_vacated_share",
          "must be in [0, 1]");
  Require(InUnit(shortest_below_stay_share), source, "shortest_below_stay_share",
          "must be in [0, 1]");
  Require(long_lag_scans >= 1 && long_lag_scans <= 16, source, "long_lag_scans",
          "must be in [1, 16]");
  Require(long_lag_below_cells >= 1 && long_lag_below_cells * long_lag_scans <= 32, source,
          "long_lag_below_cells", "must be >= 1, times long_lag_scans at most 32");
}

void HitMaps::Reset(int width_cells, int height_cells) {
  width = width_cells;
  height = height_cells;
  const auto n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  before.assign(n, 0);
  before_near.assign(n, 0);
  now.assign(n, 0);
  free_now.assign(n, 0);
  hit_cells.clear();
}

void HitMaps::ClearHits() {
  for (const std::uint32_t i : hit_cells) {
    const auto ix = static_cast<int>(i % static_cast<std::uint32_t>(width));
    const auto iy = static_cast<int>(i / static_cast<std::uint32_t>(width));
    before[i] = 0;
    for (int y = std::max(iy - 1, 0); y <= std::min(iy + 1, height - 1); ++y) {
      for (int x = std::max(ix - 1, 0); x <= std::min(ix + 1, width - 1); ++x) {
        before_near[At(x, y)] = 0;
        now[At(x, y)] = 0;
      }
    }
  }
  hit_cells.clear();
}

void HitMaps::AddBefore(int ix, int iy) {
  if (!Inside(ix, iy)) return;
  hit_cells.push_back(static_cast<std::uint32_t>(At(ix, iy)));
  before[At(ix, iy)] = 1;
  for (int y = std::max(iy - 1, 0); y <= std::min(iy + 1, height - 1); ++y) {
    for (int x = std::max(ix - 1, 0); x <= std::min(ix + 1, width - 1); ++x) {
      before_near[At(x, y)] = 1;
    }
  }
}

void HitMaps::AddFreeNow(int ix, int iy) {
  if (Inside(ix, iy)) free_now[At(ix, iy)] = 1;
}

void HitMaps::AddNow(int ix, int iy) {
  if (!Inside(ix, iy)) return;
  hit_cells.push_back(static_cast<std::uint32_t>(At(ix, iy)));
  for (int y = iy - 1; y <= iy + 1; ++y) {
    for (int x = ix - 1; x <= ix + 1; ++x) {
      if (!Inside(x, y)) continue;
      std::uint8_t& v = now[At(x, y)];
      v = std::max<std::uint8_t>(v, x == ix && y == iy ? 2 : 1);
    }
  }
}

namespace {

// The side of the default search square.
constexpr int kDefaultSearchSide = 2 * ScanFlowOptions{}.search_half_cells + 1;

// row[i] += sign * now[i] for i < n; N: n known at compile time (0: any).
template <int N>
void AddRowScores(const std::uint8_t* now, int any_n, int sign, std::int16_t* row) {
  const int n = N > 0 ? N : any_n;
  if (sign > 0) {
    for (int i = 0; i < n; ++i) row[i] = static_cast<std::int16_t>(row[i] + now[i]);
  } else {
    for (int i = 0; i < n; ++i) row[i] = static_cast<std::int16_t>(row[i] - now[i]);
  }
}

// Adds `sign` times the scores one previous hit at (x, y) gives every displacement of the search
// square (side^2 16-bit sums, row-major). Hit by hit and row by row: the dilated map's cells under
// one hit's displacements along dx are contiguous, so a row of scores takes a row of the map in one
// vectorised sum (a gather per hit and displacement before: docs/PERFORMANCE.md, "The scan
// pair's patch scores"). A displacement that takes the hit out of the window scores
// OutsideScore, which is 0 but for the cells next to the window's edge (x or y at -1, or at the
// width or height): only those are looked at, so a hit near the edge costs what one inside does
// (cell by cell, with a bounds check each, the window's edges took a third of the measurement).
void AddHitScores(const HitMaps& maps, int x, int y, int half, int sign, std::int16_t* scores) {
  const int side = 2 * half + 1;
  const int x0 = x - half;
  // The row's window columns [lo, hi) and its offsets at x = -1 and x = width (-1: none).
  const int lo = std::clamp(-x0, 0, side);
  const int hi = std::clamp(maps.width - x0, 0, side);
  const int left = -1 - x0 >= 0 && -1 - x0 < side ? -1 - x0 : -1;
  const int right = maps.width - x0 >= 0 && maps.width - x0 < side ? maps.width - x0 : -1;
  const auto add_outside = [&](std::int16_t* row, int i, int row_y) {
    row[i] = static_cast<std::int16_t>(row[i] + sign * OutsideScore(maps, x0 + i, row_y));
  };
  for (int dy = -half; dy <= half; ++dy) {
    const int row_y = y + dy;
    if (row_y < -1 || row_y > maps.height) continue;  // no hit within a cell of it
    std::int16_t* row = &scores[static_cast<std::size_t>((dy + half) * side)];
    if (row_y == -1 || row_y == maps.height) {  // the row next to the window's top or bottom
      for (int i = std::max(lo - 1, 0); i < std::min(hi + 1, side); ++i) add_outside(row, i, row_y);
      continue;
    }
    if (lo < hi) {
      const std::uint8_t* now = &maps.now[maps.At(x0 + lo, row_y)];
      // The default search over a whole row: its length known at compile time, the loop
      // unrolls (25 sums: three vector adds and one more).
      if (lo == 0 && hi == kDefaultSearchSide) {
        AddRowScores<kDefaultSearchSide>(now, kDefaultSearchSide, sign, row);
      } else {
        AddRowScores<0>(now, hi - lo, sign, row + lo);
      }
    }
    if (left >= 0) add_outside(row, left, row_y);
    if (right >= 0) add_outside(row, right, row_y);
  }
}

}  // namespace

FlowMeasurement MeasureFlow(const HitMaps& maps, const CellIndex& cell, int search_half_cells,
                            const ScanFlowOptions& options) {
  PatchScoreCache cache;
  return MeasureFlow(maps, cell, search_half_cells, options, cache);
}

FlowMeasurement MeasureFlow(const HitMaps& maps, const CellIndex& cell, int search_half_cells,
                            const ScanFlowOptions& options, PatchScoreCache& cache) {
  const int p = options.patch_half_cells;
  const auto is_hit = [&](int x, int y) {
    return maps.Inside(x, y) && maps.before[maps.At(x, y)] != 0;
  };
  int n = 0;
  int vacated = 0;
  for (int y = cell.iy - p; y <= cell.iy + p; ++y) {
    for (int x = cell.ix - p; x <= cell.ix + p; ++x) {
      if (!is_hit(x, y)) continue;
      ++n;
      if (maps.free_now[maps.At(x, y)] != 0) ++vacated;
    }
  }
  const int half = search_half_cells;
  const auto no_scores = [](const CellIndex&) { return 0; };
  if (n < options.min_patch_hits) return Decide(n, vacated, half, no_scores, options);
  const int side = 2 * half + 1;
  const auto area = static_cast<std::size_t>(side) * static_cast<std::size_t>(side);
  if (cache.scores.size() < area) cache.scores.resize(area);
  std::int16_t* scores = cache.scores.data();
  // The cached patch's scores moved to this one: the hits of the cells in one patch and not in
  // the other, added or taken away (integers: exactly the sums scored afresh). Taken where
  // fewer than the patch's own hits.
  const int dx = cell.ix - cache.cell.ix;
  const int dy = cell.iy - cache.cell.iy;
  bool moved = false;
  if (cache.maps == &maps && cache.half == half && std::abs(dx) <= 2 * p && std::abs(dy) <= 2 * p) {
    const auto in_patch = [&](const CellIndex& c, int x, int y) {
      return std::abs(x - c.ix) <= p && std::abs(y - c.iy) <= p;
    };
    struct Change {
      int x, y, sign;
    };
    std::array<Change, 2 * (2 * kMaxPatchHalfCells + 1) * (2 * kMaxPatchHalfCells + 1)> changes;
    int count = 0;
    for (int y = std::min(cell.iy, cache.cell.iy) - p; y <= std::max(cell.iy, cache.cell.iy) + p;
         ++y) {
      for (int x = std::min(cell.ix, cache.cell.ix) - p; x <= std::max(cell.ix, cache.cell.ix) + p;
           ++x) {
        const bool in_new = in_patch(cell, x, y);
        if (in_new == in_patch(cache.cell, x, y) || !is_hit(x, y)) continue;
        changes[static_cast<std::size_t>(count++)] = Change{x, y, in_new ? 1 : -1};
      }
    }
    if (count < n) {
      for (int k = 0; k < count; ++k) {
        const Change& c = changes[static_cast<std::size_t>(k)];
        AddHitScores(maps, c.x, c.y, half, c.sign, scores);
      }
      moved = true;
    }
  }
  if (!moved) {
    std::fill_n(scores, area, 0);
    for (int y = cell.iy - p; y <= cell.iy + p; ++y) {
      for (int x = cell.ix - p; x <= cell.ix + p; ++x) {
        if (is_hit(x, y)) AddHitScores(maps, x, y, half, 1, scores);
      }
    }
  }
  cache.maps = &maps;
  cache.cell = cell;
  cache.half = half;
  // The decision's passes over the scores with the default search's size known at compile time
  // (their loops unroll and vectorise), any other size as it comes.
  const auto decide = [&](auto known_half) {
    constexpr int kKnown = decltype(known_half)::value;
    const int h = kKnown > 0 ? kKnown : half;
    const int s = 2 * h + 1;
    return Decide(
        n, vacated, h,
        [&](const CellIndex& d) {
          return int{scores[static_cast<std::size_t>((d.iy + h) * s + d.ix + h)]};
        },
        options);
  };
  constexpr int kDefaultHalf = (kDefaultSearchSide - 1) / 2;
  return half == kDefaultHalf ? decide(std::integral_constant<int, kDefaultHalf>{})
                              : decide(std::integral_constant<int, 0>{});
}

FlowMeasurement MeasureFlowReference(const HitMaps& maps, const CellIndex& cell,
                                     int search_half_cells, const ScanFlowOptions& options) {
  const int p = options.patch_half_cells;
  int hits = 0;
  int vacated = 0;  // previous hits this scan sees free
  for (int y = cell.iy - p; y <= cell.iy + p; ++y) {
    for (int x = cell.ix - p; x <= cell.ix + p; ++x) {
      if (maps.Inside(x, y) && maps.before[maps.At(x, y)] != 0) {
        ++hits;
        if (maps.free_now[maps.At(x, y)] != 0) ++vacated;
      }
    }
  }
  // score(d) by the definition: 1 for a hit now at h + d, 1/2 for one next to it (doubled).
  const auto score_at = [&](const CellIndex& d) {
    int s = 0;
    for (int y = cell.iy - p; y <= cell.iy + p; ++y) {
      for (int x = cell.ix - p; x <= cell.ix + p; ++x) {
        if (!maps.Inside(x, y) || maps.before[maps.At(x, y)] == 0) continue;
        const int tx = x + d.ix;
        const int ty = y + d.iy;
        int best = 0;
        for (int ny = ty - 1; ny <= ty + 1; ++ny) {
          for (int nx = tx - 1; nx <= tx + 1; ++nx) {
            if (!maps.Inside(nx, ny) || maps.now[maps.At(nx, ny)] != 2) continue;
            best = std::max(best, nx == tx && ny == ty ? 2 : 1);
          }
        }
        s += best;
      }
    }
    return s;
  };
  return Decide(hits, vacated, search_half_cells, score_at, options);
}

ScanFlow::ScanFlow(const ScanFlowOptions& options) : options_(options) { options_.Validate(); }

void ScanFlow::Prepare(const MeasurementGrid& z) {
  const ScrollingGridGeometry& g = z.geometry;
  has_pair_ = options_.enabled && !history_.empty();
  has_long_pair_ = has_pair_ && options_.long_lag_scans > 1 &&
                   static_cast<int>(history_.size()) == options_.long_lag_scans &&
                   z.stamp > history_.front().stamp && z.stamp > history_.back().stamp;
  // The maps of the last cycle emptied where they were marked, when the window's size is the
  // same (free_now and the long pair's now are rewritten whole below).
  const auto empty = [](HitMaps& maps, int width, int height) {
    if (maps.width == width && maps.height == height) {
      maps.ClearHits();
    } else {
      maps.Reset(width, height);
    }
  };
  empty(maps_, has_pair_ ? g.width() : 0, has_pair_ ? g.height() : 0);
  empty(long_maps_, has_long_pair_ ? g.width() : 0, has_long_pair_ ? g.height() : 0);
  // The outline maps have a size only for a scan with hits off its outline.
  const bool short_outline = has_pair_ && !history_.back().outline_global.empty();
  const bool long_outline = has_long_pair_ && !history_.front().outline_global.empty();
  empty(outline_maps_, short_outline ? g.width() : 0, short_outline ? g.height() : 0);
  empty(long_outline_maps_, long_outline ? g.width() : 0, long_outline ? g.height() : 0);
  if (!has_pair_) return;
  const auto lay_before = [&](const std::vector<CellIndex>& hits_global, HitMaps& maps) {
    for (const CellIndex& global : hits_global) {
      const CellIndex local = g.LocalFromGlobal(global);
      maps.AddBefore(local.ix, local.iy);
    }
  };
  lay_before(history_.back().hits_global, maps_);
  if (short_outline) lay_before(history_.back().outline_global, outline_maps_);
  if (has_long_pair_) {
    lay_before(history_.front().hits_global, long_maps_);
    if (long_outline) lay_before(history_.front().outline_global, long_outline_maps_);
    long_lag_scale_ =
        ToSeconds(z.stamp - history_.back().stamp) / ToSeconds(z.stamp - history_.front().stamp);
  }
  LayNow(z, maps_);
  if (has_long_pair_) {  // the same scan: its maps copied
    long_maps_.now = maps_.now;
    long_maps_.free_now = maps_.free_now;
  }
}

FlowMeasurement ScanFlow::Measure(const CellIndex& cell) const {
  PatchScoreCache short_cache, long_cache;
  return Measure(cell, short_cache, long_cache);
}

FlowMeasurement ScanFlow::Measure(const CellIndex& cell, PatchScoreCache& short_cache,
                                  PatchScoreCache& long_cache) const {
  if (!has_pair_) return {};
  const FlowMeasurement one =
      MeasureFlow(maps_, cell, options_.search_half_cells, options_, short_cache);
  const bool short_move = one.kind != FlowKind::kMoves ||
                          std::max(std::abs(one.displacement.ix), std::abs(one.displacement.iy)) <
                              options_.long_lag_below_cells;
  if (!has_long_pair_ || !short_move) return one;
  FlowMeasurement lag =
      MeasureFlow(long_maps_, cell, options_.long_lag_below_cells * options_.long_lag_scans,
                  options_, long_cache);
  if (lag.kind == FlowKind::kUnknown) return one;
  lag.lag_scans = options_.long_lag_scans;
  lag.mean_x_cells = lag.displacement.ix * long_lag_scale_;
  lag.mean_y_cells = lag.displacement.iy * long_lag_scale_;
  // The long pair's move, over one cycle, must come from a previous hit: the last scan saw
  // something within a cell of where this cell's content was then. A body faster than the long
  // pair's reach (long_lag_below_cells a cycle) that the one cycle could not measure (a filled
  // or long body sliding along itself) is otherwise aliased to the edge of that reach (a 12 m/s
  // box measured at 2 cells a cycle, its cells left with the wrong velocity).
  if (lag.kind == FlowKind::kMoves) {
    const int from_x = cell.ix - static_cast<int>(std::lround(lag.mean_x_cells));
    const int from_y = cell.iy - static_cast<int>(std::lround(lag.mean_y_cells));
    bool from_hit = false;
    for (int y = from_y - 1; y <= from_y + 1; ++y) {
      for (int x = from_x - 1; x <= from_x + 1; ++x) {
        from_hit = from_hit || (maps_.Inside(x, y) && maps_.before[maps_.At(x, y)] != 0);
      }
    }
    if (!from_hit) return one;
  }
  return lag;
}

std::vector<FlowMeasurement> ScanFlow::MeasureCells(std::span<const CellIndex> cells,
                                                    std::span<const std::uint8_t> wanted) const {
  std::vector<FlowMeasurement> out(cells.size());
  if (!has_pair_) return out;
  // The wanted cells, a tenth of the sources on the junction and in runs along rows (a body
  // newly seen): a few consecutive cells a task, each scored from the one before (PatchScoreCache);
  // few enough that the runs are shared out (blocks of cells scored afresh left one thread the
  // runs).
  std::vector<std::size_t> measured;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (wanted[i] != 0) measured.push_back(i);
  }
  constexpr std::size_t kCellsPerTask = 8;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, measured.size(), kCellsPerTask),
      [&](const tbb::blocked_range<std::size_t>& r) {
        PatchScoreCache short_cache, long_cache;
        for (std::size_t m = r.begin(); m != r.end(); ++m) {
          out[measured[m]] = Measure(cells[measured[m]], short_cache, long_cache);
        }
      },
      tbb::simple_partitioner());
  // Ambiguous staying connected to measured motion is not staying: a car's long side matches
  // itself unshifted as it drives along it, the inside of a solid body too. Connected: a chain of
  // measured cells, each within link_radius of the next, that are unknown or ambiguous staying,
  // from a moving cell. A wall seen along itself, with no motion on it, stays.
  constexpr int kLinkRadius = 2;  // crosses a one-cell gap between sparse returns
  // The window's cells -> measured cell, -1 for none: kept between calls and cleared where it
  // was set (assigning the 640 kB every cycle cost more than the search).
  std::vector<std::int32_t>& index = cell_index_;
  const std::size_t window_cells =
      static_cast<std::size_t>(maps_.width) * static_cast<std::size_t>(maps_.height);
  if (index.size() != window_cells) index.assign(window_cells, -1);
  std::vector<std::size_t> queue;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (wanted[i] == 0) continue;
    const FlowMeasurement& m = out[i];
    if (m.kind == FlowKind::kMoves) {
      queue.push_back(i);
    } else if (m.kind == FlowKind::kUnknown || m.ambiguous) {
      index[maps_.At(cells[i].ix, cells[i].iy)] = static_cast<std::int32_t>(i);
    }
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const CellIndex c = cells[queue[head]];
    for (int y = c.iy - kLinkRadius; y <= c.iy + kLinkRadius; ++y) {
      for (int x = c.ix - kLinkRadius; x <= c.ix + kLinkRadius; ++x) {
        if (!maps_.Inside(x, y)) continue;
        std::int32_t& j = index[maps_.At(x, y)];
        if (j < 0) continue;
        const auto k = static_cast<std::size_t>(j);
        j = -1;  // visited
        if (out[k].kind == FlowKind::kStays) out[k].kind = FlowKind::kUnknown;
        queue.push_back(k);
      }
    }
  }
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (wanted[i] != 0) index[maps_.At(cells[i].ix, cells[i].iy)] = -1;
  }
  return out;
}

void ScanFlow::Remember(const MeasurementGrid& z) {
  if (!options_.enabled) return;
  Scan scan;
  scan.stamp = z.stamp;
  const WindowIndexer indexer(z.geometry);
  for (const std::size_t cell : z.touched) {
    if (z.p_occupied[cell] <= 0.5f) continue;
    const CellIndex global = z.geometry.GlobalFromStorage(cell);
    scan.hits_global.push_back(global);
    const CellIndex local = indexer.Local(cell);
    if (OnOutline(z, indexer, local.ix, local.iy)) scan.outline_global.push_back(global);
  }
  // A lidar's scan is outline whole: its maps serve for both.
  if (scan.outline_global.size() == scan.hits_global.size()) scan.outline_global.clear();
  history_.push_back(std::move(scan));
  while (static_cast<int>(history_.size()) > options_.long_lag_scans) history_.pop_front();
}

}  // namespace lookout::grid
