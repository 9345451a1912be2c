#include "lookout/lidar/local_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "lookout/core/input_error.h"
#include "lookout/core/pose2.h"
#include "lookout/core/random.h"

namespace lookout::lidar {
namespace {

MapOptions SmallMap() {
  MapOptions o;
  o.cell_size_m = 0.1;
  o.window_cells = 128;  // 12.8 m
  o.field_max_distance_m = 0.5;
  return o;
}

// The slow literal reference: distance to the nearest occupied cell of the window by
// scanning the cells around c.
float BruteForceDistance(const LocalMap& map, const CellIndex& c) {
  const MapOptions& o = map.options();
  double best = o.field_max_distance_m;
  // Cells further than the field's reach cannot count: only the square around c is scanned.
  const int reach = static_cast<int>(std::ceil(o.field_max_distance_m / o.cell_size_m));
  const CellIndex origin = map.WindowOrigin();
  for (int y = std::max(origin.iy, c.iy - reach);
       y < std::min(origin.iy + o.window_cells, c.iy + reach + 1); ++y) {
    for (int x = std::max(origin.ix, c.ix - reach);
         x < std::min(origin.ix + o.window_cells, c.ix + reach + 1); ++x) {
      if (!map.Occupied({x, y})) continue;
      const double d = o.cell_size_m * std::hypot(x - c.ix, y - c.iy);
      if (d <= o.field_max_distance_m) best = std::min(best, d);
    }
  }
  return static_cast<float>(best);
}

void ExpectFieldExact(const LocalMap& map, const std::string& context) {
  const CellIndex origin = map.WindowOrigin();
  const int n = map.options().window_cells;
  int wrong = 0;
  for (int y = origin.iy; y < origin.iy + n; ++y) {
    for (int x = origin.ix; x < origin.ix + n; ++x) {
      const float expected = BruteForceDistance(map, {x, y});
      if (std::abs(map.FieldDistance({x, y}) - expected) > 1e-5f && ++wrong < 5) {
        ADD_FAILURE() << context << ": cell (" << x << ", " << y << ") field "
                      << map.FieldDistance({x, y}) << " brute force " << expected;
      }
    }
  }
  EXPECT_EQ(wrong, 0) << context;
}

TEST(LocalMap, CellConversionRoundTrips) {
  const LocalMap map(SmallMap());
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.05, 0.05), Eigen::Vector2d(-0.01, 3.99),
                                   Eigen::Vector2d(-6.3, 2.0)}) {
    const CellIndex c = map.CellOf(p);
    EXPECT_EQ(map.CellOf(map.CellCentre(c)), c);
    EXPECT_LE((map.CellCentre(c) - p).cwiseAbs().maxCoeff(), 0.05 + 1e-12);
  }
  EXPECT_EQ(map.CellOf({-0.01, -0.01}), (CellIndex{-1, -1}));
}

TEST(LocalMap, HitBeforeMissInOneScan) {
  const MapOptions o = SmallMap();
  LocalMap map(o);
  // Beam 1 ends at (2, 0); beam 2 passes through that cell to (4, 0) in the same scan.
  const std::vector<Eigen::Vector2d> hits = {{2.05, 0.05}, {4.05, 0.05}};
  map.InsertScan({0.05, 0.05}, hits, {});
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({2.05, 0.05})), o.log_odds_hit);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({4.05, 0.05})), o.log_odds_hit);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({1.05, 0.05})), o.log_odds_miss);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({3.05, 0.05})), o.log_odds_miss);
  // Reversed order of the beams: the same answer.
  LocalMap reversed(o);
  const std::vector<Eigen::Vector2d> hits_reversed = {{4.05, 0.05}, {2.05, 0.05}};
  reversed.InsertScan({0.05, 0.05}, hits_reversed, {});
  EXPECT_FLOAT_EQ(reversed.LogOdds(reversed.CellOf({2.05, 0.05})), o.log_odds_hit);
}

