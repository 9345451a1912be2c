#include "lookout/grid/ray_traversal.h"

#include <gtest/gtest.h>

#include "lookout/grid/testing/segment_in_cell.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "lookout/core/random.h"

namespace lookout::grid {
namespace {

using Eigen::Vector2d;

struct Visit {
  std::size_t storage = 0;
  bool is_end = false;
};

std::vector<Visit> Traverse(const ScrollingGridGeometry& g, const Vector2d& a, const Vector2d& b) {
  std::vector<Visit> visits;
  TraverseSegment(g, a, b, [&](std::size_t i, bool is_end) { visits.push_back({i, is_end}); });
  return visits;
}

using testing::LengthInCell;

// Checks one segment against the exact answer: every window cell the segment crosses along a
// positive length is visited; every visited cell at least touches the segment; the walk is
// 4-connected, never repeats, and flags the end cell (if in the window) last.
void CheckSegment(const ScrollingGridGeometry& g, const Vector2d& a, const Vector2d& b,
                  const std::string& context) {
  const std::vector<Visit> visits = Traverse(g, a, b);
  std::set<std::size_t> visited;
  for (std::size_t k = 0; k < visits.size(); ++k) {
    ASSERT_TRUE(visited.insert(visits[k].storage).second) << "repeat; " << context;
    ASSERT_EQ(visits[k].is_end, k + 1 == visits.size() && g.ContainsPoint(b)) << context;
    const CellIndex c = g.GlobalFromStorage(visits[k].storage);
    ASSERT_TRUE(LengthInCell(g, c, a, b).has_value())
        << "visited a cell off the segment; " << context;
    if (k > 0) {
      const CellIndex p = g.GlobalFromStorage(visits[k - 1].storage);
      ASSERT_EQ(std::abs(c.ix - p.ix) + std::abs(c.iy - p.iy), 1) << "not 4-connected; " << context;
    }
  }
  if (g.ContainsPoint(a) && !visits.empty()) {
    ASSERT_EQ(visits.front().storage, *g.StorageIndexAt(a)) << context;
  }
  int touching_only = 0;
  for (std::size_t i = 0; i < g.CellCount(); ++i) {
    const std::optional<double> length = LengthInCell(g, g.GlobalFromStorage(i), a, b);
    const bool crossed = length.has_value() && *length > 1e-9;
    if (crossed) {
      ASSERT_TRUE(visited.count(i) == 1) << "missed a crossed cell; " << context;
    } else if (visited.count(i) == 1) {
      ++touching_only;
    }
  }
  // Touching in a point happens only at exact corner crossings: one per corner.
  ASSERT_LE(touching_only, 2) << context;
}

TEST(RayTraversalTest, VisitsExactlyTheCrossedCellsOfRandomSegments) {
  const std::uint64_t seed = 8001;
  Rng rng(seed);
  for (int trial = 0; trial < 3000; ++trial) {
    const int w = 1 + static_cast<int>(rng.UniformIndex(30));
    const int h = 1 + static_cast<int>(rng.UniformIndex(30));
    const double s = trial % 2 == 0 ? 0.15 : 0.25;
    // Origins that put the wrap anywhere in the window, far from the odometry origin too.
    const CellIndex origin{static_cast<int>(rng.UniformIndex(4001)) - 2000,
                           static_cast<int>(rng.UniformIndex(4001)) - 2000};
    const ScrollingGridGeometry g(s, w, h, origin);
    const Vector2d lower = g.WindowLowerLeftM();
    const Vector2d size(w * s, h * s);
    auto point = [&](double margin) {
      return Vector2d{lower.x() + rng.Uniform(-margin, 1.0 + margin) * size.x(),
                      lower.y() + rng.Uniform(-margin, 1.0 + margin) * size.y()};
    };
    // Starts mostly inside (a sensor), sometimes outside; ends anywhere, some far away.
    const Vector2d a = point(trial % 5 == 0 ? 0.5 : 0.0);
    const Vector2d b = trial % 7 == 0 ? a + 50.0 * (point(0.0) - a) : point(1.0);
    CheckSegment(g, a, b, "seed " + std::to_string(seed) + " trial " + std::to_string(trial));
  }
}

TEST(RayTraversalTest, ExactCornerCrossingsStepAlongYFirst) {
  // Cell size 0.25 m is exact in binary: the diagonal passes exactly through cell corners.
  const ScrollingGridGeometry g(0.25, 8, 8);
  const std::vector<Visit> visits = Traverse(g, {0.125, 0.125}, {0.875, 0.875});
  ASSERT_EQ(visits.size(), 7u);  // start, then (y, x) per corner: 1 + 3 + 3
  EXPECT_EQ(g.GlobalFromStorage(visits[1].storage), (CellIndex{0, 1}));
  EXPECT_EQ(g.GlobalFromStorage(visits[2].storage), (CellIndex{1, 1}));
  EXPECT_TRUE(visits.back().is_end);
  EXPECT_EQ(g.GlobalFromStorage(visits.back().storage), (CellIndex{3, 3}));
}

TEST(RayTraversalTest, SegmentOnACellBoundaryFollowsTheHalfOpenRule) {
  const ScrollingGridGeometry g(0.25, 8, 8);
  // Along y = 0.5 m exactly: the boundary between rows 1 and 2 belongs to row 2.
  for (const auto& [a, b] : {std::pair{Vector2d(0.1, 0.5), Vector2d(1.9, 0.5)},
                             std::pair{Vector2d(1.9, 0.5), Vector2d(0.1, 0.5)}}) {
    const std::vector<Visit> visits = Traverse(g, a, b);
    ASSERT_EQ(visits.size(), 8u);
    for (const Visit& v : visits) EXPECT_EQ(g.GlobalFromStorage(v.storage).iy, 2);
  }
}

TEST(RayTraversalTest, DegenerateAndOutsideSegments) {
  const ScrollingGridGeometry g(0.15, 10, 10, CellIndex{-5, -5});
  const std::vector<Visit> point = Traverse(g, {0.01, 0.02}, {0.01, 0.02});
  ASSERT_EQ(point.size(), 1u);
  EXPECT_TRUE(point[0].is_end);
  EXPECT_TRUE(Traverse(g, {5.0, 5.0}, {6.0, -5.0}).empty());  // misses the window
  // Starts outside, crosses it, ends outside: enters and leaves, no end flag.
  const std::vector<Visit> through = Traverse(g, {-2.0, 0.05}, {2.0, 0.05});
  ASSERT_EQ(through.size(), 10u);
  for (const Visit& v : through) EXPECT_FALSE(v.is_end);
}

}  // namespace
}  // namespace lookout::grid
