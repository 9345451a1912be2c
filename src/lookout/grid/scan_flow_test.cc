#include "lookout/grid/scan_flow.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "lookout/core/input_error.h"
#include "lookout/grid/filter_state.h"

namespace lookout::grid {
namespace {

constexpr int kSide = 64;

// The hits a lidar gives of a car seen from its rear-left corner: an L of two one-cell lines,
// 12 cells along x and 6 along y, corner at (x0, y0).
std::vector<CellIndex> CarOutline(int x0, int y0) {
  std::vector<CellIndex> cells;
  for (int x = 0; x < 12; ++x) cells.push_back({x0 + x, y0});
  for (int y = 1; y < 6; ++y) cells.push_back({x0, y0 + y});
  return cells;
}

HitMaps Pair(const std::vector<CellIndex>& before, const std::vector<CellIndex>& now,
             const std::vector<CellIndex>& free_now = {}) {
  HitMaps m;
  m.Reset(kSide, kSide);
  for (const CellIndex& c : before) m.AddBefore(c.ix, c.iy);
  for (const CellIndex& c : now) m.AddNow(c.ix, c.iy);
  for (const CellIndex& c : free_now) m.AddFreeNow(c.ix, c.iy);
  return m;
}

void ExpectSame(const FlowMeasurement& a, const FlowMeasurement& b) {
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.displacement, b.displacement);
  EXPECT_EQ(a.patch_hits, b.patch_hits);
  EXPECT_DOUBLE_EQ(a.score, b.score);
  EXPECT_EQ(a.ambiguous, b.ambiguous);
}

TEST(ScanFlowTest, AnOutlineThatMovedIsFoundAtItsDisplacement) {
  const ScanFlowOptions options;
  for (const CellIndex d : {CellIndex{7, 0}, CellIndex{-3, 2}, CellIndex{0, -11}}) {
    SCOPED_TRACE("displacement " + std::to_string(d.ix) + "," + std::to_string(d.iy));
    std::vector<CellIndex> moved;
    for (const CellIndex& c : CarOutline(20, 20)) moved.push_back({c.ix + d.ix, c.iy + d.iy});
    const HitMaps maps = Pair(CarOutline(20, 20), moved);
    // The corner's patch holds both sides: the motion is pinned in both axes.
    const FlowMeasurement m = MeasureFlow(maps, {21, 21}, options.search_half_cells, options);
    EXPECT_EQ(m.kind, FlowKind::kMoves);
    EXPECT_EQ(m.displacement, d);
    EXPECT_DOUBLE_EQ(m.mean_x_cells, d.ix);
    EXPECT_DOUBLE_EQ(m.mean_y_cells, d.iy);
    ExpectSame(m, MeasureFlowReference(maps, {21, 21}, options.search_half_cells, options));
  }
}

TEST(ScanFlowTest, AStaticOutlineStays) {
  const ScanFlowOptions options;
  const HitMaps maps = Pair(CarOutline(20, 20), CarOutline(20, 20));
  const FlowMeasurement corner = MeasureFlow(maps, {21, 21}, options.search_half_cells, options);
  EXPECT_EQ(corner.kind, FlowKind::kStays);
  EXPECT_FALSE(corner.ambiguous);
  // Mid-side the line matches itself shifted along it too: staying, but ambiguous.
  const FlowMeasurement side = MeasureFlow(maps, {28, 20}, options.search_half_cells, options);
  EXPECT_EQ(side.kind, FlowKind::kStays);
  EXPECT_TRUE(side.ambiguous);
}

// A solid slab (20 x 2 cells) moving 4 cells along x: its rear edge's patch matches the slab
// moved 4, 5, 6... cells (further into itself), but the scan sees through where the rear was:
// the shortest displacement, 4, is its motion. Without that rule the rear edge is ambiguous.
TEST(ScanFlowTest, ASolidBodyMovesByTheShortestDisplacementWhereItLeftFreeSpace) {
  const ScanFlowOptions options;
  std::vector<CellIndex> before, now, free_now;
  for (int y = 20; y < 22; ++y) {
    for (int x = 10; x < 30; ++x) {
      before.push_back({x, y});
      now.push_back({x + 4, y});
    }
    for (int x = 10; x < 14; ++x) free_now.push_back({x, y});
  }
  const FlowMeasurement seen_through =
      MeasureFlow(Pair(before, now, free_now), {11, 20}, options.search_half_cells, options);
  EXPECT_EQ(seen_through.kind, FlowKind::kMoves);
  EXPECT_EQ(seen_through.displacement, (CellIndex{4, 0}));
  ScanFlowOptions no_shortest = options;
  no_shortest.shortest_min_vacated_share = 1.0;
  no_shortest.shortest_below_stay_share = 0.0;
  const FlowMeasurement without =
      MeasureFlow(Pair(before, now, free_now), {11, 20}, options.search_half_cells, no_shortest);
  EXPECT_EQ(without.kind, FlowKind::kUnknown);
}

// A straight surface moving along itself (the aperture problem): no displacement is claimed.
TEST(ScanFlowTest, ALineSlidingAlongItselfIsNoMotion) {
  const ScanFlowOptions options;
  std::vector<CellIndex> before, now;
  for (int x = 0; x < 40; ++x) before.push_back({10 + x, 30});
  for (int x = 0; x < 40; ++x) now.push_back({15 + x, 30});
  const HitMaps maps = Pair(before, now);
  const FlowMeasurement m = MeasureFlow(maps, {30, 30}, options.search_half_cells, options);
  EXPECT_NE(m.kind, FlowKind::kMoves);
}

TEST(ScanFlowTest, TooFewHitsAreUnknown) {
  const ScanFlowOptions options;
  const HitMaps maps = Pair({{30, 30}, {31, 30}}, {{33, 30}, {34, 30}});
  const FlowMeasurement m = MeasureFlow(maps, {30, 30}, options.search_half_cells, options);
  EXPECT_EQ(m.kind, FlowKind::kUnknown);
  EXPECT_EQ(m.patch_hits, 2);
}

// The fast path (offsets gathered once, lookups into the dilated map) against the definition
// on random hit sets: every field equal.
TEST(ScanFlowTest, FastPathMatchesTheDefinitionOnRandomScans) {
  ScanFlowOptions options;
  options.search_half_cells = 6;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> cell(0, kSide - 1), shift(-4, 4), keep(0, 9);
    std::vector<CellIndex> before, now, free_now;
    const CellIndex d{shift(rng), shift(rng)};
    for (int k = 0; k < 300; ++k) {
      const CellIndex c{cell(rng), cell(rng)};
      before.push_back(c);
      if (keep(rng) < 8) now.push_back({c.ix + d.ix, c.iy + d.iy});  // most moved, some lost
      if (keep(rng) == 0) now.push_back({cell(rng), cell(rng)});     // and clutter
      if (keep(rng) < 4) free_now.push_back(c);                      // some seen through
    }
    const HitMaps maps = Pair(before, now, free_now);
    for (int k = 0; k < 40; ++k) {
      const CellIndex at{cell(rng), cell(rng)};
      ExpectSame(MeasureFlow(maps, at, options.search_half_cells, options),
                 MeasureFlowReference(maps, at, options.search_half_cells, options));
    }
  }
}