TEST(LocalMap, EachCellUpdatedOncePerScan) {
  const MapOptions o = SmallMap();
  LocalMap map(o);
  // Three beams into one cell and many rays through one cell near the origin.
  const std::vector<Eigen::Vector2d> hits = {{3.01, 1.01}, {3.05, 1.05}, {3.09, 1.09}};
  map.InsertScan({0.05, 0.05}, hits, {});
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({3.05, 1.05})), o.log_odds_hit);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({0.15, 0.05})), o.log_odds_miss);
}

TEST(LocalMap, LogOddsAreClamped) {
  const MapOptions o = SmallMap();
  LocalMap map(o);
  const std::vector<Eigen::Vector2d> hits = {{2.05, 0.05}};
  for (int i = 0; i < 50; ++i) map.InsertScan({0.05, 0.05}, hits, {});
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({2.05, 0.05})), o.log_odds_max);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({1.05, 0.05})), o.log_odds_min);
  // A clamped cell changes its mind after a bounded number of contrary scans.
  const std::vector<Eigen::Vector2d> through = {{3.05, 0.05}};
  const int needed = static_cast<int>(std::ceil((o.log_odds_max - o.occupied_log_odds) /
                                                -o.log_odds_miss)) + 1;
  for (int i = 0; i < needed; ++i) map.InsertScan({0.05, 0.05}, through, {});
  EXPECT_FALSE(map.Occupied(map.CellOf({2.05, 0.05})));
}

TEST(LocalMap, HitsBeyondInsertRangeOnlyClear) {
  MapOptions o = SmallMap();
  o.max_insert_range_m = 2.0;
  LocalMap map(o);
  const std::vector<Eigen::Vector2d> hits = {{4.05, 0.05}};
  map.InsertScan({0.05, 0.05}, hits, {});
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({4.05, 0.05})), 0.0f);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({1.55, 0.05})), o.log_odds_miss);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({3.05, 0.05})), 0.0f);
}

// A map with a minimum insert range updates nothing nearer than it: a ray's cells from there
// on, a hit beyond it; a hit nearer is left out with its whole ray.
TEST(LocalMap, NothingNearerThanTheMinimumInsertRangeIsUpdated) {
  MapOptions o = SmallMap();
  o.min_insert_range_m = 2.0;
  LocalMap map(o);
  const Eigen::Vector2d origin(0.05, 0.05);
  const std::vector<Eigen::Vector2d> hits = {{3.05, 0.05}, {0.05, 1.05}};
  map.InsertScan(origin, hits, {});
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({3.05, 0.05})), o.log_odds_hit);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({2.55, 0.05})), o.log_odds_miss);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({1.05, 0.05})), 0.0f);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({0.05, 1.05})), 0.0f);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({0.05, 0.55})), 0.0f);
  o.min_insert_range_m = o.max_insert_range_m;
  EXPECT_THROW(o.Validate(), InputError);
}

// A bare hit marks its cell and clears nothing: its ray is the caller's (the lidar chain clears
// it only up to where the neighbouring beams found a surface).
TEST(LocalMap, BareHitsMarkTheirCellOnly) {
  const MapOptions o = SmallMap();
  LocalMap map(o);
  const Eigen::Vector2d origin(0.05, 0.05);
  const std::vector<Eigen::Vector2d> bare = {{3.05, 0.05}};
  const std::vector<Eigen::Vector2d> short_ray = {{1.05, 0.05}};
  map.InsertScan(origin, {}, short_ray, {}, bare);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({3.05, 0.05})), o.log_odds_hit);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({0.55, 0.05})), o.log_odds_miss);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({2.05, 0.05})), 0.0f);
  // The same return as an ordinary hit clears its whole ray.
  LocalMap whole(o);
  whole.InsertScan(origin, bare, {});
  EXPECT_FLOAT_EQ(whole.LogOdds(whole.CellOf({2.05, 0.05})), o.log_odds_miss);
  EXPECT_FLOAT_EQ(whole.LogOdds(whole.CellOf({3.05, 0.05})), o.log_odds_hit);
}

