#include "lookout/grid/cluster_motion.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "lookout/core/input_error.h"
#include "lookout/core/messages.h"
#include "lookout/grid/extended_grid.h"
#include "lookout/grid/filter_state.h"

namespace lookout::grid {
namespace {

constexpr double kClusterCellM = 0.15;
constexpr double kClusterDtS = 0.08;
constexpr TimeNs kClusterDtNs = 80'000'000;

// Hit maps of `width` x `height` cells with the previous scan's hits `before` (this scan's are
// not read by the measurement: it takes them as its argument).
HitMaps HitsBefore(int width, int height, const std::vector<CellIndex>& before) {
  HitMaps m;
  m.Reset(width, height);
  for (const CellIndex& c : before) m.AddBefore(c.ix, c.iy);
  return m;
}

std::vector<CellIndex> ShiftedCells(const std::vector<CellIndex>& cells, int dx, int dy) {
  std::vector<CellIndex> out;
  for (const CellIndex& c : cells) out.push_back({c.ix + dx, c.iy + dy});
  return out;
}

// A car's side (12 cells along x) and front (6 cells along y) as the lidar sees them: an L.
std::vector<CellIndex> CarOutlineCells() {
  std::vector<CellIndex> l;
  for (int x = 20; x < 32; ++x) l.push_back({x, 20});
  for (int y = 21; y < 27; ++y) l.push_back({20, y});
  return l;
}

// The scores against their definition, every offset of every search: random previous hits on a
// small map, and hits now anywhere near it, so that many offsets take a hit off the map (where
// only a previous hit next to it scores).
TEST(MeasureClusterMotionTest, ScoresAreTheDefinition) {
  const std::uint64_t seed = 7301;
  std::mt19937_64 rng(seed);
  for (int trial = 0; trial < 200; ++trial) {
    std::uniform_int_distribution<int> width(1, 30), height(1, 30);
    HitMaps maps;
    maps.Reset(width(rng), height(rng));
    std::uniform_int_distribution<int> x(-1, maps.width), y(-1, maps.height);
    for (int k = static_cast<int>(rng() % 40); k > 0; --k) maps.AddBefore(x(rng), y(rng));
    std::uniform_int_distribution<int> hx(-8, maps.width + 8), hy(-8, maps.height + 8);
    std::vector<CellIndex> hits;
    for (int k = 1 + static_cast<int>(rng() % 12); k > 0; --k) hits.push_back({hx(rng), hy(rng)});
    const CellIndex predicted{static_cast<int>(rng() % 7) - 3, static_cast<int>(rng() % 7) - 3};
    const int half = 1 + static_cast<int>(rng() % 6);
    const std::vector<int> scores = ClusterMotionScores(maps, hits, predicted, half);
    const int side = 2 * half + 1;
    const auto before_at = [&](int cx, int cy) {
      return maps.Inside(cx, cy) && maps.before[maps.At(cx, cy)] != 0;
    };
    for (int oy = -half; oy <= half; ++oy) {
      for (int ox = -half; ox <= half; ++ox) {
        int expected = 0;
        for (const CellIndex& h : hits) {
          const int cx = h.ix - predicted.ix - ox, cy = h.iy - predicted.iy - oy;
          bool next_to = false;
          for (int ny = cy - 1; ny <= cy + 1; ++ny) {
            for (int nx = cx - 1; nx <= cx + 1; ++nx) next_to = next_to || before_at(nx, ny);
          }
          expected += before_at(cx, cy) ? 2 : (next_to ? 1 : 0);
        }
        ASSERT_EQ(scores[static_cast<std::size_t>((oy + half) * side + ox + half)], expected)
            << "seed " << seed << " trial " << trial << " offset " << ox << ", " << oy;
      }
    }
  }
}

TEST(MeasureClusterMotionTest, AnLMovedByWholeCellsIsMeasuredAtItsDisplacement) {
  const std::vector<CellIndex> before = CarOutlineCells();
  const HitMaps maps = HitsBefore(64, 64, before);
  const std::vector<CellIndex> now = ShiftedCells(before, 4, -3);
  // Predicted one cell off in each axis: the search finds the rest.
  const ClusterMotion m = MeasureClusterMotion(maps, now, {3, -2}, 3, {});
  ASSERT_TRUE(m.measured);
  EXPECT_EQ(m.hits, static_cast<int>(now.size()));
  EXPECT_DOUBLE_EQ(m.score, static_cast<double>(now.size()));
  // Whole-cell truth: the parabola through symmetric neighbours keeps the vertex at the peak.
  EXPECT_NEAR(m.dx_cells, 4.0, 0.15);
  EXPECT_NEAR(m.dy_cells, -3.0, 0.15);
}

TEST(MeasureClusterMotionTest, AStraightSideAloneIsAmbiguousAlongItself) {
  std::vector<CellIndex> side;
  for (int x = 5; x < 45; ++x) side.push_back({x, 20});
  const HitMaps maps = HitsBefore(64, 64, side);
  // Moved by 3 cells along itself: every shift along it explains nearly every hit.
  const ClusterMotion m = MeasureClusterMotion(maps, ShiftedCells(side, 3, 0), {2, 0}, 3, {});
  EXPECT_FALSE(m.measured);
  // Across itself it is no less a line: still not measured (the caller keeps eq. 14's velocity).
  const ClusterMotion across = MeasureClusterMotion(maps, ShiftedCells(side, 0, 2), {0, 2}, 3, {});
  EXPECT_FALSE(across.measured);
}

// A body seen whole (12 x 6 cells, a dense sensor's view of a car) moved 11 cells along x:
// its hits match themselves two and three cells off nearly as well as at its motion (the
// inside matches everywhere), so all its hits are ambiguous; its outlines, on which the clusters'
// stage measures a body (scan_flow.h), are measured at the motion.
TEST(MeasureClusterMotionTest, ASolidBodyIsMeasuredByItsOutline) {
  std::vector<CellIndex> solid, outline;
  for (int y = 20; y < 26; ++y) {
    for (int x = 10; x < 22; ++x) {
      solid.push_back({x, y});
      if (x == 10 || x == 21 || y == 20 || y == 25) outline.push_back({x, y});
    }
  }
  const ClusterMotion whole =
      MeasureClusterMotion(HitsBefore(64, 64, solid), ShiftedCells(solid, 11, 0), {10, 0}, 3, {});
  EXPECT_FALSE(whole.measured);
  const ClusterMotion m = MeasureClusterMotion(HitsBefore(64, 64, outline),
                                               ShiftedCells(outline, 11, 0), {10, 0}, 3, {});
  ASSERT_TRUE(m.measured);
  EXPECT_DOUBLE_EQ(m.dx_cells, 11.0);
  EXPECT_DOUBLE_EQ(m.dy_cells, 0.0);
}

// The outline of the box of cells [x0, x0 + 12) x [20, 26), a body seen whole.
std::vector<CellIndex> BoxOutline(int x0) {
  std::vector<CellIndex> cells;
  for (int y = 20; y < 26; ++y) {
    for (int x = x0; x < x0 + 12; ++x) {
      if (x == x0 || x == x0 + 11 || y == 20 || y == 25) cells.push_back({x, y});
    }
  }
  return cells;
}

// The box above moved 11 cells, its outline now without its rear side (the cells it shares with
// the scan before, which its cluster did not hold): two rows and a front, which match
// themselves moved two cells further 88 % as well. Where the box left free space behind it, a
// longer displacement is no rival and the box is measured at its motion.
TEST(MeasureClusterMotionTest, ABodyThatLeftFreeSpaceHasNoLongerRivals) {
  std::vector<CellIndex> before_solid;
  for (int y = 20; y < 26; ++y) {
    for (int x = 10; x < 22; ++x) before_solid.push_back({x, y});
  }
  std::vector<CellIndex> now;
  for (const CellIndex& c : BoxOutline(21)) {
    if (c.ix != 21) now.push_back(c);
  }
  HitMaps outlines = HitsBefore(64, 64, BoxOutline(10));
  EXPECT_FALSE(MeasureClusterMotion(outlines, now, {10, 0}, 3, {}).measured);
  const ClusterMotion m = MeasureClusterMotion(outlines, now, {10, 0}, 3, {}, true);
  ASSERT_TRUE(m.measured);
  EXPECT_NEAR(m.dx_cells, 11.0, 0.5);
  EXPECT_DOUBLE_EQ(m.dy_cells, 0.0);
  // The same hits where the box stood, predicted 2 cells on: staying is the best and keeps its
  // longer rivals (two cells on matches 85 % as well).
  std::vector<CellIndex> stayed;
  for (const CellIndex& c : BoxOutline(10)) {
    if (c.ix != 10) stayed.push_back(c);
  }
  EXPECT_FALSE(MeasureClusterMotion(outlines, stayed, {2, 0}, 3, {}, true).measured);

  // The free space: the scan before's hits (the whole box) seen free where the box left them.
  HitMaps pair = HitsBefore(64, 64, before_solid);
  for (const CellIndex& c : before_solid) {
    if (c.ix < 21) pair.AddFreeNow(c.ix, c.iy);
  }
  // Where it was (its box now moved back 10 cells, a cell wider): 66 hits before, 60 seen free.
  EXPECT_TRUE(LeftFreeSpace(pair, now, {10, 0}, 0.25));
  EXPECT_TRUE(LeftFreeSpace(pair, now, {10, 0}, 59.5 / 66.0));
  EXPECT_FALSE(LeftFreeSpace(pair, now, {10, 0}, 60.5 / 66.0));
  // A wall hit where it stood: nothing seen free.
  EXPECT_FALSE(LeftFreeSpace(HitsBefore(64, 64, before_solid), BoxOutline(10), {0, 0}, 0.25));
  EXPECT_FALSE(LeftFreeSpace(HitMaps{}, now, {10, 0}, 0.25));
}

TEST(MeasureClusterMotionTest, TooFewHitsOrNoMatchAreNotMeasured) {
  const std::vector<CellIndex> before = CarOutlineCells();
  const HitMaps maps = HitsBefore(64, 64, before);
  const std::vector<CellIndex> three(before.begin(), before.begin() + 3);
  EXPECT_FALSE(MeasureClusterMotion(maps, ShiftedCells(three, 1, 0), {1, 0}, 3, {}).measured);
  // HitsMeasurement far from anything the previous scan saw (beyond the search): no displacement
  // explains them.
  EXPECT_FALSE(MeasureClusterMotion(maps, ShiftedCells(before, 20, 20), {0, 0}, 3, {}).measured);
}

// The cells a dense outline of a disc's near half falls in, the disc's centre at (cx, cy) cells.
std::vector<CellIndex> DiscArcCells(double cx, double cy, double radius) {
  std::vector<CellIndex> cells;
  for (int k = 0; k <= 60; ++k) {
    const double a = M_PI / 2.0 + M_PI * k / 60.0;  // the half facing -x
    const CellIndex c{static_cast<int>(std::floor(cx + radius * std::cos(a))),
                      static_cast<int>(std::floor(cy + radius * std::sin(a)))};
    if (cells.empty() || cells.back().ix != c.ix || cells.back().iy != c.iy) cells.push_back(c);
  }
  return cells;
}

// A walker's arc moved by 2.5 cells: whole-cell matching alone says 2 or 3 (0.5 cell off); the
// parabola through the scores finds the half cell.
TEST(MeasureClusterMotionTest, SubCellDisplacementFromTheScoresParabola) {
  const HitMaps maps = HitsBefore(64, 64, DiscArcCells(20.3, 20.3, 2.4));
  const std::vector<CellIndex> now = DiscArcCells(22.8, 20.3, 2.4);
  const ClusterMotion m = MeasureClusterMotion(maps, now, {2, 0}, 3, {});
  ASSERT_TRUE(m.measured);
  std::printf("arc moved 2.5 cells: measured (%.3f, %.3f)\n", m.dx_cells, m.dy_cells);
  EXPECT_NEAR(m.dx_cells, 2.5, 0.25);
  EXPECT_NEAR(m.dy_cells, 0.0, 0.25);
}

TEST(ClusterMotionOptionsTest, ValidateNamesTheField) {
  ClusterMotionOptions o;
  EXPECT_NO_THROW(o.Validate());
  o.blend = 1.5;
  try {
    o.Validate("test");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("grid.filter.cluster_motion.blend"), std::string::npos)
        << e.what();
  }
  o = {};
  o.min_link = 1.0;
  EXPECT_THROW(o.Validate(), InputError);
  o = {};
  o.side_max_cells = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(o.Validate(), InputError);
  o = {};
  o.side_min_disagreement = -0.1;
  EXPECT_THROW(o.Validate(), InputError);
}

// --- the stage on a grid

// A filter state by hand: a moving block of cells (a body) whose velocity lags the truth, and a
// wall beside it that rigidity links joined to it and that carries the body's wrong velocity
// (as a wall does beside a walker in the crowd scenario).
struct HandMadeFilterState {
  GridLayers layers{ScrollingGridGeometry(kClusterCellM, 48, 48, CellIndex{0, 0})};
  FilterLayerIds ids = AddFilterLayers(layers);