// Scored from the patch before (PatchScoreCache): along a walk of small steps (runs along rows,
// diagonal and longer steps, the window's edges), with the maps and the search changing under
// one cache, every field as the definition.
TEST(ScanFlowTest, ScoresMovedFromTheCachedPatchAreTheDefinition) {
  ScanFlowOptions options;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> cell(0, kSide - 1), shift(-3, 3), step(-2, 2), coin(0, 9);
    std::array<HitMaps, 2> maps;
    for (HitMaps& m : maps) {
      std::vector<CellIndex> before, now, free_now;
      const CellIndex d{shift(rng), shift(rng)};
      for (int k = 0; k < 900; ++k) {  // dense: most patches hold more hits than a step changes
        const CellIndex c{cell(rng), cell(rng)};
        before.push_back(c);
        if (coin(rng) < 8) now.push_back({c.ix + d.ix, c.iy + d.iy});
        if (coin(rng) < 2) free_now.push_back(c);
      }
      m = Pair(before, now, free_now);
    }
    PatchScoreCache cache;
    CellIndex at{cell(rng), cell(rng)};
    for (int k = 0; k < 300; ++k) {
      const int r = coin(rng);
      if (r < 6) {
        at.ix = std::clamp(at.ix + 1, 0, kSide - 1);  // along a row
      } else if (r < 9) {
        at = {std::clamp(at.ix + step(rng), 0, kSide - 1),
              std::clamp(at.iy + step(rng), 0, kSide - 1)};
      } else {
        at = {cell(rng), cell(rng)};
      }
      const HitMaps& m = maps[static_cast<std::size_t>(k / 100 % 2)];
      const int half = k < 200 ? options.search_half_cells : 5;
      ExpectSame(MeasureFlow(m, at, half, options, cache),
                 MeasureFlowReference(m, at, half, options));
    }
  }
}