// A beam that saw nothing clears its ray only up to the first occupied cell: the mapped wall
// it should have hit keeps its log-odds and the space behind the wall stays unknown; the
// same ray as a free end (a dynamic return's) clears through.
TEST(LocalMap, EmptyBeamsClearUpToTheFirstOccupiedCell) {
  const MapOptions o = SmallMap();
  LocalMap map(o);
  const Eigen::Vector2d origin(0.05, 0.05);
  const std::vector<Eigen::Vector2d> wall = {{3.05, 0.05}};
  for (int i = 0; i < 3; ++i) map.InsertScan(origin, wall, {});
  const float wall_before = map.LogOdds(map.CellOf({3.05, 0.05}));
  ASSERT_TRUE(map.Occupied(map.CellOf({3.05, 0.05})));
  const float before_wall = map.LogOdds(map.CellOf({1.55, 0.05}));
  const std::vector<Eigen::Vector2d> empty = {{5.05, 0.05}, {0.05, 4.05}};
  map.InsertScan(origin, {}, {}, empty);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({1.55, 0.05})), before_wall + o.log_odds_miss);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({3.05, 0.05})), wall_before);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({4.05, 0.05})), 0.0f);
  // Nothing in the way: cleared to its end.
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({0.05, 2.05})), o.log_odds_miss);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({0.05, 4.05})), o.log_odds_miss);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({0.05, 4.55})), 0.0f);
  const std::vector<Eigen::Vector2d> free_end = {{5.05, 0.05}};
  map.InsertScan(origin, {}, free_end);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({3.05, 0.05})), wall_before + o.log_odds_miss);
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({4.05, 0.05})), o.log_odds_miss);
  ExpectFieldExact(map, "after the empty and free rays");
}

TEST(LocalMap, LikelihoodFieldMatchesBruteForceAsCellsAppearAndVanish) {
  const MapOptions o = SmallMap();
  LocalMap map(o);
  const std::uint64_t seed = 12345;
  Rng rng(seed);
  for (int scan = 0; scan < 30; ++scan) {
    const Eigen::Vector2d origin{rng.Uniform(-2.0, 2.0), rng.Uniform(-2.0, 2.0)};
    std::vector<Eigen::Vector2d> hits;
    for (int i = 0; i < 40; ++i) {
      const double a = rng.Uniform(-kPi, kPi);
      const double r = rng.Uniform(0.5, 5.0);
      hits.emplace_back(origin + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    map.InsertScan(origin, hits, {});
    if (scan % 10 == 9) ExpectFieldExact(map, "seed 12345 scan " + std::to_string(scan));
  }
}

TEST(LocalMap, InterpolatedFieldGradientMatchesFiniteDifferences) {
  const MapOptions o = SmallMap();
  LocalMap map(o);
  const std::vector<Eigen::Vector2d> hits = {{2.05, 0.05}, {2.05, 0.65}, {1.0, -1.0}};
  map.InsertScan({0.05, 0.05}, hits, {});
  const double h = 1e-6;
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(1.83, 0.27), Eigen::Vector2d(2.21, 0.41),
                                   Eigen::Vector2d(1.12, -0.77)}) {
    const LocalMap::FieldSample s = map.InterpolatedField(p);
    const double gx = (map.InterpolatedField(p + Eigen::Vector2d(h, 0.0)).distance_m -
                       map.InterpolatedField(p - Eigen::Vector2d(h, 0.0)).distance_m) / (2 * h);
    const double gy = (map.InterpolatedField(p + Eigen::Vector2d(0.0, h)).distance_m -
                       map.InterpolatedField(p - Eigen::Vector2d(0.0, h)).distance_m) / (2 * h);
    EXPECT_NEAR(s.gradient.x(), gx, 1e-5);
    EXPECT_NEAR(s.gradient.y(), gy, 1e-5);
  }
  // At a cell centre the interpolation is the cell's value.
  const CellIndex c = map.CellOf({1.83, 0.27});
  EXPECT_NEAR(map.InterpolatedField(map.CellCentre(c)).distance_m,
              static_cast<double>(map.FieldDistance(c)), 1e-6);
}