  void Set(int x, int y, float occupancy, float vx, float confidence) {
    const std::size_t s = layers.geometry().StorageIndexOfLocal({x, y});
    layers.Values(ids.occupancy)[s] = occupancy;
    layers.Values(ids.velocity_x_mps)[s] = vx;
    layers.Values(ids.velocity_y_mps)[s] = 0.0f;
    layers.Values(ids.velocity_confidence)[s] = confidence;
    for (const LayerId d : ids.rigidity) layers.Values(d)[s] = 0.3f;
  }
  float Vx(int x, int y) const {
    return layers.Values(ids.velocity_x_mps)[layers.geometry().StorageIndexOfLocal({x, y})];
  }
  float Vy(int x, int y) const {
    return layers.Values(ids.velocity_y_mps)[layers.geometry().StorageIndexOfLocal({x, y})];
  }
  float Confidence(int x, int y) const {
    return layers.Values(ids.velocity_confidence)[layers.geometry().StorageIndexOfLocal({x, y})];
  }
};

MeasurementGrid HitsMeasurement(const ScrollingGridGeometry& g, const std::vector<CellIndex>& hits,
                                TimeNs stamp) {
  MeasurementGrid z;
  z.geometry = g;
  z.stamp = stamp;
  z.p_occupied.assign(g.CellCount(), 0.3f);
  for (const CellIndex& c : hits) z.p_occupied[g.StorageIndexOfLocal(c)] = 0.7f;
  for (std::size_t i = 0; i < z.p_occupied.size(); ++i) z.touched.push_back(i);
  return z;
}

// The scan pair of two scans a cycle apart, hitting `before` then `now`; `z` is the second.
struct TwoScans {
  ScanFlow flow;
  MeasurementGrid z;
  TwoScans(const ScrollingGridGeometry& g, const std::vector<CellIndex>& before,
           const std::vector<CellIndex>& now) {
    flow.Prepare(HitsMeasurement(g, before, kClusterDtNs));
    flow.Remember(HitsMeasurement(g, before, kClusterDtNs));
    z = HitsMeasurement(g, now, 2 * kClusterDtNs);
    flow.Prepare(z);
  }
};

// Long_lag_scans + 1 scans a cycle apart into `flow`, scan k hitting hits_at(k); returns the
// last one's measurement, `flow` prepared for it (the long pair its first scan).
template <typename HitsAt>
MeasurementGrid FeedScans(const ScrollingGridGeometry& g, ScanFlow& flow, const HitsAt& hits_at) {
  const int lag = ScanFlowOptions{}.long_lag_scans;
  for (int k = 0; k < lag; ++k) {
    const MeasurementGrid older = HitsMeasurement(g, hits_at(k), (k + 1) * kClusterDtNs);
    flow.Prepare(older);
    flow.Remember(older);
  }
  MeasurementGrid z = HitsMeasurement(g, hits_at(lag), (lag + 1) * kClusterDtNs);
  flow.Prepare(z);
  return z;
}

TEST(ApplyClusterMotionTest, TheBodyTakesItsMeasuredVelocityTheWallBesideItKeepsItsOwn) {
  HandMadeFilterState state;
  // The body: a 3 x 3 block at x 20-22, y 20-22, truly moving 2 cells a cycle along x
  // (3.75 m/s), believed at 1 m/s. The wall: y 18, x 18-23, static, believed at 1 m/s too.
  std::vector<CellIndex> body_now, wall;
  for (int y = 20; y <= 22; ++y) {
    for (int x = 20; x <= 22; ++x) {
      state.Set(x, y, 0.9f, 1.0f, 0.6f);
      body_now.push_back({x, y});
    }
  }
  for (int x = 18; x <= 23; ++x) {
    state.Set(x, 18, 0.9f, 1.0f, 0.6f);
    // The wall has been hit where it stands for two seconds; the body is new.
    state.layers.Values(state.ids.hit_scans)[state.layers.geometry().StorageIndexOfLocal({x, 18})] =
        25.0f;
    wall.push_back({x, 18});
  }
  // Between the two, a cell linking them (rigidity joins the wall to the body).
  state.Set(21, 19, 0.9f, 1.0f, 0.6f);
  const CellIndex arriving{23, 21};  // hit now, not before: the body's front arriving
  const ScrollingGridGeometry& g = state.layers.geometry();
  std::vector<CellIndex> before = ShiftedCells(body_now, -2, 0);
  before.insert(before.end(), wall.begin(), wall.end());
  std::vector<CellIndex> now = body_now;
  now.insert(now.end(), wall.begin(), wall.end());
  now.push_back(arriving);
  const TwoScans scans(g, before, now);
  const ScanFlow& flow = scans.flow;
  const MeasurementGrid& z = scans.z;
  const HandMadeFilterState initial = state;
  ApplyClusterMotion(state.layers, state.ids, z, flow, kClusterDtS, 0.25, {});

  // The body: half way from 1 m/s to what the pair measured (3.75 m/s, the wall's hits in the
  // body's score pulling it towards staying), its trailing column too: the previous scan hit
  // it (the block overlaps itself), but it is no wall, hit there for a second.
  for (const CellIndex& c : body_now) {
    EXPECT_GT(state.Vx(c.ix, c.iy), 2.0f) << c.ix << "," << c.iy;
    EXPECT_LT(state.Vx(c.ix, c.iy), 2.4f) << c.ix << "," << c.iy;
  }
  // The wall: hit before and now while the body moved two cells, and for two seconds: staying
  // explains it.
  for (const CellIndex& c : wall) EXPECT_EQ(state.Vx(c.ix, c.iy), 1.0f) << c.ix;
  // Without the count (every cell the two scans hit left out, as before): the trailing column
  // keeps its own velocity too.
  HandMadeFilterState uncounted = initial;
  ClusterMotionOptions all_staying;
  all_staying.staying_min_hit_scans = 0;
  ApplyClusterMotion(uncounted.layers, uncounted.ids, z, flow, kClusterDtS, 0.25, all_staying);
  for (int y = 20; y <= 22; ++y) EXPECT_EQ(uncounted.Vx(20, y), 1.0f) << y;
  EXPECT_GT(uncounted.Vx(21, 21), 2.0f);
  // The arriving front: the body's velocity and a tracked cell's confidence.
  EXPECT_GT(state.Vx(arriving.ix, arriving.iy), 3.0f);
  EXPECT_FLOAT_EQ(state.Confidence(arriving.ix, arriving.iy), 0.25f);

  // Off: nothing changes.
  HandMadeFilterState off;
  off.Set(21, 21, 0.9f, 1.0f, 0.6f);
  ClusterMotionOptions disabled;
  disabled.enabled = false;
  ApplyClusterMotion(off.layers, off.ids, z, flow, kClusterDtS, 0.25, disabled);
  EXPECT_EQ(off.Vx(21, 21), 1.0f);
}

// A car's side, 22 cells along x with its 12-cell front face at x = 9, moving 2 cells a cycle
// towards -x (3.75 m/s), believed at 1 m/s: each side cell stays under the sliding side for 11
// scans and more, and has been hit 13 in a row, more than staying_min_hit_scans (12); a wall
// cell beside it, linked to it, 40. The side is no wall: hit for no longer than the car takes to
// pass (its 23 cells along x over 2 a cycle, two scans spare); the wall is.
TEST(ApplyClusterMotionTest, AFastCarsSideHitLongerThanTheCountIsNoWall) {
  HandMadeFilterState state;
  const ScrollingGridGeometry& g = state.layers.geometry();
  const auto hit_scans = [&](const CellIndex& c) -> float& {
    return state.layers.Values(state.ids.hit_scans)[g.StorageIndexOfLocal(c)];
  };
  std::vector<CellIndex> car_now;
  for (int x = 10; x < 32; ++x) car_now.push_back({x, 20});
  for (int y = 21; y <= 31; ++y) car_now.push_back({9, y});
  for (const CellIndex& c : car_now) {
    state.Set(c.ix, c.iy, 0.9f, -1.0f, 0.6f);
    hit_scans(c) = c.ix >= 12 && c.iy == 20 ? 13.0f : 1.0f;  // the side's first cells are new
  }
  const CellIndex wall{32, 20};
  state.Set(wall.ix, wall.iy, 0.9f, -1.0f, 0.6f);
  hit_scans(wall) = 40.0f;
  std::vector<CellIndex> before = ShiftedCells(car_now, 2, 0), now = car_now;
  for (std::vector<CellIndex>* scan : {&before, &now}) scan->push_back(wall);  // hit in both
  const TwoScans scans(g, before, now);
  const HandMadeFilterState initial = state;
  ApplyClusterMotion(state.layers, state.ids, scans.z, scans.flow, kClusterDtS, 0.25, {});
  // Half way from -1 m/s to the measured -3.75 (the wall's hit pulls the score to staying a
  // little), the side's old cells as its new ones.
  for (const CellIndex& c : car_now) {
    EXPECT_LT(state.Vx(c.ix, c.iy), -2.0f) << c.ix << "," << c.iy;
  }
  EXPECT_EQ(state.Vx(wall.ix, wall.iy), -1.0f);
  // Hit for longer than the car takes to pass, the same cells are a wall's.
  HandMadeFilterState long_hit = initial;
  for (int x = 12; x < 32; ++x) {
    long_hit.layers.Values(long_hit.ids.hit_scans)[g.StorageIndexOfLocal({x, 20})] = 40.0f;
  }
  ApplyClusterMotion(long_hit.layers, long_hit.ids, scans.z, scans.flow, kClusterDtS, 0.25, {});
  for (int x = 12; x < 32; ++x) EXPECT_EQ(long_hit.Vx(x, 20), -1.0f) << x;
}

// A slow car (1.5 cells a cycle towards -x, 2.8 m/s) seen from the side: its front face, a
// column of 12 cells, and a side of 21 cells along y = 20, hit in every scan. The cluster holds
// the face and the side's first 8 cells, tracked at -2.8 m/s; the side's rear 13 cells read
// -0.5 m/s with a confidence under the clusters' (the aperture problem: a side slides along
// itself) and have been hit for 3 scans. The long pair (six scans) measures the body 9 cells on.
struct SlowCarScene {
  HandMadeFilterState state;
  ScanFlow flow;
  MeasurementGrid z;
  std::vector<CellIndex> trailing;