// Scans of a scrolling grid: a walker-sized arc moving 0.6 cell a cycle. One cycle cannot tell
// 0.6 cell from staying; the scan long_lag_scans back can, to half a cell over the baseline.
MeasurementGrid ArcScan(const ScrollingGridGeometry& g, double x_cells, TimeNs stamp) {
  MeasurementGrid z{g, stamp, std::vector<float>(g.CellCount(), 0.5f), {}, {}};
  for (int k = -2; k <= 2; ++k) {
    const CellIndex local{static_cast<int>(std::lround(x_cells + 0.3 * k * k)), 30 + k};
    const std::size_t s = g.StorageIndexOfLocal(local);
    z.p_occupied[s] = 0.7f;
    z.touched.push_back(s);
  }
  return z;
}

// The map of cells at or next to a previous scan's hit, against its definition: every cell of a
// map with random hits, edges and corners among them, is 1 exactly where a hit lies within its
// 3 x 3 block.
TEST(ScanFlowTest, BeforeNearIsEveryCellNextToAHitOfThePreviousScan) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    HitMaps m;
    m.Reset(37, 23);
    std::uniform_int_distribution<int> x(-2, m.width + 1), y(-2, m.height + 1);
    for (int k = 0; k < 60; ++k) m.AddBefore(x(rng), y(rng));
    for (int cy = 0; cy < m.height; ++cy) {
      for (int cx = 0; cx < m.width; ++cx) {
        bool near = false;
        for (int ny = cy - 1; ny <= cy + 1; ++ny) {
          for (int nx = cx - 1; nx <= cx + 1; ++nx) {
            near = near || (m.Inside(nx, ny) && m.before[m.At(nx, ny)] != 0);
          }
        }
        ASSERT_EQ(m.before_near[m.At(cx, cy)] != 0, near) << "cell " << cx << ", " << cy;
      }
    }
  }
}

TEST(ScanFlowTest, ASlowArcIsMeasuredOverTheLongBaseline) {
  ScanFlowOptions options;
  options.enabled = true;
  ScanFlow flow(options);
  const ScrollingGridGeometry g(0.15, kSide, kSide, CellIndex{-5, 7});
  const TimeNs period = 80'000'000;  // 12.5 Hz
  FlowMeasurement m;
  for (int k = 0; k <= options.long_lag_scans; ++k) {
    const MeasurementGrid z = ArcScan(g, 20.0 + 0.6 * k, period * (k + 1));
    flow.Prepare(z);
    m = flow.Measure({static_cast<int>(std::lround(20.0 + 0.6 * (k - 1))), 30});
    flow.Remember(z);
  }
  ASSERT_EQ(m.kind, FlowKind::kMoves);
  EXPECT_EQ(m.lag_scans, options.long_lag_scans);
  EXPECT_NEAR(m.mean_x_cells, 0.6, 0.5 / options.long_lag_scans + 1e-9);
  EXPECT_NEAR(m.mean_y_cells, 0.0, 1e-9);
}

// MeasureCells: an ambiguous "stays" connected to measured motion is not staying (a car's long
// side matches itself unshifted as it drives along it; its corner pins the motion); on its own
// (a wall seen along itself) it is.
TEST(ScanFlowTest, AmbiguousStayingConnectedToMotionIsUnknown) {
  ScanFlowOptions options;
  options.enabled = true;
  options.long_lag_scans = 1;
  const ScrollingGridGeometry g(0.15, kSide, kSide);
  const auto scan = [&](const std::vector<CellIndex>& cells, TimeNs stamp) {
    MeasurementGrid z{g, stamp, std::vector<float>(g.CellCount(), 0.5f), {}, {}};
    for (const CellIndex& c : cells) {
      const std::size_t s = g.StorageIndexOfLocal(c);
      z.p_occupied[s] = 0.7f;
      z.touched.push_back(s);
    }
    return z;
  };
  // A wall, and a car 30 cells long driving 7 cells along its side.
  std::vector<CellIndex> before, now;
  for (int x = 0; x < 50; ++x) {
    before.push_back({5 + x, 55});
    now.push_back({5 + x, 55});
  }
  for (int x = 0; x < 30; ++x) {
    before.push_back({5 + x, 20});
    now.push_back({12 + x, 20});
  }
  for (int y = 1; y < 6; ++y) {
    before.push_back({5, 20 + y});
    now.push_back({12, 20 + y});
  }
  ScanFlow flow(options);
  flow.Remember(scan(before, 1));
  flow.Prepare(scan(now, 2));
  // Every hit of the previous scan is a cell to measure.
  const std::vector<std::uint8_t> wanted(before.size(), 1);
  const std::vector<FlowMeasurement> m = flow.MeasureCells(before, wanted);
  const auto index_of = [&](const CellIndex& c) {
    const auto it = std::find(before.begin(), before.end(), c);
    EXPECT_NE(it, before.end());
    return static_cast<std::size_t>(it - before.begin());
  };
  const FlowMeasurement wall = m[index_of({30, 55})];
  EXPECT_EQ(wall.kind, FlowKind::kStays);
  EXPECT_TRUE(wall.ambiguous);
  const FlowMeasurement corner = m[index_of({5, 21})];
  EXPECT_EQ(corner.kind, FlowKind::kMoves);
  EXPECT_EQ(corner.displacement, (CellIndex{7, 0}));
  // Mid-side: on its own it stays, ambiguously; connected to the corner, it is left unknown.
  const HitMaps pair = Pair(before, now);
  const FlowMeasurement side_alone =
      MeasureFlow(pair, {25, 20}, options.search_half_cells, options);
  EXPECT_EQ(side_alone.kind, FlowKind::kStays);
  EXPECT_TRUE(side_alone.ambiguous);
  EXPECT_EQ(m[index_of({25, 20})].kind, FlowKind::kUnknown);
}

