#include "lookout/grid/scrolling_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "lookout/core/random.h"

namespace lookout::grid {
namespace {

using Eigen::Vector2d;

using GlobalKey = std::pair<int, int>;
GlobalKey Key(const CellIndex& c) { return {c.ix, c.iy}; }

// Storage indices named by a VacatedCells, expanded.
std::set<std::size_t> Expand(const ScrollingGridGeometry& g, const VacatedCells& v) {
  std::set<std::size_t> out;
  const auto w = static_cast<std::size_t>(g.width());
  for (std::size_t i = 0; i < g.CellCount(); ++i) {
    const auto column = static_cast<int>(i % w);
    const auto row = static_cast<int>(i / w);
    if (v.all || std::find(v.columns.begin(), v.columns.end(), column) != v.columns.end() ||
        std::find(v.rows.begin(), v.rows.end(), row) != v.rows.end()) {
      out.insert(i);
    }
  }
  return out;
}

TEST(ScrollingGridGeometryTest, MetresToCellToMetresRoundTrips) {
  const std::uint64_t seed = 7001;
  Rng rng(seed);
  const ScrollingGridGeometry g(0.15, 400, 400);
  for (int i = 0; i < 100000; ++i) {
    // Far from the origin too: after 100 km of driving, cells must still be exact.
    const double scale = i % 2 == 0 ? 50.0 : 1.0e5;
    const Vector2d p{rng.Uniform(-scale, scale), rng.Uniform(-scale, scale)};
    const CellIndex c = g.GlobalCellAt(p);
    const Vector2d lower_left = g.CellLowerLeftM(c);
    ASSERT_LE(lower_left.x(), p.x() + 1e-9) << "seed " << seed << " draw " << i;
    ASSERT_LE(lower_left.y(), p.y() + 1e-9) << "seed " << seed << " draw " << i;
    ASSERT_GT(lower_left.x() + 0.15, p.x() - 1e-9) << "seed " << seed << " draw " << i;
    ASSERT_GT(lower_left.y() + 0.15, p.y() - 1e-9) << "seed " << seed << " draw " << i;
    ASSERT_EQ(g.GlobalCellAt(g.CellCenterM(c)), c) << "seed " << seed << " draw " << i;
  }
}

TEST(ScrollingGridGeometryTest, CellsAreHalfOpen) {
  const ScrollingGridGeometry g(0.25, 8, 8, CellIndex{-4, -4});  // exact binary cell size
  EXPECT_EQ(g.GlobalCellAt({0.0, 0.0}), (CellIndex{0, 0}));
  EXPECT_EQ(g.GlobalCellAt({0.25, -0.25}), (CellIndex{1, -1}));
  EXPECT_EQ(g.GlobalCellAt({-1e-12, 0.2499}), (CellIndex{-1, 0}));
  EXPECT_TRUE(g.ContainsPoint({-1.0, -1.0}));
  EXPECT_FALSE(g.ContainsPoint({1.0, 0.0}));  // x = 1 m is cell 4: the window is [-4, 4)
  EXPECT_FALSE(g.StorageIndexAt({-1.0001, 0.0}).has_value());
  EXPECT_EQ(g.WindowLowerLeftM(), Vector2d(-1.0, -1.0));
  EXPECT_EQ(g.WindowCenterM(), Vector2d(0.0, 0.0));
}

TEST(ScrollingGridGeometryTest, GlobalStorageRoundTripsAcrossTheWrap) {
  const std::uint64_t seed = 7002;
  Rng rng(seed);
  for (int trial = 0; trial < 200; ++trial) {
    const int w = 1 + static_cast<int>(rng.UniformIndex(23));
    const int h = 1 + static_cast<int>(rng.UniformIndex(17));
    const CellIndex origin{static_cast<int>(rng.UniformIndex(2001)) - 1000,
                           static_cast<int>(rng.UniformIndex(2001)) - 1000};
    const ScrollingGridGeometry g(0.15, w, h, origin);
    std::vector<bool> seen(g.CellCount(), false);
    for (int ly = 0; ly < h; ++ly) {
      for (int lx = 0; lx < w; ++lx) {
        const CellIndex global = g.GlobalFromLocal({lx, ly});
        ASSERT_TRUE(g.Contains(global));
        ASSERT_EQ(g.LocalFromGlobal(global), (CellIndex{lx, ly}));
        const std::size_t s = g.StorageIndex(global);
        ASSERT_LT(s, g.CellCount());
        ASSERT_FALSE(seen[s]) << "storage index used twice; seed " << seed << " trial " << trial;
        seen[s] = true;
        ASSERT_EQ(g.GlobalFromStorage(s), global) << "seed " << seed << " trial " << trial;
        ASSERT_EQ(g.StorageIndexAt(g.CellCenterM(global)), s);
      }
    }
    ASSERT_FALSE(g.Contains(g.GlobalFromLocal({w, 0})));
    ASSERT_FALSE(g.Contains(g.GlobalFromLocal({0, -1})));
  }
}

TEST(ScrollingGridGeometryTest, RecenterKeepsThePositionInTheCentralCell) {
  ScrollingGridGeometry g(GridOptions{});
  EXPECT_EQ(g.window_origin(), (CellIndex{-200, -200}));
  for (const Vector2d& p : {Vector2d(0.1, 0.1), Vector2d(-123.456, 78.9), Vector2d(1e4, -3e3)}) {
    g.Recenter(p);
    EXPECT_EQ(g.LocalFromGlobal(g.GlobalCellAt(p)), (CellIndex{200, 200}));
    EXPECT_LE((g.WindowCenterM() - p).cwiseAbs().maxCoeff(), 0.15);
  }
  EXPECT_TRUE(g.Recenter(Vector2d(1e4, -3e3) + Vector2d(0.01, 0.01)).empty());
  const GridGeometry window = g.WindowGeometry();
  EXPECT_EQ(window.origin_m, g.WindowLowerLeftM());
  EXPECT_EQ(window.width, 400);
}

TEST(ScrollingGridGeometryTest, VacatedCellsAreExactlyTheNewCells) {
  const std::uint64_t seed = 7003;
  Rng rng(seed);
  ScrollingGridGeometry g(0.5, 11, 7, CellIndex{3, -2});
  for (int step = 0; step < 2000; ++step) {
    const ScrollingGridGeometry before = g;
    const int reach = step % 3 == 0 ? 30 : 6;  // sometimes further than the window
    const auto span = static_cast<std::uint64_t>(2 * reach + 1);
    const CellIndex to{g.window_origin().ix + static_cast<int>(rng.UniformIndex(span)) - reach,
                       g.window_origin().iy + static_cast<int>(rng.UniformIndex(span)) - reach};
    const VacatedCells v = g.MoveWindowTo(to);
    std::set<std::size_t> expected;
    for (std::size_t i = 0; i < g.CellCount(); ++i) {
      if (!before.Contains(g.GlobalFromStorage(i))) expected.insert(i);
    }
    ASSERT_EQ(Expand(g, v), expected) << "seed " << seed << " step " << step;
    ASSERT_EQ(v.empty(), expected.empty());
  }
}

// The recentering property: a value written at a world position is found at that position
// after any sequence of moves for as long as the position stays in the window, and every cell
// new to the window holds its layer's reset value. Checked against a map of global cells.
TEST(GridLayersTest, ValuesStayPutInTheWorldWhileTheWindowScrolls) {
  const std::uint64_t seed = 7004;
  Rng rng(seed);
  GridLayers layers(ScrollingGridGeometry(0.2, 13, 9, CellIndex{-6, -4}));
  const LayerId occupancy = layers.Add("occupancy", 0.5f);
  const LayerId speed = layers.Add("speed", 0.0f);
  std::map<GlobalKey, float> written;  // occupancy; speed holds -occupancy
  std::vector<Vector2d> positions;
  Vector2d centre(0.0, 0.0);
  for (int step = 0; step < 3000; ++step) {
    const ScrollingGridGeometry& g = layers.geometry();
    for (int k = 0; k < 5; ++k) {
      const Vector2d lower = g.WindowLowerLeftM();
      const Vector2d p = lower + Vector2d{rng.Uniform(0.0, 13 * 0.2), rng.Uniform(0.0, 9 * 0.2)};
      const auto i = g.StorageIndexAt(p);
      if (!i) continue;  // rounding at the upper edge
      const auto value = static_cast<float>(rng.Uniform());
      layers.Values(occupancy)[*i] = value;
      layers.Values(speed)[*i] = -value;
      written[Key(g.GlobalCellAt(p))] = value;
      positions.push_back(p);
    }
    // Positive, negative, sub-cell, and larger-than-the-window moves.
    const double reach_m = step % 7 == 0 ? 10.0 : 1.0;
    centre += Vector2d{rng.Uniform(-reach_m, reach_m), rng.Uniform(-reach_m, reach_m)};
    layers.Recenter(centre);
    for (auto it = written.begin(); it != written.end();) {
      it = layers.geometry().Contains({it->first.first, it->first.second}) ? std::next(it)
                                                                           : written.erase(it);
    }
    for (std::size_t i = 0; i < g.CellCount(); ++i) {
      const auto found = written.find(Key(g.GlobalFromStorage(i)));
      const float expected = found == written.end() ? 0.5f : found->second;
      ASSERT_EQ(layers.Values(occupancy)[i], expected) << "seed " << seed << " step " << step;
      ASSERT_EQ(layers.Values(speed)[i], found == written.end() ? 0.0f : -expected)
          << "seed " << seed << " step " << step;
    }
    for (const Vector2d& p : positions) {
      const auto value = layers.ValueAt(occupancy, p);
      if (!value) continue;
      const auto found = written.find(Key(g.GlobalCellAt(p)));
      ASSERT_EQ(*value, found == written.end() ? 0.5f : found->second);
    }
  }
}

TEST(GridLayersTest, ScrollingResetsOnlyTheNewCells) {
  GridLayers layers(ScrollingGridGeometry(GridOptions{}));
  const LayerId a = layers.Add("a", 0.5f);
  std::fill(layers.Values(a).begin(), layers.Values(a).end(), 7.0f);
  const Vector2d world_point(3.0, -4.0);
  const VacatedCells v = layers.Recenter(Vector2d(3 * 0.15 + 0.01, -2 * 0.15 + 0.01));
  EXPECT_EQ(v.columns.size(), 3u);
  EXPECT_EQ(v.rows.size(), 2u);
  EXPECT_EQ(*layers.ValueAt(a, world_point), 7.0f);
  std::size_t reset = 0;
  for (const float x : layers.Values(a)) reset += x == 0.5f ? 1 : 0;
  EXPECT_EQ(reset, 3u * 400u + 2u * 400u - 3u * 2u);  // three columns, two rows, 6 crossings

  // Further than the window: everything is new.
  std::fill(layers.Values(a).begin(), layers.Values(a).end(), 7.0f);
  EXPECT_TRUE(layers.Recenter(Vector2d(-100.0, 0.0)).all);
  for (const float x : layers.Values(a)) ASSERT_EQ(x, 0.5f);
}

TEST(ResetVacatedTest, WorksOnAnyStorageIndexedArray) {
  const ScrollingGridGeometry before(1.0, 5, 4, CellIndex{-1, 0});
  ScrollingGridGeometry g = before;
  std::vector<std::uint8_t> mask(g.CellCount(), 1);
  // Right by two columns, whose storage columns (4 and 0) straddle the wrap, and up by one row.
  const VacatedCells v = g.MoveWindowTo({1, 1});
  EXPECT_EQ(v.columns, (std::vector<int>{4, 0}));
  ResetVacated(g, v, std::span<std::uint8_t>(mask), std::uint8_t{0});
  for (std::size_t i = 0; i < g.CellCount(); ++i) {
    EXPECT_EQ(mask[i], before.Contains(g.GlobalFromStorage(i)) ? 1 : 0) << i;
  }
  // A hand-made list that is not two runs takes the cell-by-cell path.
  std::vector<float> values(g.CellCount(), 1.0f);
  ResetVacated(g, VacatedCells{false, {0, 2, 4}, {}}, std::span<float>(values), 0.0f);
  for (std::size_t i = 0; i < g.CellCount(); ++i)
    EXPECT_EQ(values[i], i % 5 % 2 == 0 ? 0.0f : 1.0f);
}

TEST(GridLayersTest, NamesLookupResetAndSwap) {
  GridLayers layers(ScrollingGridGeometry(0.15, 4, 3));
  const LayerId now = layers.Add("occupancy", 0.5f);
  const LayerId next = layers.Add("occupancy_next", 0.5f);
  EXPECT_EQ(layers.LayerCount(), 2);
  EXPECT_EQ(layers.Find("occupancy_next"), next);
  EXPECT_FALSE(layers.Find("velocity").has_value());
  EXPECT_EQ(layers.Name(now), "occupancy");
  EXPECT_EQ(layers.Values(now).size(), 12u);
  const std::span<float> before = layers.Values(now);
  layers.Add("late", 1.0f);  // adding layers does not move existing data
  EXPECT_EQ(layers.Values(now).data(), before.data());
  layers.Values(next)[5] = 0.9f;
  layers.SwapValues(now, next);
  EXPECT_EQ(layers.Values(now)[5], 0.9f);
  EXPECT_EQ(layers.Values(next)[5], 0.5f);
  EXPECT_EQ(layers.Name(now), "occupancy");
  layers.Reset(now);
  EXPECT_EQ(layers.Values(now)[5], 0.5f);
}

TEST(GridLayersTest, WindowOrderFollowsTheWindowGeometry) {
  GridLayers layers(ScrollingGridGeometry(0.5, 7, 5, CellIndex{-3, 11}));  // wraps both axes
  const LayerId id = layers.Add("id", 0.0f);
  const ScrollingGridGeometry& g = layers.geometry();
  for (std::size_t i = 0; i < g.CellCount(); ++i) {
    const CellIndex c = g.GlobalFromStorage(i);
    layers.Values(id)[i] = static_cast<float>(1000 * c.iy + c.ix);
  }
  const std::vector<float> image = layers.CopyInWindowOrder(id);
  const GridGeometry window = g.WindowGeometry();
  ASSERT_EQ(image.size(), g.CellCount());
  for (int k = 0; k < window.CellCount(); ++k) {
    const CellIndex local = window.FromLinear(k);
    const CellIndex global = g.GlobalFromLocal(local);
    EXPECT_EQ(image[static_cast<std::size_t>(k)], static_cast<float>(1000 * global.iy + global.ix));
    EXPECT_EQ(g.StorageIndexOfLocal(local), g.StorageIndex(global));
    // The window geometry and the scrolling geometry agree on where the cell is.
    EXPECT_EQ(*window.CellAt(g.CellCenterM(global)), local);
  }
}

}  // namespace
}  // namespace lookout::grid
