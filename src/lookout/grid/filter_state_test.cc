#include "lookout/grid/filter_state.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <vector>

#include "lookout/core/random.h"

namespace lookout::grid {
namespace {

TEST(WindowIndexerTest, LocalInvertsStorageAcrossTheWrap) {
  const std::uint64_t seed = 20261206;
  Rng rng(seed);
  for (int trial = 0; trial < 200; ++trial) {
    const int w = 1 + static_cast<int>(rng.UniformIndex(41));
    const int h = 1 + static_cast<int>(rng.UniformIndex(29));
    const CellIndex origin{static_cast<int>(rng.UniformIndex(2001)) - 1000,
                           static_cast<int>(rng.UniformIndex(2001)) - 1000};
    const ScrollingGridGeometry g(0.15, w, h, origin);
    const WindowIndexer indexer(g);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::size_t s = indexer.Storage(x, y);
        ASSERT_EQ(s, g.StorageIndexOfLocal({x, y})) << "seed " << seed << " trial " << trial;
        ASSERT_EQ(indexer.Local(s), (CellIndex{x, y})) << "seed " << seed << " trial " << trial;
        ASSERT_EQ(indexer.Local(s), g.LocalFromGlobal(g.GlobalFromStorage(s)));
      }
    }
  }
}

// The target index by its definition: targets in order of first appearance over the entries,
// each with its entries in entry order; entries leaving the window filed nowhere.
TargetIndex LiteralTargetIndex(const Associations& a) {
  TargetIndex index;
  index.first.push_back(0);
  for (std::size_t e = 0; e < a.EntryCount(); ++e) {
    if (a.target[e] == kOutsideWindow) continue;
    const auto t = static_cast<std::size_t>(a.target[e]);
    bool known = false;
    for (const std::size_t seen : index.targets) known = known || seen == t;
    if (known) continue;
    index.targets.push_back(t);
    for (std::size_t f = e; f < a.EntryCount(); ++f) {
      if (a.target[f] == a.target[e]) index.entries.push_back(static_cast<std::uint32_t>(f));
    }
    index.first.push_back(index.entries.size());
  }
  return index;
}

TEST(TargetIndexTest, IsTheDefinitionOnRandomEntries) {
  const std::uint64_t seed = 7103;
  Rng rng(seed);
  constexpr std::size_t kCells = 300;
  FilterWorkspace workspace;
  workspace.Resize(kCells);
  for (int trial = 0; trial < 100; ++trial) {
    Associations a;
    const std::size_t entries = rng.UniformIndex(400);
    // Few distinct targets, so that most are shared, as windows overlap on the grid.
    const std::size_t span = 1 + rng.UniformIndex(kCells);
    for (std::size_t e = 0; e < entries; ++e) {
      a.target.push_back(rng.Bernoulli(0.1) ? kOutsideWindow
                                            : static_cast<EntryTarget>(rng.UniformIndex(span)));
    }
    const TargetIndex fast = BuildTargetIndex(a, workspace);
    const TargetIndex literal = LiteralTargetIndex(a);
    ASSERT_EQ(fast.targets, literal.targets) << "seed " << seed << " trial " << trial;
    ASSERT_EQ(fast.first, literal.first) << "seed " << seed << " trial " << trial;
    ASSERT_EQ(fast.entries, literal.entries) << "seed " << seed << " trial " << trial;
    // The workspace is left as it was found.
    for (const std::uint32_t slot : workspace.slot_of_cell) {
      ASSERT_EQ(slot, FilterWorkspace::kNone) << "seed " << seed << " trial " << trial;
    }
  }
}

// The update list holds each target, source and evidence cell once, and MovedCells is exactly
// its cells that are a target or a source (the carried attributes' passes stop after them).
TEST(UpdateListTest, MovedCellsAreTheTargetsAndTheSources) {
  const std::uint64_t seed = 7211;
  Rng rng(seed);
  constexpr std::size_t kCells = 300;
  FilterWorkspace workspace;
  workspace.Resize(kCells);
  for (int trial = 0; trial < 100; ++trial) {
    Associations a;
    std::vector<char> is_source(kCells, 0);
    for (std::size_t cell = 0; cell < kCells; ++cell) {
      if (!rng.Bernoulli(0.05)) continue;
      a.source.push_back(cell);
      is_source[cell] = 1;
    }
    std::vector<char> is_target(kCells, 0);
    for (std::size_t e = rng.UniformIndex(200); e > 0; --e) {
      const std::size_t cell = rng.UniformIndex(kCells);
      a.target.push_back(static_cast<EntryTarget>(cell));
      is_target[cell] = 1;
    }
    MeasurementGrid z;
    z.p_occupied.assign(kCells, 0.5f);
    for (std::size_t cell = 0; cell < kCells; ++cell) {
      if (!rng.Bernoulli(0.3)) continue;
      z.p_occupied[cell] = 0.3f;
      z.touched.push_back(cell);
    }
    MapSources(a, workspace);
    const TargetIndex targets = BuildTargetIndex(a, workspace);
    const std::vector<UpdateCell> cells = BuildUpdateList(targets, a, z, workspace);
    ClearSourceMap(a, workspace);
    const std::span<const UpdateCell> moved = MovedCells(cells);
    std::vector<int> listed(kCells, 0);
    for (std::size_t u = 0; u < cells.size(); ++u) {
      const std::size_t cell = cells[u].cell;
      ++listed[cell];
      ASSERT_EQ(u < moved.size(), is_source[cell] || is_target[cell])
          << "seed " << seed << " trial " << trial << " cell " << cell;
    }
    for (std::size_t cell = 0; cell < kCells; ++cell) {
      const bool evidence = z.p_occupied[cell] != 0.5f;
      ASSERT_EQ(listed[cell], is_source[cell] || is_target[cell] || evidence ? 1 : 0)
          << "seed " << seed << " trial " << trial << " cell " << cell;
    }
  }
}

}  // namespace
}  // namespace lookout::grid