// A solid block's hits: its border is its outline, its inside is not; a line is outline
// whole; a hit on the window's edge is outline (off the window counts as no hit).
TEST(ScanFlowTest, TheOutlineIsEveryHitWithANeighbourNotHit) {
  const ScrollingGridGeometry g(0.15, 24, 16, CellIndex{-7, 3});
  const WindowIndexer indexer(g);
  MeasurementGrid z{g, 1, std::vector<float>(g.CellCount(), 0.3f), {}, {}};
  const auto hit = [&](int x, int y) { z.p_occupied[indexer.Storage(x, y)] = 0.7f; };
  for (int y = 4; y < 10; ++y) {
    for (int x = 5; x < 17; ++x) hit(x, y);  // 12 x 6
  }
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 3; ++x) hit(x, y);  // 3 x 4 in the window's corner
  }
  for (int x = 18; x < 24; ++x) hit(x, 12);  // a line
  int outline = 0, inside = 0;
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      if (z.p_occupied[indexer.Storage(x, y)] < 0.5f) continue;
      const bool expected_inside =
          (x > 5 && x < 16 && y > 4 && y < 9) || (x == 1 && y > 0 && y < 3);
      EXPECT_EQ(OnOutline(z, indexer, x, y), !expected_inside) << x << " " << y;
      ++(expected_inside ? inside : outline);
    }
  }
  EXPECT_EQ(inside, 10 * 4 + 2);
  EXPECT_EQ(outline, 2 * 12 + 2 * 4 + 12 - 2 + 6);
}