  static int FaceX(int k) { return 19 - static_cast<int>(std::lround(1.5 * k)); }
  static std::vector<CellIndex> CarAt(int face_x) {
    std::vector<CellIndex> hits;
    for (int y = 21; y <= 32; ++y) hits.push_back({face_x, y});
    for (int x = face_x + 1; x <= face_x + 21; ++x) hits.push_back({x, 20});
    return hits;
  }

  explicit SlowCarScene(float trailing_hit_scans = 3.0f, float trailing_vx = -0.5f) {
    const ScrollingGridGeometry& g = state.layers.geometry();
    z = FeedScans(g, flow, [](int k) { return CarAt(FaceX(k)); });
    const int face = FaceX(ScanFlowOptions{}.long_lag_scans);
    for (const CellIndex& c : CarAt(face)) {
      if (c.iy == 20 && c.ix > face + 8) {
        state.Set(c.ix, c.iy, 0.9f, trailing_vx, 0.1f);
        state.layers.Values(state.ids.hit_scans)[g.StorageIndexOfLocal(c)] = trailing_hit_scans;
        trailing.push_back(c);
      } else {
        state.Set(c.ix, c.iy, 0.9f, -2.8f, 0.6f);
      }
    }
  }
};

TEST(ApplyClusterMotionTest, ASlowCarsTrailingSideTakesTheBodysVelocity) {
  SlowCarScene car;
  ASSERT_NE(car.flow.long_pair(), nullptr);
  ApplyClusterMotion(car.state.layers, car.state.ids, car.z, car.flow, kClusterDtS, 0.25, {});
  // Half way from -0.5 m/s to the body's -2.8, and a tracked cell's confidence: the next cycle's
  // cluster holds them.
  ASSERT_EQ(car.trailing.size(), 13u);
  for (const CellIndex& c : car.trailing) {
    EXPECT_NEAR(car.state.Vx(c.ix, c.iy), -1.65f, 0.15f) << c.ix;
    EXPECT_FLOAT_EQ(car.state.Confidence(c.ix, c.iy), 0.25f) << c.ix;
  }
  // Without the rule the side keeps its reading.
  SlowCarScene off;
  ClusterMotionOptions no_sides;
  no_sides.sides = false;
  ApplyClusterMotion(off.state.layers, off.state.ids, off.z, off.flow, kClusterDtS, 0.25, no_sides);
  for (const CellIndex& c : off.trailing) EXPECT_EQ(off.state.Vx(c.ix, c.iy), -0.5f) << c.ix;
  // Hit where they are for longer than the car takes to pass: a wall's cells, left alone.
  SlowCarScene wall(/*trailing_hit_scans=*/40.0f);
  ApplyClusterMotion(wall.state.layers, wall.state.ids, wall.z, wall.flow, kClusterDtS, 0.25, {});
  for (const CellIndex& c : wall.trailing) EXPECT_EQ(wall.state.Vx(c.ix, c.iy), -0.5f) << c.ix;
  // Reading the body's motion within side_min_disagreement of its speed: their own kept.
  SlowCarScene agreeing(3.0f, /*trailing_vx=*/-2.5f);
  ApplyClusterMotion(agreeing.state.layers, agreeing.state.ids, agreeing.z, agreeing.flow,
                     kClusterDtS, 0.25, {});
  for (const CellIndex& c : agreeing.trailing) {
    EXPECT_EQ(agreeing.state.Vx(c.ix, c.iy), -2.5f) << c.ix;
  }
}

TEST(CountHitScansTest, HitsCountUpFreeResetsUnobservedKeeps) {
  const ScrollingGridGeometry g(kClusterCellM, 4, 1, CellIndex{0, 0});
  std::vector<float> count(g.CellCount(), 0.0f);
  MeasurementGrid z;
  z.geometry = g;
  // Cells 0-3: hit, hit, free, unobserved; three scans, then cell 1 seen free.
  z.p_occupied = {0.7f, 0.7f, 0.3f, 0.5f};
  z.touched = {1, 2, 0};  // the rays' order, not storage order
  count[2] = 5.0f;
  count[3] = 7.0f;
  for (int k = 0; k < 3; ++k) {
    // The hits come back in z.touched's order.
    EXPECT_EQ(CountHitScans(z, count), (std::vector<std::size_t>{1, 0}));
  }
  EXPECT_EQ(count, (std::vector<float>{3.0f, 3.0f, 0.0f, 7.0f}));
  z.p_occupied[1] = 0.3f;
  EXPECT_EQ(CountHitScans(z, count), (std::vector<std::size_t>{0}));
  EXPECT_EQ(count, (std::vector<float>{4.0f, 0.0f, 0.0f, 7.0f}));
}

// A walker's arc crossing the beams at 0.6 cell a cycle (1.1 m/s), believed still with a
// trusted confidence (the one-cycle pair called it staying), and a pole four cells away, still
// and hit at the same cells every scan. The long pair (six scans) sees the arc 3.6 cells
// further on.
struct HeldStillScene {
  HandMadeFilterState state;
  ScanFlow flow;
  MeasurementGrid z;
  std::vector<CellIndex> arc_now, pole;