TEST(LocalMap, MovingWindowForgetsWhatLeavesAndKeepsTheFieldExact) {
  const MapOptions o = SmallMap();  // 12.8 m window, recentred beyond 3.2 m
  LocalMap map(o);
  const std::vector<Eigen::Vector2d> west = {{-5.0, 0.3}, {-5.0, 0.6}, {-4.0, -2.0}};
  map.InsertScan({-3.0, 0.0}, west, {});
  const std::vector<Eigen::Vector2d> east = {{2.0, 1.0}, {2.5, -1.0}};
  map.InsertScan({0.0, 0.0}, east, {});
  ASSERT_TRUE(map.Occupied(map.CellOf({-5.0, 0.3})));
  EXPECT_FALSE(map.RecentreOn({3.0, 0.0}));  // within the share: no move
  EXPECT_TRUE(map.RecentreOn({6.0, 0.0}));   // beyond it
  EXPECT_FALSE(map.InWindow(map.CellOf({-5.0, 0.3})));
  EXPECT_FALSE(map.Occupied(map.CellOf({-5.0, 0.3})));
  EXPECT_TRUE(map.Occupied(map.CellOf({2.0, 1.0})));
  ExpectFieldExact(map, "after recentring");
  // What enters is unknown, even in slots that held the forgotten cells.
  const CellIndex entering = map.CellOf({-5.0 + 12.8, 0.3});
  EXPECT_TRUE(map.InWindow(entering));
  EXPECT_FLOAT_EQ(map.LogOdds(entering), 0.0f);
  const MapRaster raster = map.Raster();
  EXPECT_GT(raster.geometry.width, 0);
  EXPECT_EQ(raster.log_odds.size(), static_cast<std::size_t>(raster.geometry.CellCount()));
}

// RecentreOn visits only the strips that enter and the kept cells near the kept region's
// border: checked against the brute-force field over moves along both axes, both signs, and
// a jump of more than a window (everything forgotten).
TEST(LocalMap, RecentringAlongEveryAxisKeepsTheFieldExact) {
  const MapOptions o = SmallMap();  // 12.8 m window, recentred beyond 3.2 m
  LocalMap map(o);
  const std::uint64_t seed = 777;
  Rng rng(seed);
  const std::vector<Eigen::Vector2d> path = {{0.0, 0.0},  {4.0, 0.5},   {4.5, 5.0},
                                             {-1.0, 2.0}, {-1.5, -3.0}, {30.0, -30.0}};
  int moves = 0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    if (map.RecentreOn(path[k])) ++moves;
    const std::string context = "seed 777 stop " + std::to_string(k);
    ExpectFieldExact(map, context + " after recentring");
    for (int scan = 0; scan < 5; ++scan) {
      std::vector<Eigen::Vector2d> hits;
      for (int i = 0; i < 40; ++i) {
        const double a = rng.Uniform(-kPi, kPi);
        const double r = rng.Uniform(0.5, 5.0);
        hits.emplace_back(path[k] + r * Eigen::Vector2d(std::cos(a), std::sin(a)));
      }
      map.InsertScan(path[k], hits, {});
    }
    ExpectFieldExact(map, context + " after mapping");
  }
  EXPECT_EQ(moves, 5);
  // After the jump nothing of the earlier stops is left.
  EXPECT_FLOAT_EQ(map.LogOdds(map.CellOf({30.0 - 5.5, -30.0})), 0.0f);
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(4.0, 0.5), Eigen::Vector2d(-1.5, -3.0)}) {
    EXPECT_FALSE(map.InWindow(map.CellOf(p)));
  }
}

}  // namespace
}  // namespace lookout::lidar