// Prepare lays this scan's hits and free cells on the window row by row from storage, and the
// previous scans' outlines where they are not all their hits; the maps must be those of the
// cells' own window coordinates wherever the window has scrolled (its storage wraps inside
// each row and between rows).
TEST(ScanFlowTest, PrepareLaysTheScanOnTheWindowWhereverItScrolled) {
  const std::uint64_t seed = 3101;
  std::mt19937_64 rng(seed);
  ScanFlowOptions options;
  options.enabled = true;
  options.long_lag_scans = 2;
  for (const CellIndex origin : {CellIndex{0, 0}, CellIndex{-5, 7}, CellIndex{37, -70}}) {
    const ScrollingGridGeometry g(0.15, kSide, kSide - 9, origin);
    // Sparse scans (a hit in ten cells) and dense ones (nine in ten: many hits inside areas of
    // hits, which the outline pairs leave out).
    const auto random_scan = [&](TimeNs stamp) {
      const bool dense = stamp % 2 == 0;
      MeasurementGrid z{g, stamp, std::vector<float>(g.CellCount(), 0.5f), {}, {}};
      for (std::size_t s = 0; s < g.CellCount(); ++s) {
        const auto draw = rng() % 10;
        if (!dense && draw >= 3) continue;
        z.p_occupied[s] = (dense ? draw != 0 : draw == 0) ? 0.7f : 0.3f;
        z.touched.push_back(s);
      }
      return z;
    };
    // A hit with a neighbour that is no hit or off the window, by its definition.
    const auto outline = [&](const MeasurementGrid& scan, const CellIndex& local) {
      const auto hit = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < g.width() && y < g.height() &&
               scan.p_occupied[g.StorageIndexOfLocal({x, y})] > 0.5f;
      };
      if (!hit(local.ix, local.iy)) return false;
      for (int y = local.iy - 1; y <= local.iy + 1; ++y) {
        for (int x = local.ix - 1; x <= local.ix + 1; ++x) {
          if (!hit(x, y)) return true;
        }
      }
      return false;
    };
    ScanFlow flow(options);
    std::vector<MeasurementGrid> scans = {random_scan(1), random_scan(2)};
    flow.Remember(scans[0]);
    flow.Remember(scans[1]);
    // Cycle after cycle on one ScanFlow: each cycle's maps are emptied only where the last
    // cycle's marked them (HitMaps::ClearHits); no mark may survive into the next.
    for (TimeNs stamp = 3; stamp <= 6; ++stamp) {
      const MeasurementGrid& z = scans.emplace_back(random_scan(stamp));
      flow.Prepare(z);
      // The maps by their definition, from each touched cell's window coordinates.
      const auto laid = [&](const MeasurementGrid& before) {
        HitMaps expected;
        expected.Reset(g.width(), g.height());
        for (const std::size_t s : before.touched) {
          const CellIndex local = g.LocalFromGlobal(g.GlobalFromStorage(s));
          if (before.p_occupied[s] > 0.5f) expected.AddBefore(local.ix, local.iy);
        }
        for (const std::size_t s : z.touched) {
          const CellIndex local = g.LocalFromGlobal(g.GlobalFromStorage(s));
          if (z.p_occupied[s] > 0.5f) expected.AddNow(local.ix, local.iy);
          if (z.p_occupied[s] < 0.5f) expected.AddFreeNow(local.ix, local.iy);
        }
        return expected;
      };
      ASSERT_NE(flow.long_pair(), nullptr);
      const std::size_t k = scans.size() - 1;
      const std::array<std::pair<const HitMaps*, HitMaps>, 2> pairs = {
          std::pair{&flow.short_pair(), laid(scans[k - 1])},
          std::pair{flow.long_pair(), laid(scans[k - 2])}};
      for (const auto& [maps, expected] : pairs) {
        SCOPED_TRACE("seed " + std::to_string(seed) + ", origin " + std::to_string(origin.ix) +
                     " " + std::to_string(origin.iy) + ", cycle " + std::to_string(stamp));
        EXPECT_EQ(maps->now, expected.now);
        EXPECT_EQ(maps->free_now, expected.free_now);
        EXPECT_EQ(maps->before, expected.before);
        EXPECT_EQ(maps->before_near, expected.before_near);
      }
      // The outline pairs: the previous scans' outline hits only (the dense scans have others).
      const auto laid_outline = [&](const MeasurementGrid& before) {
        HitMaps expected;
        expected.Reset(g.width(), g.height());
        for (const std::size_t s : before.touched) {
          const CellIndex local = g.LocalFromGlobal(g.GlobalFromStorage(s));
          if (outline(before, local)) expected.AddBefore(local.ix, local.iy);
        }
        return expected;
      };
      ASSERT_NE(flow.long_outline_pair(), nullptr);
      const std::array<std::pair<const HitMaps*, HitMaps>, 2> outline_pairs = {
          std::pair{&flow.short_outline_pair(), laid_outline(scans[k - 1])},
          std::pair{flow.long_outline_pair(), laid_outline(scans[k - 2])}};
      for (const auto& [maps, expected] : outline_pairs) {
        SCOPED_TRACE("outline, seed " + std::to_string(seed) + ", cycle " + std::to_string(stamp));
        EXPECT_EQ(maps->before, expected.before);
        EXPECT_EQ(maps->before_near, expected.before_near);
      }
      flow.Remember(z);
    }
  }
}

// ClearHits undoes AddBefore and AddNow wherever they marked, edges and corners among them,
// and leaves free_now as it was.
TEST(ScanFlowTest, ClearHitsEmptiesWhatTheHitsMarked) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    HitMaps m;
    m.Reset(37, 23);
    std::uniform_int_distribution<int> x(-2, m.width + 1), y(-2, m.height + 1);
    for (int k = 0; k < 60; ++k) {
      m.AddBefore(x(rng), y(rng));
      m.AddNow(x(rng), y(rng));
      m.AddFreeNow(x(rng), y(rng));
    }
    const std::vector<std::uint8_t> free_now = m.free_now;
    m.ClearHits();
    const std::vector<std::uint8_t> zero(m.before.size(), 0);
    EXPECT_EQ(m.before, zero);
    EXPECT_EQ(m.before_near, zero);
    EXPECT_EQ(m.now, zero);
    EXPECT_EQ(m.free_now, free_now);
  }
}

TEST(ScanFlowTest, OptionsOutOfRangeAreNamed) {
  ScanFlowOptions options;
  options.patch_half_cells = 9;
  try {
    options.Validate("test.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("patch_half_cells"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lookout::grid