  static std::vector<CellIndex> ArcAt(double y_cells) { return DiscArcCells(20.3, y_cells, 1.7); }

  // `free_elsewhere`: the scans see free space wherever they do not hit (false: unknown).
  // `arc_occupancy`: what the grid believes of the arc's cells now; `hide_older`: the last scan
  // does not see where the arc was before (an occluder's shadow came over it).
  explicit HeldStillScene(bool free_elsewhere, float arc_occupancy = 0.9f,
                          bool hide_older = false) {
    for (int y = 30; y <= 31; ++y) {
      for (int x = 26; x <= 27; ++x) pole.push_back({x, y});
    }
    const ScrollingGridGeometry& g = state.layers.geometry();
    const auto scan = [&](double y_cells, TimeNs stamp) {
      std::vector<CellIndex> hits = ArcAt(y_cells);
      hits.insert(hits.end(), pole.begin(), pole.end());
      MeasurementGrid m = HitsMeasurement(g, hits, stamp);
      if (!free_elsewhere) {
        for (float& p : m.p_occupied) {
          if (p < 0.5f) p = 0.5f;
        }
      }
      return m;
    };
    const int lag = ScanFlowOptions{}.long_lag_scans;
    for (int k = 0; k < lag; ++k) {
      const MeasurementGrid older = scan(20.3 + 0.6 * k, (k + 1) * kClusterDtNs);
      flow.Prepare(older);
      flow.Remember(older);
    }
    z = scan(20.3 + 0.6 * lag, (lag + 1) * kClusterDtNs);
    arc_now = ArcAt(20.3 + 0.6 * lag);
    if (hide_older) {
      for (int k = 0; k < lag; ++k) {
        for (const CellIndex& c : ArcAt(20.3 + 0.6 * k)) {
          float& p = z.p_occupied[g.StorageIndexOfLocal(c)];
          if (p < 0.5f) p = 0.5f;
        }
      }
    }
    flow.Prepare(z);
    for (const CellIndex& c : arc_now) state.Set(c.ix, c.iy, arc_occupancy, 0.0f, 0.9f);
    for (const CellIndex& c : pole) state.Set(c.ix, c.iy, 0.9f, 0.0f, 0.9f);
  }
  float Vy(int x, int y) const {
    const GridLayers& l = state.layers;
    return l.Values(state.ids.velocity_y_mps)[l.geometry().StorageIndexOfLocal({x, y})];
  }
  float Occupancy(const CellIndex& c) const {
    const GridLayers& l = state.layers;
    return l.Values(state.ids.occupancy)[l.geometry().StorageIndexOfLocal(c)];
  }
  float Seen(const CellIndex& c) const {
    const GridLayers& l = state.layers;
    return l.Values(state.ids.seen)[l.geometry().StorageIndexOfLocal(c)];
  }
};

TEST(ApplyClusterMotionTest, AWalkerHeldStillIsMovedAtWhatTheLongBaselineSaw) {
  HeldStillScene scene(/*free_elsewhere=*/true);
  ASSERT_NE(scene.flow.long_pair(), nullptr);
  ApplyClusterMotion(scene.state.layers, scene.state.ids, scene.z, scene.flow, kClusterDtS, 0.25,
                     {});
  // 0.6 cell a cycle is 1.125 m/s; the whole-cell match over six scans finds 3 or 4 cells, the
  // parabola a fraction between.
  for (const CellIndex& c : scene.arc_now) {
    EXPECT_NEAR(scene.Vy(c.ix, c.iy), 1.125f, 0.2f) << c.ix << "," << c.iy;
    EXPECT_FLOAT_EQ(scene.state.Confidence(c.ix, c.iy), 0.25f);
  }
  // The pole stayed where it was: still.
  for (const CellIndex& c : scene.pole) {
    EXPECT_EQ(scene.Vy(c.ix, c.iy), 0.0f);
    EXPECT_FLOAT_EQ(scene.state.Confidence(c.ix, c.iy), 0.9f);
  }
  // Off: the walker stays held still.
  HeldStillScene off(/*free_elsewhere=*/true);
  ClusterMotionOptions no_still;
  no_still.still_bodies = false;
  ApplyClusterMotion(off.state.layers, off.state.ids, off.z, off.flow, kClusterDtS, 0.25, no_still);
  for (const CellIndex& c : off.arc_now) EXPECT_EQ(off.Vy(c.ix, c.iy), 0.0f);
}

// A body the grid believes faster than the long baseline measures it (a fast car's piece,
// under the dynamic clusters' confidence floor, that the long pair aliases to a slow
// displacement) is not held still: it keeps its own velocity.
TEST(ApplyClusterMotionTest, ABodyBelievedFasterThanMeasuredIsLeftAlone) {
  HeldStillScene scene(/*free_elsewhere=*/true);
  const GridLayers& l = scene.state.layers;
  for (const CellIndex& c : scene.arc_now) {
    const std::size_t s = l.geometry().StorageIndexOfLocal(c);
    scene.state.layers.Values(scene.state.ids.velocity_y_mps)[s] = 3.0f;
    scene.state.layers.Values(scene.state.ids.velocity_confidence)[s] = 0.2f;
  }
  ApplyClusterMotion(scene.state.layers, scene.state.ids, scene.z, scene.flow, kClusterDtS, 0.25,
                     {});
  for (const CellIndex& c : scene.arc_now) {
    EXPECT_EQ(scene.Vy(c.ix, c.iy), 3.0f);
    EXPECT_FLOAT_EQ(scene.state.Confidence(c.ix, c.iy), 0.2f);
  }
}

// The same hits without free space between them (a pattern of hits sliding along a wall as
// the ego drives: nothing is seen through where they were): not moved.
TEST(ApplyClusterMotionTest, HitsThatLeaveNothingSeenFreeAreNotMoved) {
  HeldStillScene scene(/*free_elsewhere=*/false);
  ApplyClusterMotion(scene.state.layers, scene.state.ids, scene.z, scene.flow, kClusterDtS, 0.25,
                     {});
  for (const CellIndex& c : scene.arc_now) EXPECT_EQ(scene.Vy(c.ix, c.iy), 0.0f);
}

// A far walker walking into space the grid saw free: its hits take a cell believed free (0.02)
// only to 0.045, so it never holds occupancy and no body above min_occupancy holds it. With
// births, the body of its hits is measured all the same, moved, and its hits take what a hit
// gives to unknown space.
TEST(ApplyClusterMotionTest, AWalkerInSpaceSeenFreeIsMovedAndBorn) {
  for (const bool births : {true, false}) {
    SCOPED_TRACE(births ? "births" : "no births");
    HeldStillScene scene(/*free_elsewhere=*/true, /*arc_occupancy=*/0.045f);
    ClusterMotionOptions options;
    options.births = births;
    ApplyClusterMotion(scene.state.layers, scene.state.ids, scene.z, scene.flow, kClusterDtS, 0.25,
                       options);
    for (const CellIndex& c : scene.arc_now) {
      if (births) {
        EXPECT_NEAR(scene.Vy(c.ix, c.iy), 1.125f, 0.2f) << c.ix << "," << c.iy;
        EXPECT_FLOAT_EQ(scene.Occupancy(c), 0.7f);  // the scan's p_hit
        EXPECT_FLOAT_EQ(scene.Seen(c), 1.0f);
      } else {
        EXPECT_EQ(scene.Vy(c.ix, c.iy), 0.0f);
        EXPECT_FLOAT_EQ(scene.Occupancy(c), 0.045f);
      }
    }
    // The pole, believed occupied and hit where it stands: neither moved nor changed.
    for (const CellIndex& c : scene.pole) {
      EXPECT_EQ(scene.Vy(c.ix, c.iy), 0.0f);
      EXPECT_FLOAT_EQ(scene.Occupancy(c), 0.9f);
    }
  }
}

// The same walker after a nearer one's shadow came over where it was: nothing there is seen
// vacated, but it arrived on cells the grid believed free, and is moved. Believed occupied
// there instead (hits sliding along a surface the grid holds), it is not.
TEST(ApplyClusterMotionTest, AWalkerWhoseOldPlaceIsHiddenIsMovedByWhereItArrived) {
  HeldStillScene arrived(/*free_elsewhere=*/true, /*arc_occupancy=*/0.045f, /*hide_older=*/true);
  ApplyClusterMotion(arrived.state.layers, arrived.state.ids, arrived.z, arrived.flow, kClusterDtS,
                     0.25, {});
  for (const CellIndex& c : arrived.arc_now) {
    EXPECT_NEAR(arrived.Vy(c.ix, c.iy), 1.125f, 0.2f) << c.ix << "," << c.iy;
  }
  HeldStillScene held(/*free_elsewhere=*/true, /*arc_occupancy=*/0.9f, /*hide_older=*/true);
  ApplyClusterMotion(held.state.layers, held.state.ids, held.z, held.flow, kClusterDtS, 0.25, {});
  for (const CellIndex& c : held.arc_now) EXPECT_EQ(held.Vy(c.ix, c.iy), 0.0f);
}

// A car's front face (six hits across x) and the first two cells of its side, seen for the
// first time on space seen free and believed still, the grid holding nothing of it (0.045 a
// cell: one hit on free space). Moving two cells a cycle (3.75 m/s) it is 12 cells further than
// the long pair's scan (six scans back), beyond that pair's +-6 search: the one-cycle pair
// measures it. `sliding`: instead a line of four hits moving two cells a cycle along itself, as
// a wall's hits slide along it while the ego drives (the crowd's walls did).
struct NewFaceScene {
  HandMadeFilterState state;
  ScanFlow flow;
  MeasurementGrid z;
  std::vector<CellIndex> hits_now;

  static std::vector<CellIndex> HitsAt(int step, bool sliding) {
    std::vector<CellIndex> hits;
    if (sliding) {
      for (int k = 0; k < 4; ++k) hits.push_back({20, 4 + 2 * step + k});
      return hits;
    }
    const int x = 40 - 2 * step;
    for (int k = 0; k < 6; ++k) hits.push_back({x, 20 + k});
    hits.push_back({x + 1, 20});
    hits.push_back({x + 2, 20});
    return hits;
  }
  explicit NewFaceScene(bool sliding) {
    z = FeedScans(state.layers.geometry(), flow, [&](int k) { return HitsAt(k, sliding); });
    hits_now = HitsAt(ScanFlowOptions{}.long_lag_scans, sliding);
    for (const CellIndex& c : hits_now) state.Set(c.ix, c.iy, 0.045f, 0.0f, 0.9f);
  }
  float Vy(const CellIndex& c) const { return state.Vy(c.ix, c.iy); }
};

TEST(ApplyClusterMotionTest, AFaceTooFastForTheLongPairIsMeasuredOverOneCycle) {
  NewFaceScene face(/*sliding=*/false);
  ASSERT_NE(face.flow.long_pair(), nullptr);
  ApplyClusterMotion(face.state.layers, face.state.ids, face.z, face.flow, kClusterDtS, 0.25, {});
  for (const CellIndex& c : face.hits_now) {
    EXPECT_NEAR(face.state.Vx(c.ix, c.iy), -3.75f, 0.2f) << c.ix << "," << c.iy;
    EXPECT_NEAR(face.Vy(c), 0.0f, 0.2f);
    EXPECT_FLOAT_EQ(face.state.Confidence(c.ix, c.iy), 0.25f);
  }
  // A line sliding along itself is measured at (0, 2) cells by its ends but not moved: a line's
  // motion along itself is not in the scan (the aperture problem).
  NewFaceScene sliding(/*sliding=*/true);
  ApplyClusterMotion(sliding.state.layers, sliding.state.ids, sliding.z, sliding.flow, kClusterDtS,
                     0.25, {});
  for (const CellIndex& c : sliding.hits_now) {
    EXPECT_EQ(sliding.state.Vx(c.ix, c.iy), 0.0f);
    EXPECT_EQ(sliding.Vy(c), 0.0f) << c.ix << "," << c.iy;
    EXPECT_FLOAT_EQ(sliding.state.Confidence(c.ix, c.iy), 0.9f);
  }
}

// A walker's body of five hits, believed at 1 m/s along x (0.53 cells a cycle: measured over
// the long pair, six scans). `older_shift`: where the long pair's older scan hit the same shape
// (the body moved by minus it over six scans).
struct SmallBodyScene {
  HandMadeFilterState state;
  ScanFlow flow;
  MeasurementGrid z;
  std::vector<CellIndex> body{{20, 20}, {21, 20}, {22, 20}, {20, 21}, {20, 22}};

  explicit SmallBodyScene(const CellIndex& older_shift) {
    // The older scans on the way from older_shift to here, the oldest at older_shift.
    const int lag = ScanFlowOptions{}.long_lag_scans;
    z = FeedScans(state.layers.geometry(), flow, [&](int k) {
      return ShiftedCells(body, older_shift.ix * (lag - k) / lag, older_shift.iy * (lag - k) / lag);
    });
    for (const CellIndex& c : body) state.Set(c.ix, c.iy, 0.9f, 1.0f, 0.6f);
  }
  float Vy(const CellIndex& c) const { return state.Vy(c.ix, c.iy); }
};

TEST(ApplyClusterMotionTest, ASmallBodysMeasurementFarFromItsPredictionIsNotTaken) {
  // Six cells along y over six scans (1.9 m/s across its believed motion: another walker's
  // older hits): not taken; taken with the gate off.
  SmallBodyScene jump(CellIndex{0, -6});
  ASSERT_NE(jump.flow.long_pair(), nullptr);
  ApplyClusterMotion(jump.state.layers, jump.state.ids, jump.z, jump.flow, kClusterDtS, 0.25, {});
  for (const CellIndex& c : jump.body) {
    EXPECT_EQ(jump.state.Vx(c.ix, c.iy), 1.0f) << c.ix << "," << c.iy;
    EXPECT_EQ(jump.Vy(c), 0.0f) << c.ix << "," << c.iy;
  }
  SmallBodyScene ungated(CellIndex{0, -6});
  ClusterMotionOptions no_gate;
  no_gate.small_body_max_hits = 0;
  ApplyClusterMotion(ungated.state.layers, ungated.state.ids, ungated.z, ungated.flow, kClusterDtS,
                     0.25, no_gate);
  for (const CellIndex& c : ungated.body) EXPECT_GT(ungated.Vy(c), 0.5f) << c.ix << "," << c.iy;
  // Three cells along x (0.94 m/s, its belief within 0.1 m/s): taken.
  SmallBodyScene walking(CellIndex{-3, 0});
  ApplyClusterMotion(walking.state.layers, walking.state.ids, walking.z, walking.flow, kClusterDtS,
                     0.25, {});
  for (const CellIndex& c : walking.body) {
    EXPECT_NEAR(walking.state.Vx(c.ix, c.iy), 0.97f, 0.05f) << c.ix << "," << c.iy;
  }
}

// A truck seen for the first time (intersafe-fig8's, 5.6 m/s towards -x): its face, 17 cells
// across, and 20 cells of its side, three cells further each cycle, on cells the grid believes
// free and still (occupancy 0.045: hit once); the long pair's older scan (18 cells back) lies
// beyond its search. The one-cycle pair measures the body whole: it moves and is born.
std::vector<CellIndex> TruckAt(int face_x) {
  std::vector<CellIndex> hits;
  for (int y = 20; y <= 36; ++y) hits.push_back({face_x, y});
  for (int x = face_x + 1; x <= face_x + 20; ++x) hits.push_back({x, 20});
  return hits;
}

TEST(ApplyClusterMotionTest, ATruckNewInViewIsMovedAndBornWhole) {
  for (const int max_extent : {80, 8}) {
    SCOPED_TRACE(max_extent);
    HandMadeFilterState state;
    const ScrollingGridGeometry& g = state.layers.geometry();
    ScanFlow flow;
    const auto face_x = [](int k) { return 44 - 3 * k; };
    const MeasurementGrid z = FeedScans(g, flow, [&](int k) { return TruckAt(face_x(k)); });
    const std::vector<CellIndex> now = TruckAt(face_x(ScanFlowOptions{}.long_lag_scans));
    for (const CellIndex& c : now) state.Set(c.ix, c.iy, 0.045f, 0.0f, 0.9f);
    ClusterMotionOptions options;
    options.new_body_max_extent_cells = max_extent;
    ApplyClusterMotion(state.layers, state.ids, z, flow, kClusterDtS, 0.25, options);
    for (const CellIndex& c : now) {
      const float occupancy = state.layers.Values(state.ids.occupancy)[g.StorageIndexOfLocal(c)];
      if (max_extent == 80) {
        EXPECT_NEAR(state.Vx(c.ix, c.iy), -5.625f, 0.2f) << c.ix << "," << c.iy;
        EXPECT_FLOAT_EQ(occupancy, 0.7f) << c.ix << "," << c.iy;
      } else {  // a walker's size at most: the truck is left as it was
        EXPECT_EQ(state.Vx(c.ix, c.iy), 0.0f) << c.ix << "," << c.iy;
        EXPECT_FLOAT_EQ(occupancy, 0.045f) << c.ix << "," << c.iy;
      }
    }
  }
}

// A body measured moving two cells a cycle: its front, hit for the first time on cells the grid
// saw free, is born with it; under birth_min_cells (a walker's pace), it is not.
TEST(ApplyClusterMotionTest, AFastBodysNewFaceIsBorn) {
  for (const double min_cells : {1.0, 3.0}) {
    SCOPED_TRACE(min_cells);
    HandMadeFilterState state;
    std::vector<CellIndex> body_now;
    for (int y = 20; y <= 22; ++y) {
      for (int x = 20; x <= 22; ++x) {
        state.Set(x, y, 0.9f, 3.75f, 0.6f);
        body_now.push_back({x, y});
      }
    }
    // The face arriving: a column five cells ahead, on cells believed free.
    std::vector<CellIndex> face;
    for (int y = 20; y <= 22; ++y) {
      face.push_back({27, y});
      state.Set(27, y, 0.02f, 0.0f, 0.0f);
    }
    const ScrollingGridGeometry& g = state.layers.geometry();
    std::vector<CellIndex> before = ShiftedCells(body_now, -2, 0);
    const std::vector<CellIndex> face_before = ShiftedCells(face, -2, 0);
    before.insert(before.end(), face_before.begin(), face_before.end());
    std::vector<CellIndex> now = body_now;
    now.insert(now.end(), face.begin(), face.end());
    ScanFlow flow;
    flow.Prepare(HitsMeasurement(g, before, kClusterDtNs));
    flow.Remember(HitsMeasurement(g, before, kClusterDtNs));
    const MeasurementGrid z = HitsMeasurement(g, now, 2 * kClusterDtNs);
    flow.Prepare(z);
    ClusterMotionOptions options;
    options.birth_min_cells = min_cells;
    ApplyClusterMotion(state.layers, state.ids, z, flow, kClusterDtS, 0.25, options);
    for (const CellIndex& c : face) {
      const std::size_t s = g.StorageIndexOfLocal(c);
      const float occupancy = state.layers.Values(state.ids.occupancy)[s];
      if (min_cells <= 2.0) {
        EXPECT_FLOAT_EQ(occupancy, 0.7f) << c.iy;
        EXPECT_FLOAT_EQ(state.layers.Values(state.ids.seen)[s], 1.0f) << c.iy;
      } else {
        EXPECT_FLOAT_EQ(occupancy, 0.02f) << c.iy;
      }
      EXPECT_GT(state.Vx(c.ix, c.iy), 3.0f) << c.iy;  // attached either way
    }
  }
}

// --- in the filter: a walker seen by a lidar from one side

// A scan from the origin of a disc of `radius_m` at `centre_m` (0.25 degree beams over +-60
// degrees; beams that miss it return nothing).
LidarScan ScanOfDisc(const Eigen::Vector2d& centre_m, double radius_m, TimeNs stamp) {
  LidarScan scan;
  scan.stamp = stamp;
  scan.angle_min_rad = -M_PI / 3.0;
  scan.angle_increment_rad = 0.25 * M_PI / 180.0;
  scan.max_range_m = 30.0;
  const int beams = static_cast<int>(std::lround(2.0 * M_PI / 3.0 / scan.angle_increment_rad));
  for (int i = 0; i <= beams; ++i) {
    const double a = scan.BeamAngle(static_cast<std::size_t>(i));
    const Eigen::Vector2d u(std::cos(a), std::sin(a));
    const double along = u.dot(centre_m);
    const double off2 = centre_m.squaredNorm() - along * along;
    const double r2 = radius_m * radius_m;
    const float range = (along > 0.0 && off2 < r2)
                            ? static_cast<float>(along - std::sqrt(r2 - off2))
                            : static_cast<float>(scan.max_range_m);
    scan.ranges_m.push_back(range);
  }
  return scan;
}

// RMS of the velocity error over the disc's occupied cells, cycles [from, to).
double WalkerVelocityRms(const FilterOptions& options, int from, int to) {
  const Eigen::Vector2d v(0.0, 1.1);  // the crossing group's walkers
  const Eigen::Vector2d start(8.0, -2.0);
  constexpr double kRadiusM = 0.25;
  ExtendedGrid grid(ScrollingGridGeometry(kClusterCellM, 80, 80, CellIndex{0, -40}), options);
  double sum2 = 0.0;
  int n = 0;
  for (int k = 0; k < to; ++k) {
    const Eigen::Vector2d p = start + v * (k * kClusterDtS);
    MeasurementGrid z = ComputeInverseSensorModel(ScanOfDisc(p, kRadiusM, (k + 1) * kClusterDtNs),
                                                  Pose2(), grid.geometry(), {});
    z.stamp = (k + 1) * kClusterDtNs;
    grid.Update(z, kClusterDtS);
    if (k < from) continue;
    const ScrollingGridGeometry& g = grid.geometry();
    for (std::size_t s = 0; s < g.CellCount(); ++s) {
      const Eigen::Vector2d c = g.CellCenterM(g.GlobalFromStorage(s));
      if ((c - p).norm() > kRadiusM + 0.5 * kClusterCellM) continue;
      if (grid.layers().Values(grid.ids().occupancy)[s] <= 0.5f) continue;
      const Eigen::Vector2d e(
          static_cast<double>(grid.layers().Values(grid.ids().velocity_x_mps)[s]) - v.x(),
          static_cast<double>(grid.layers().Values(grid.ids().velocity_y_mps)[s]) - v.y());
      sum2 += e.squaredNorm();
      ++n;
    }
  }
  EXPECT_GT(n, 50);
  return std::sqrt(sum2 / std::max(n, 1));
}

// The crossing group's case (docs/grid.md): a walker crossing the beams at 8 m, its near arc
// sliding along itself. From its second second on, the body measured whole holds its cells'
// velocity within 0.25 m/s RMS; eq. 14 alone lags by twice that.
TEST(ClusterMotionInTheFilterTest, AWalkersArcIsTrackedAtItsSpeed) {
  FilterOptions on;
  FilterOptions off;
  off.cluster_motion.enabled = false;
  const double with = WalkerVelocityRms(on, 12, 40);
  const double without = WalkerVelocityRms(off, 12, 40);
  std::printf("walker at 1.1 m/s, cycles 12-39: velocity RMS %.3f m/s with, %.3f without\n", with,
              without);
  EXPECT_LT(with, 0.25);
  EXPECT_LT(with, 0.6 * without);
}

}  // namespace
}  // namespace lookout::grid
