#include "lookout/grid/extended_grid.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "lookout/core/input_error.h"
#include "lookout/grid/reference_filter.h"

namespace lookout::grid {
namespace {

constexpr double kCellM = 0.15;
constexpr double kDtS = 0.08;  // 12.5 Hz lidar
// The same in stamp units: the scan pair's long baseline scales by the measurements' stamps.
constexpr TimeNs kDtNs = 80'000'000;
constexpr float kHit = 0.7f;
constexpr float kFree = 0.3f;

ScrollingGridGeometry Geometry(int width, int height) {
  return ScrollingGridGeometry(kCellM, width, height, CellIndex{0, 0});
}

// An axis-aligned box of cells [x0, x0 + w) x [y0, y0 + h), in metres of the odometry frame.
struct BoxM {
  double x0_m, y0_m, width_m, height_m;
};

// A synthetic measurement: cells whose centre lies in a box get p_hit; the rest of the window
// gets p_free where `observed`, else 0.5.
MeasurementGrid Measure(const ScrollingGridGeometry& g, const std::vector<BoxM>& boxes,
                        bool observed = true) {
  MeasurementGrid z;
  z.geometry = g;
  z.p_occupied.assign(g.CellCount(), observed ? kFree : kUnknownProbability);
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const Eigen::Vector2d c = g.CellCenterM(g.GlobalFromLocal({x, y}));
      for (const BoxM& b : boxes) {
        if (c.x() >= b.x0_m && c.x() < b.x0_m + b.width_m && c.y() >= b.y0_m &&
            c.y() < b.y0_m + b.height_m) {
          z.p_occupied[g.StorageIndexOfLocal({x, y})] = kHit;
        }
      }
    }
  }
  for (std::size_t i = 0; i < z.p_occupied.size(); ++i) {
    if (z.p_occupied[i] != kUnknownProbability) z.touched.push_back(i);
  }
  return z;
}

std::span<const float> Layer(const ExtendedGrid& grid, LayerId id) {
  return grid.layers().Values(id);
}

// Mean velocity over the cells of `box` whose occupancy is at least `min_occupancy`.
Eigen::Vector2d MeanVelocityIn(const ExtendedGrid& grid, const BoxM& box, double min_occupancy,
                               int* count = nullptr) {
  const auto& g = grid.geometry();
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int n = 0;
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const Eigen::Vector2d c = g.CellCenterM(g.GlobalFromLocal({x, y}));
      if (c.x() < box.x0_m || c.x() >= box.x0_m + box.width_m || c.y() < box.y0_m ||
          c.y() >= box.y0_m + box.height_m) {
        continue;
      }
      const std::size_t i = g.StorageIndexOfLocal({x, y});
      if (static_cast<double>(Layer(grid, grid.ids().occupancy)[i]) < min_occupancy) continue;
      sum += Eigen::Vector2d(Layer(grid, grid.ids().velocity_x_mps)[i],
                             Layer(grid, grid.ids().velocity_y_mps)[i])
                 .cast<double>();
      ++n;
    }
  }
  if (count) *count = n;
  return n > 0 ? Eigen::Vector2d(sum / n) : Eigen::Vector2d::Zero();
}

// Runs a box of `size` moving at `velocity` for `cycles` cycles; returns the grid.
ExtendedGrid TrackBox(int width, int height, Eigen::Vector2d start_m, Eigen::Vector2d size_m,
                      Eigen::Vector2d velocity_mps, int cycles, const FilterOptions& options = {}) {
  ExtendedGrid grid(Geometry(width, height), options);
  for (int k = 0; k < cycles; ++k) {
    const Eigen::Vector2d p = start_m + velocity_mps * (k * kDtS);
    MeasurementGrid z = Measure(grid.geometry(), {BoxM{p.x(), p.y(), size_m.x(), size_m.y()}});
    z.stamp = (k + 1) * kDtNs;
    grid.Update(z, kDtS);
  }
  return grid;
}

// --- agreement with the literal reference

struct RandomWorld {
  ExtendedGrid grid;
  MeasurementGrid z;
};

// A 24 x 24 grid with a few blobs of tracked occupancy (random velocities, seen or new, random
// class pmfs and links) and a measurement of the blobs moved by about their velocity.
RandomWorld MakeRandomWorld(std::uint64_t seed, const FilterOptions& options) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto g = Geometry(24, 24);
  RandomWorld w{ExtendedGrid(g, options), MeasurementGrid{}};
  GridLayers& layers = w.grid.mutable_layers();
  const FilterLayerIds& ids = w.grid.ids();
  std::vector<BoxM> moved;
  for (int blob = 0; blob < 3; ++blob) {
    const int x0 = 4 + static_cast<int>(unit(rng) * 14), y0 = 4 + static_cast<int>(unit(rng) * 14);
    const int bw = 2 + static_cast<int>(unit(rng) * 3), bh = 2 + static_cast<int>(unit(rng) * 3);
    const double vx = (unit(rng) - 0.5) * 8.0, vy = (unit(rng) - 0.5) * 8.0;
    const float seen = unit(rng) < 0.7 ? 0.9f : 0.1f;
    for (int y = y0; y < std::min(24, y0 + bh); ++y) {
      for (int x = x0; x < std::min(24, x0 + bw); ++x) {
        const std::size_t i = g.StorageIndexOfLocal({x, y});
        layers.Values(ids.occupancy)[i] = static_cast<float>(0.65 + 0.3 * unit(rng));
        layers.Values(ids.velocity_x_mps)[i] = static_cast<float>(vx);
        layers.Values(ids.velocity_y_mps)[i] = static_cast<float>(vy);
        layers.Values(ids.velocity_confidence)[i] = static_cast<float>(unit(rng));
        layers.Values(ids.seen)[i] = seen;
        double total = 0.0;
        std::array<double, kGridClassCount> pmf{};
        for (double& p : pmf) total += (p = 0.05 + unit(rng));
        for (std::size_t c = 0; c < kGridClassCount; ++c) {
          layers.Values(ids.class_pmf[c])[i] = static_cast<float>(pmf[c] / total);
        }
        for (std::size_t d = 0; d < kNeighbourCount; ++d) {
          layers.Values(ids.rigidity[d])[i] = static_cast<float>(0.8 * unit(rng));
        }
      }
    }
    moved.push_back(BoxM{(x0 + vx * kDtS / kCellM) * kCellM, (y0 + vy * kDtS / kCellM) * kCellM,
                         bw * kCellM, bh * kCellM});
  }
  w.z = Measure(g, moved);
  // Part of the window unobserved, to exercise the 0.5 path.
  for (int y = 0; y < 24; ++y) {
    for (int x = 16; x < 24; ++x) w.z.p_occupied[g.StorageIndexOfLocal({x, y})] = 0.5f;
  }
  return w;
}

// Bounds of the factorised rigidity term against the literal one (see the test).
constexpr double kMixedOccupancyBound = 0.15;
constexpr double kMixedVelocityBoundMps = 0.4;
constexpr double kTrackedOccupancyBound = 0.03;
constexpr double kTrackedVelocityBoundMps = 0.08;

struct LayerDiff {
  double occupancy = 0.0, seen = 0.0, velocity_mps = 0.0, confidence = 0.0, rigidity = 0.0;
  // Velocity over the cells the fast path holds occupied (elsewhere a velocity carried by a
  // negligible mass is meaningless and any approximation moves it freely).
  double occupied_velocity_mps = 0.0;
};

LayerDiff Compare(const ExtendedGrid& fast, const GridLayers& reference) {
  const FilterLayerIds& ids = fast.ids();
  const auto max_diff = [&](LayerId id) {
    double m = 0.0;
    const auto a = fast.layers().Values(id);
    const auto b = reference.Values(id);
    for (std::size_t i = 0; i < a.size(); ++i) {
      m = std::max(m, std::abs(static_cast<double>(a[i]) - static_cast<double>(b[i])));
    }
    return m;
  };
  LayerDiff d;
  d.occupancy = max_diff(ids.occupancy);
  d.seen = max_diff(ids.seen);
  d.velocity_mps = std::max(max_diff(ids.velocity_x_mps), max_diff(ids.velocity_y_mps));
  d.confidence = max_diff(ids.velocity_confidence);
  for (const LayerId id : ids.rigidity) d.rigidity = std::max(d.rigidity, max_diff(id));
  const auto o = fast.layers().Values(ids.occupancy);
  for (std::size_t i = 0; i < o.size(); ++i) {
    if (o[i] < 0.6f) continue;
    for (const LayerId id : {ids.velocity_x_mps, ids.velocity_y_mps}) {
      d.occupied_velocity_mps = std::max(d.occupied_velocity_mps,
                                         std::abs(static_cast<double>(fast.layers().Values(id)[i]) -
                                                  static_cast<double>(reference.Values(id)[i])));
    }
  }
  return d;
}

LayerDiff RunAgainstReference(std::uint64_t seed, const FilterOptions& options) {
  RandomWorld w = MakeRandomWorld(seed, options);
  GridLayers reference = w.grid.layers();
  w.grid.Update(w.z, kDtS);
  ReferenceUpdate(reference, w.grid.ids(), w.z, kDtS, options);
  return Compare(w.grid, reference);
}

// Where every stage is the literal equation, fast and reference differ by float rounding only.
void ExpectMatchesReference(const LayerDiff& d) {
  EXPECT_LT(d.occupancy, 1e-4);
  EXPECT_LT(d.seen, 1e-4);
  EXPECT_LT(d.velocity_mps, 1e-3);
  EXPECT_LT(d.confidence, 1e-4);
  EXPECT_LT(d.rigidity, 1e-4);
}

// Exact stages (everything but the factorised rigidity term): float vs double only.
TEST(ExtendedGridReferenceTest, FastPathMatchesLiteralReference) {
  FilterOptions options;
  options.enable_rigidity_constraint = false;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const LayerDiff d = RunAgainstReference(seed, options);
    ExpectMatchesReference(d);
  }
}

// The same with the coarse window's dense core and the moved share on: the reference builds the
// core's samples and the share on its own.
TEST(ExtendedGridReferenceTest, FastPathMatchesLiteralReferenceWithDenseCoreAndMovedShare) {
  FilterOptions options;
  options.enable_rigidity_constraint = false;
  options.new_window_dense_half_cells = 2;
  options.moved_share_exponent = 0.5;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    ExpectMatchesReference(RunAgainstReference(seed, options));
  }
  options.enable_rigidity_constraint = true;
  options.rigidity_exact_across_lattices = true;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed) + " exact rigidity");
    ExpectMatchesReference(RunAgainstReference(seed, options));
  }
}

// With the scan pair's windows (scan_flow.h) on: the reference, given the grid's scan pair,
// chooses the same windows and agrees to float rounding; and the pair changed the result (the
// check is not vacuous).
TEST(ExtendedGridReferenceTest, FastPathMatchesLiteralReferenceWithScanFlow) {
  FilterOptions options;
  options.enable_rigidity_constraint = false;
  options.scan_flow.enabled = true;
  options.scan_flow.long_lag_scans = 2;
  ExtendedGrid grid(Geometry(48, 32), options);
  const auto world = [](int k) {
    const double t = k * kDtS;
    return std::vector<BoxM>{BoxM{0.9 + 7.5 * t, 1.2, 0.15, 0.9},  // a thin side, 4 cells a cycle
                             BoxM{4.5, 3.3 - 1.9 * t, 0.9, 0.15}, BoxM{0.3, 4.2, 5.4, 0.15}};
  };
  for (int k = 0; k < 2; ++k) grid.Update(Measure(grid.geometry(), world(k)), kDtS);
  MeasurementGrid z = Measure(grid.geometry(), world(2));
  // The grid's pairs need stamps: Measure leaves them 0, the long baseline is then skipped.
  ScanFlow flow = grid.scan_flow();
  flow.Prepare(z);
  ASSERT_TRUE(flow.HasPair());
  GridLayers reference = grid.layers();
  GridLayers without_flow = grid.layers();
  grid.Update(z, kDtS);
  ReferenceUpdate(reference, grid.ids(), z, kDtS, options, &flow);
  ReferenceUpdate(without_flow, grid.ids(), z, kDtS, options, nullptr);
  ExpectMatchesReference(Compare(grid, reference));
  EXPECT_GT(Compare(grid, without_flow).occupancy, 1e-3);
}

// The dense core's entries: every displacement within +-dense_half of the centre once, the
// lattice's where it has them, EntryOf the inverse of Displacement, Psi summing to one.
TEST(SearchWindowTest, DenseCoreHoldsEveryNearDisplacementOnce) {
  SearchWindow w;
  w.center = {3, -1};
  w.half = 6;
  w.stride = 2;
  w.dense_half = 2;
  w.mean_x_cells = 3.3;
  w.mean_y_cells = -0.8;
  w.sigma_cells = 6.0;
  w.stay_weight = 0.5;
  w.stay_sigma_cells = 0.4;
  EXPECT_EQ(w.EntryCount(), 169u + 16u);
  std::vector<int> hits(25, 0);
  for (std::size_t k = 0; k < w.EntryCount(); ++k) {
    const CellIndex d = w.Displacement(k);
    EXPECT_EQ(w.EntryOf(d), static_cast<std::int64_t>(k));
    const int x = d.ix - w.center.ix, y = d.iy - w.center.iy;
    if (std::abs(x) <= 2 && std::abs(y) <= 2) ++hits[static_cast<std::size_t>((y + 2) * 5 + x + 2)];
  }
  for (const int h : hits) EXPECT_EQ(h, 1);
  std::size_t k_each = 0;
  w.ForEachDisplacement([&](std::size_t k, const CellIndex& d) {
    EXPECT_EQ(k, k_each++);
    EXPECT_EQ(d, w.Displacement(k));
  });
  EXPECT_EQ(k_each, w.EntryCount());
  EXPECT_EQ(w.EntryOf({w.center.ix + 3, w.center.iy}), -1);  // off the lattice, outside the core
  std::vector<float> psi(w.EntryCount()), share(w.EntryCount());
  ComputePsi(w, psi.data(), share.data());
  double sum = 0.0;
  for (const float p : psi) sum += static_cast<double>(p);
  EXPECT_NEAR(sum, 1.0, 1e-5);
  // The sample nearest the mean, (3, -1), is a lattice one; its neighbour (4, -1) a core one,
  // which the stay component (sigma 0.4) reaches and the lattice alone could not.
  const auto nearest = static_cast<std::size_t>(w.EntryOf({3, -1}));
  const auto core = static_cast<std::size_t>(w.EntryOf({4, -1}));
  EXPECT_GE(core, 169u);
  EXPECT_GT(share[nearest], 0.9f);
  EXPECT_GT(psi[core], 0.01f);
}

// The factorised rigidity term against the literal O(M^6) one. Exact where a linked neighbour's
// window has the cell's lattice; elsewhere the neighbour's pmf is replaced by the Gaussian of its
// two moments. The random worlds are a hard case (strong random links, coarse stride-2 windows
// next to fine ones, pmfs made multi-modal by eq. 10); measured worst over seeds 1-8: occupancy
// 0.116 and velocity 0.31 m/s with mixed windows, 0.021 and 0.024 m/s with fine windows only
// (2026-12-02; the printed figures). The exact form is ExactRigidityMatchesLiteralReference.
TEST(ExtendedGridReferenceTest, FactorisedRigidityStaysCloseToLiteral) {
  for (const bool tracked : {false, true}) {
    FilterOptions options;
    if (tracked) options.seen_threshold = options.known_confidence = 1e-3;  // fine windows only
    LayerDiff worst;
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
      SCOPED_TRACE("seed " + std::to_string(seed) + (tracked ? " tracked" : " mixed"));
      const LayerDiff d = RunAgainstReference(seed, options);
      worst.occupancy = std::max(worst.occupancy, d.occupancy);
      worst.occupied_velocity_mps = std::max(worst.occupied_velocity_mps, d.occupied_velocity_mps);
      worst.rigidity = std::max(worst.rigidity, d.rigidity);
      EXPECT_LT(d.occupancy, tracked ? kTrackedOccupancyBound : kMixedOccupancyBound);
      EXPECT_LT(d.occupied_velocity_mps,
                tracked ? kTrackedVelocityBoundMps : kMixedVelocityBoundMps);
    }
    std::printf(
        "factorised vs literal (%s windows), worst over seeds 1-8: occupancy %.3f, "
        "velocity in occupied cells %.3f m/s, rigidity links %.3f\n",
        tracked ? "fine" : "mixed", worst.occupancy, worst.occupied_velocity_mps, worst.rigidity);
  }
}

// The same comparison with the rigidity term summed exactly across lattices
// (rigidity_exact_across_lattices): every stage is then the literal equation, so the fast path
// matches the O(M^6) reference to float rounding (measured worst over seeds 1-8, mixed windows:
// occupancy 9e-8, velocity 7e-7 m/s, links 2e-7).
TEST(ExtendedGridReferenceTest, ExactRigidityMatchesLiteralReference) {
  for (const bool tracked : {false, true}) {
    FilterOptions options;
    options.rigidity_exact_across_lattices = true;
    if (tracked) options.seen_threshold = options.known_confidence = 1e-3;  // fine windows only
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
      SCOPED_TRACE("seed " + std::to_string(seed) + (tracked ? " tracked" : " mixed"));
      const LayerDiff d = RunAgainstReference(seed, options);
      ExpectMatchesReference(d);
    }
  }
  // Windows of other sides than the defaults' (whose loops the fast path unrolls at compile
  // time: BlurLattice in interaction_constraints.cc).
  FilterOptions options;
  options.rigidity_exact_across_lattices = true;
  options.window_size_cells = 5;
  options.new_window_size_cells = 9;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed) + " windows 5 and 9");
    ExpectMatchesReference(RunAgainstReference(seed, options));
  }
}

// --- determinism

TEST(ExtendedGridTest, IdenticalOutputForOneAndTwoThreads) {
  const auto run = [](int threads) {
    tbb::task_arena arena(threads);
    std::vector<std::vector<float>> out;
    arena.execute([&] {
      ExtendedGrid grid(Geometry(96, 64));
      for (int k = 0; k < 8; ++k) {
        const double t = k * kDtS;
        grid.Update(Measure(grid.geometry(),
                            {BoxM{1.0 + 3.0 * t, 2.0, 0.9, 0.6},
                             BoxM{12.0 - 10.0 * t, 6.0, 2.4, 1.2}, BoxM{5.0, 0.3, 6.0, 0.3}}),
                    kDtS);
      }
      for (int l = 0; l < grid.layers().LayerCount(); ++l) {
        const auto v = grid.layers().Values(LayerId{l});
        out.emplace_back(v.begin(), v.end());
      }
    });
    return out;
  };
  EXPECT_EQ(run(1), run(2));
}

// --- behaviour

TEST(ExtendedGridTest, StaticWorldConverges) {
  const std::vector<BoxM> world = {BoxM{0.6, 0.6, 3.0, 0.3}, BoxM{4.5, 3.0, 0.6, 0.6}};
  ExtendedGrid grid(Geometry(48, 48));
  for (int k = 0; k < 20; ++k) grid.Update(Measure(grid.geometry(), world), kDtS);
  const MeasurementGrid truth = Measure(grid.geometry(), world);
  const auto o = Layer(grid, grid.ids().occupancy);
  const auto vx = Layer(grid, grid.ids().velocity_x_mps);
  const auto vy = Layer(grid, grid.ids().velocity_y_mps);
  double worst_occupied = 1.0, worst_free = 0.0, worst_speed = 0.0;
  for (std::size_t i = 0; i < o.size(); ++i) {
    if (truth.p_occupied[i] == kHit) {
      worst_occupied = std::min(worst_occupied, static_cast<double>(o[i]));
      worst_speed =
          std::max(worst_speed, std::hypot(static_cast<double>(vx[i]), static_cast<double>(vy[i])));
    } else {
      worst_free = std::max(worst_free, static_cast<double>(o[i]));
    }
  }
  EXPECT_GT(worst_occupied, 0.95);
  EXPECT_LT(worst_free, 0.05);
  EXPECT_LT(worst_speed, 0.2);
}

// A 0.9 m x 0.6 m box moving at 3.75 m/s (2 cells per cycle), velocity from rest: the mean
// velocity over its occupied cells is within 0.3 m/s of the truth from cycle kConverged on, and
// stays there.
TEST(ExtendedGridTest, MovingBoxVelocityConvergesFromRest) {
  const Eigen::Vector2d v(3.75, 0.0);
  const Eigen::Vector2d start(0.9, 1.5);
  constexpr int kCycles = 25, kConverged = 15;
  ExtendedGrid grid(Geometry(128, 24));
  int last_bad = -1;
  for (int k = 0; k < kCycles; ++k) {
    const Eigen::Vector2d p = start + v * (k * kDtS);
    const BoxM box{p.x(), p.y(), 0.9, 0.6};
    grid.Update(Measure(grid.geometry(), {box}), kDtS);
    int count = 0;
    const Eigen::Vector2d mean = MeanVelocityIn(grid, box, 0.6, &count);
    if (count < 10 || (mean - v).norm() >= 0.3) last_bad = k;
    std::printf("3.75 m/s box, cycle %d: mean velocity %.2f m/s over %d cells\n", k, mean.x(),
                count);
  }
  EXPECT_LT(last_bad + 1, kConverged) << "converged (for good) from cycle " << last_bad + 1;
}

// 20 m/s: 10.7 cells per cycle, beyond the paper's cap of 3 cells per cycle with M = 7. The
// synthetic box is rasterised on 0.15 m cells, so it jumps by 10 or 11 cells a scan (18.75 or
// 20.6 m/s): a single cycle's estimate carries that sampling noise, hence the error is taken on
// the mean over the last 8 cycles (0.64 s), and the box's size as the fewest of its 72 cells
// held (occupancy >= 0.6) in any of them. Tracked since a body is measured on the scans'
// outlines and a body seen whole that left free space behind it has no longer rivals
// (cluster_motion.h): before, the box matched itself two or three cells off nearly as well as
// at its motion, the clusters' stage called it ambiguous, and the box was lost (0 cells from
// cycle 19). Now 66-72 of its cells are held at 19.0-19.9 m/s.
TEST(ExtendedGridTest, TwentyMetresPerSecondSolidBoxIsTracked) {
  const Eigen::Vector2d v(20.0, 0.0);
  const Eigen::Vector2d start(0.9, 1.2);
  constexpr int kCycles = 20, kAveraged = 8;
  ExtendedGrid grid(Geometry(300, 24));
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int min_count = 1 << 30;
  for (int k = 0; k < kCycles; ++k) {
    const Eigen::Vector2d p = start + v * (k * kDtS);
    const BoxM box{p.x(), p.y(), 1.8, 0.9};
    MeasurementGrid z = Measure(grid.geometry(), {box});
    z.stamp = (k + 1) * kDtNs;
    grid.Update(z, kDtS);
    if (k < kCycles - kAveraged) continue;
    int count = 0;
    const Eigen::Vector2d mean = MeanVelocityIn(grid, box, 0.6, &count);
    std::printf("20 m/s box, cycle %d: mean velocity (%.2f, %.2f) m/s over %d cells\n", k, mean.x(),
                mean.y(), count);
    sum += mean;
    min_count = std::min(min_count, count);
  }
  const Eigen::Vector2d mean = sum / kAveraged;
  EXPECT_GT(min_count, 50) << "of the box's 72 cells";
  EXPECT_LT((mean - v).norm(), 0.5) << mean.transpose();
}

// Tracked occupancy mass: O S, the occupancy that tracked cells carried in (step 5's seen
// share). The renewal of the cells an occluded object leaves drifts them back to unknown (0.5)
// with S = 0: ignorance, not object mass.
double MassNear(const ExtendedGrid& grid, const Eigen::Vector2d& centre_m, double radius_m) {
  const auto& g = grid.geometry();
  const auto o = Layer(grid, grid.ids().occupancy);
  const auto s = Layer(grid, grid.ids().seen);
  double mass = 0.0;
  for (std::size_t i = 0; i < o.size(); ++i) {
    if ((g.CellCenterM(g.GlobalFromStorage(i)) - centre_m).norm() < radius_m) {
      mass += static_cast<double>(o[i]) * static_cast<double>(s[i]);
    }
  }
  return mass;
}

// The RMS distance of the occupancy mass from its centroid, a cell's mass being its occupancy
// above `floor`: how far the grid's belief about an object is spread. With the free floor
// (FilterOptions::occupancy_clamp, where space seen free settles) every bit of the object's
// belief counts; with 0.5 (2 O - 1, the mass above the prior) only its confident core does, and
// a belief that diffuses lowers its cells' occupancy, so its core shrinks as it spreads.
double MassSpreadM(const ExtendedGrid& grid, double floor) {
  const auto& g = grid.geometry();
  const auto o = Layer(grid, grid.ids().occupancy);
  double mass = 0.0;
  Eigen::Vector2d first = Eigen::Vector2d::Zero();
  double second = 0.0;
  for (std::size_t i = 0; i < o.size(); ++i) {
    const double w = std::max(0.0, static_cast<double>(o[i]) - floor);
    const Eigen::Vector2d c = g.CellCenterM(g.GlobalFromStorage(i));
    mass += w;
    first += w * c;
    second += w * c.squaredNorm();
  }
  const Eigen::Vector2d mean = first / mass;
  return std::sqrt(std::max(0.0, second / mass - mean.squaredNorm()));
}

// A 0.45 m box walking at 1.5 m/s, seen for 15 cycles, then hidden (every measurement 0.5) for
// 12 (~1 s): its mass stays near the truth and its belief spreads. The spread is the whole
// belief's (MassSpreadM above the free floor), checked also on a pure diffusion (both
// constraints of step 4 off), which spreads by construction: there the core above 0.5
// shrinks (0.145 -> 0.032 m with the scan pair, 2026-12-03), so the core cannot be the measure.
// With the scan pair the box stays tracked and step 4 holds it together: its core shrinks too.
// `cycles` updates of a square box of side `side_m` seen moving at `v` from its lower-left
// corner `start`, every scan seeing the rest free; and `cycles` updates seeing nothing (all 1/2).
void SeeMovingBox(ExtendedGrid& grid, const Eigen::Vector2d& start, const Eigen::Vector2d& v,
                  double side_m, int cycles, TimeNs& stamp) {
  for (int k = 0; k < cycles; ++k) {
    const Eigen::Vector2d p = start + v * (k * kDtS);
    MeasurementGrid z = Measure(grid.geometry(), {BoxM{p.x(), p.y(), side_m, side_m}});
    z.stamp = stamp += kDtNs;
    grid.Update(z, kDtS);
  }
}
void SeeNothing(ExtendedGrid& grid, int cycles, TimeNs& stamp) {
  for (int k = 0; k < cycles; ++k) {
    MeasurementGrid unknown = Measure(grid.geometry(), {}, /*observed=*/false);
    unknown.stamp = stamp += kDtNs;
    grid.Update(unknown, kDtS);
  }
}

TEST(ExtendedGridTest, OccludedObjectPersistsAndSpreads) {
  const Eigen::Vector2d v(1.5, 0.0);
  const Eigen::Vector2d start(1.5, 2.4);
  const Eigen::Vector2d half_size(0.225, 0.225);
  constexpr int kSeen = 15, kHidden = 12;  // ~1 s hidden
  FilterOptions diffusion;
  diffusion.enable_no_convergence_constraint = false;
  diffusion.enable_rigidity_constraint = false;
  for (const FilterOptions& options : {FilterOptions{}, diffusion}) {
    const bool constrained = options.enable_rigidity_constraint;
    SCOPED_TRACE(constrained ? "defaults" : "both constraints off");
    ExtendedGrid grid(Geometry(64, 40), options);
    const double floor = options.occupancy_clamp;
    TimeNs stamp = 0;
    SeeMovingBox(grid, start, v, 0.45, kSeen, stamp);
    const double spread_before = MassSpreadM(grid, floor);
    const double core_before = MassSpreadM(grid, 0.5);
    const Eigen::Vector2d seen_at = start + v * ((kSeen - 1) * kDtS) + half_size;
    const double mass_before = MassNear(grid, seen_at, 1.0);
    SeeNothing(grid, kHidden, stamp);
    const Eigen::Vector2d truth = start + v * ((kSeen + kHidden - 1) * kDtS) + half_size;
    const double near = MassNear(grid, truth, 1.0);
    const double total = MassNear(grid, truth, 100.0);  // reported only (see the report)
    const double spread_after = MassSpreadM(grid, floor);
    std::printf(
        "occluded, %s: mass before %.2f, after %.2f of which %.2f within 1 m of the truth; "
        "spread %.3f -> %.3f m (core above 0.5: %.3f -> %.3f m)\n",
        constrained ? "defaults" : "no constraints", mass_before, total, near, spread_before,
        spread_after, core_before, MassSpreadM(grid, 0.5));
    EXPECT_GT(spread_after, spread_before + 0.1) << "occluded occupancy should spread";
    if (constrained) {
      EXPECT_GT(near, 0.5 * mass_before) << "the occluded object's mass was lost or left behind";
    }
  }
}

// A 3 m/s body hidden for a second keeps the speed it was tracked at
// (FilterOptions::velocity_persists_unobserved): the decay of the motion model stands for
// measurements that stop supporting a velocity, and a hidden cell has none. Decaying, each of
// the twelve hidden cycles takes exp(-0.08 / 3) of the prediction, and eq. 14, which reads the
// displacement of the decayed prediction, compounds it: 2.9 -> 1.9 m/s (measured 2026-12-05;
// persisting, 2.8).
TEST(ExtendedGridTest, AHiddenBodyKeepsItsSpeed) {
  const Eigen::Vector2d v(3.0, 0.0);
  const Eigen::Vector2d start(1.5, 2.4);
  constexpr int kSeen = 15, kHidden = 12;
  const BoxM everywhere{-100.0, -100.0, 200.0, 200.0};
  for (const bool persists : {true, false}) {
    SCOPED_TRACE(persists ? "persists" : "decays");
    FilterOptions options;
    options.velocity_persists_unobserved = persists;
    // The filter's own motion model alone: the hidden bodies' stage would carry the box at its
    // speed either way (HiddenBodiesTest).
    options.hidden_bodies.enabled = false;
    ExtendedGrid grid(Geometry(64, 40), options);
    TimeNs stamp = 0;
    SeeMovingBox(grid, start, v, 0.9, kSeen, stamp);
    int seen_cells = 0;
    const double seen_speed = MeanVelocityIn(grid, everywhere, 0.3, &seen_cells).x();
    SeeNothing(grid, kHidden, stamp);
    int hidden_cells = 0;
    const double hidden_speed = MeanVelocityIn(grid, everywhere, 0.3, &hidden_cells).x();
    std::printf(
        "hidden body, %s: %.3f m/s over %d cells when last seen, %.3f over %d after %d "
        "hidden cycles\n",
        persists ? "persisting" : "decaying", seen_speed, seen_cells, hidden_speed, hidden_cells,
        kHidden);
    ASSERT_GT(seen_cells, 0);
    ASSERT_GT(hidden_cells, 0);
    EXPECT_NEAR(seen_speed, v.x(), 0.3);
    if (persists) {
      EXPECT_NEAR(hidden_speed, seen_speed, 0.1 * seen_speed);
    } else {
      EXPECT_LT(hidden_speed, 0.8 * seen_speed);
    }
  }
}

// The occluded-pedestrian's walker in small (grid.occluded_retention_s's evidence): a 0.45 m
// body at 1.5 m/s seen for 1.2 s, then hidden for 2 s in an occluder's shadow, the space around
// seen free. The filter alone spreads it and loses its evidence; the hidden bodies' stage
// carries it whole (hidden_bodies.h).
double EvidenceNear(const ExtendedGrid& grid, const Eigen::Vector2d& centre_m, double radius_m) {
  const auto& g = grid.geometry();
  const auto o = Layer(grid, grid.ids().occupancy);
  double evidence = 0.0;
  for (std::size_t i = 0; i < o.size(); ++i) {
    if ((g.CellCenterM(g.GlobalFromStorage(i)) - centre_m).norm() < radius_m) {
      evidence += std::max(0.0, 2.0 * static_cast<double>(o[i]) - 1.0);
    }
  }
  return evidence;
}

TEST(ExtendedGridTest, AHiddenWalkerIsCarriedWholeThroughTheShadow) {
  const Eigen::Vector2d v(1.5, 0.0);
  const Eigen::Vector2d start(1.5, 2.4);
  const Eigen::Vector2d half_size(0.225, 0.225);
  constexpr int kSeen = 15, kHidden = 25;
  for (const bool carried : {true, false}) {
    SCOPED_TRACE(carried ? "hidden bodies on" : "off");
    FilterOptions options;
    options.hidden_bodies.enabled = carried;
    ExtendedGrid grid(Geometry(64, 40), options);
    TimeNs stamp = 0;
    SeeMovingBox(grid, start, v, 0.45, kSeen, stamp);
    const double seen = EvidenceNear(grid, start + v * ((kSeen - 1) * kDtS) + half_size, 1.0);
    double least = seen, last = seen;
    for (int k = 0; k < kHidden; ++k) {
      // Behind an occluder: its shadow (x 3.1-8 m, y 1.6-3.6 m) unobserved, the rest seen free.
      MeasurementGrid z = Measure(grid.geometry(), {});
      z.touched.clear();
      const auto& g = grid.geometry();
      for (std::size_t i = 0; i < z.p_occupied.size(); ++i) {
        const Eigen::Vector2d c = g.CellCenterM(g.GlobalFromStorage(i));
        if (c.x() >= 3.1 && c.x() < 8.0 && c.y() >= 1.6 && c.y() < 3.6) {
          z.p_occupied[i] = kUnknownProbability;
        } else {
          z.touched.push_back(i);
        }
      }
      z.stamp = stamp += kDtNs;
      grid.Update(z, kDtS);
      const Eigen::Vector2d truth = start + v * ((kSeen + k) * kDtS) + half_size;
      last = EvidenceNear(grid, truth, 1.0);
      least = std::min(least, last);
    }
    std::printf(
        "hidden walker, %s: evidence within 1 m %.2f when last seen, at least %.2f over "
        "%d hidden cycles, %.2f at the end\n",
        carried ? "carried" : "filter alone", seen, least, kHidden, last);
    ASSERT_GT(seen, 1.0);
    if (carried) {
      // The cycle it is remembered holds its cells above the stage's 0.6 only; then the body's
      // own cells each cycle, and the filter's spread of them around.
      EXPECT_GE(least, 0.75 * seen);
      EXPECT_GE(last, seen);
      EXPECT_EQ(grid.hidden_bodies().bodies().size(), 1u);
      const std::vector<std::uint8_t> mask = HiddenBodyMask(grid.hidden_bodies(), grid.geometry());
      EXPECT_EQ(std::count(mask.begin(), mask.end(), 1),
                static_cast<long>(grid.hidden_bodies().bodies()[0].cells.size()));
    } else {
      EXPECT_LT(last, 0.6 * seen);
    }
  }
}

// Two tracked cells aimed at the same target with no evidence: they may not pile up.
TEST(ExtendedGridTest, TwoCellsCannotMergeIntoOne) {
  const auto run = [](bool constrained) {
    FilterOptions options;
    options.enable_no_convergence_constraint = constrained;
    ExtendedGrid grid(Geometry(24, 24), options);
    GridLayers& l = grid.mutable_layers();
    const auto& g = grid.geometry();
    const std::size_t a = g.StorageIndexOfLocal({10, 12}), b = g.StorageIndexOfLocal({14, 12});
    for (const auto& [cell, vx] :
         {std::pair{a, 2 * kCellM / kDtS}, std::pair{b, -2 * kCellM / kDtS}}) {
      l.Values(grid.ids().occupancy)[cell] = 0.95f;
      l.Values(grid.ids().seen)[cell] = 1.0f;
      l.Values(grid.ids().velocity_x_mps)[cell] = static_cast<float>(vx);
      l.Values(grid.ids().velocity_confidence)[cell] = 1.0f;
      l.Values(grid.ids().class_pmf[0])[cell] = 0.96f;  // static: narrowest sigma
      for (std::size_t c = 1; c < kGridClassCount; ++c) {
        l.Values(grid.ids().class_pmf[c])[cell] = 0.01f;
      }
    }
    grid.Update(Measure(g, {}, /*observed=*/false), kDtS);
    return static_cast<double>(l.Values(grid.ids().occupancy)[g.StorageIndexOfLocal({12, 12})]);
  };
  const double merged = run(false);
  const double kept_apart = run(true);
  EXPECT_GT(merged, 0.98) << "without the constraint both pour into the meeting cell";
  EXPECT_LT(kept_apart, merged - 0.1);
}

// A rigid body moves as one: the velocities across a tracked box agree.
TEST(ExtendedGridTest, RigidBodyMovesAsOne) {
  const Eigen::Vector2d v(0.0, 3.0);
  constexpr int kCycles = 15;
  const ExtendedGrid grid = TrackBox(40, 120, {2.1, 0.6}, {1.2, 0.9}, v, kCycles);
  const Eigen::Vector2d p = Eigen::Vector2d(2.1, 0.6) + v * ((kCycles - 1) * kDtS);
  const BoxM box{p.x(), p.y(), 1.2, 0.9};
  const Eigen::Vector2d mean = MeanVelocityIn(grid, box, 0.6);
  const auto& g = grid.geometry();
  double sq = 0.0;
  double linked = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < g.CellCount(); ++i) {
    const Eigen::Vector2d c = g.CellCenterM(g.GlobalFromStorage(i));
    if (c.x() < box.x0_m || c.x() >= box.x0_m + box.width_m || c.y() < box.y0_m ||
        c.y() >= box.y0_m + box.height_m || Layer(grid, grid.ids().occupancy)[i] < 0.6f) {
      continue;
    }
    const Eigen::Vector2d vi(Layer(grid, grid.ids().velocity_x_mps)[i],
                             Layer(grid, grid.ids().velocity_y_mps)[i]);
    sq += (vi - mean).squaredNorm();
    for (const LayerId d : grid.ids().rigidity) linked += static_cast<double>(Layer(grid, d)[i]);
    ++n;
  }
  ASSERT_GT(n, 10);
  const double rms = std::sqrt(sq / n);
  std::printf("rigid body at 3 m/s: mean (%.2f, %.2f) m/s, rms spread %.2f m/s, mean link %.3f\n",
              mean.x(), mean.y(), rms, linked / (8.0 * n));
  EXPECT_LT((mean - v).norm(), 0.3);
  // Bound set after measuring 0.37-0.40 m/s (rms over the body's occupied cells, defaults).
  EXPECT_LT(rms, 0.45) << "the body's cells should share one velocity";
  // A sharp shared move pmf of sigma ~ 0.5 cell gives D = sum_a p(a)^2 ~ 0.3; two independent
  // diffuse ones give ~ 1 / 49.
  EXPECT_GT(linked / (8.0 * n), 0.1);
}

// The grid lives in the odometry frame: while the window follows an ego driving at 15 m/s
// (and turning: only its position matters to the window), a static world stays static.
// Returns the occupied static cells in view and how many of them read as moving.
std::pair<int, int> ScrollThroughStaticWorld(const FilterOptions& options) {
  const std::vector<BoxM> world = {BoxM{3.0, 4.5, 6.0, 0.3}, BoxM{12.0, -3.0, 0.6, 0.6},
                                   BoxM{20.0, 2.1, 4.5, 1.8}, BoxM{28.0, -4.5, 0.3, 9.0}};
  ExtendedGrid grid(ScrollingGridGeometry(kCellM, 240, 160, CellIndex{-120, -80}), options);
  const double speed_mps = 15.0, yaw_rate_rps = 0.5;
  Eigen::Vector2d ego = Eigen::Vector2d::Zero();
  double yaw = 0.0;
  for (int k = 0; k < 15; ++k) {  // 18 m, 0.6 rad
    ego += speed_mps * kDtS * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
    yaw += yaw_rate_rps * kDtS;
    grid.Recenter(ego);
    MeasurementGrid z = Measure(grid.geometry(), world);
    z.stamp = (k + 1) * kDtNs;
    grid.Update(z, kDtS);
  }
  const auto& g = grid.geometry();
  const MeasurementGrid truth = Measure(g, world);
  const auto o = Layer(grid, grid.ids().occupancy);
  const auto vx = Layer(grid, grid.ids().velocity_x_mps);
  const auto vy = Layer(grid, grid.ids().velocity_y_mps);
  int occupied = 0, dynamic = 0;
  for (std::size_t i = 0; i < o.size(); ++i) {
    if (truth.p_occupied[i] != kHit || o[i] < 0.6f) continue;
    ++occupied;
    // Dynamic: a velocity the grid vouches for (confidence at least known_confidence).
    if (std::hypot(static_cast<double>(vx[i]), static_cast<double>(vy[i])) > 0.5 &&
        static_cast<double>(Layer(grid, grid.ids().velocity_confidence)[i]) >=
            grid.options().known_confidence) {
      ++dynamic;
    }
  }
  std::printf("scrolling static world: %d occupied cells in view, %d read faster than 0.5 m/s\n",
              occupied, dynamic);
  return {occupied, dynamic};
}

// The scan pair (on by default) shows the newly revealed boxes staying (grid/scan_flow.h).
TEST(ExtendedGridTest, StaticWorldStaysStaticWhileTheWindowScrolls) {
  const auto [occupied, dynamic] = ScrollThroughStaticWorld(FilterOptions{});
  EXPECT_GT(occupied, 50);
  EXPECT_LE(dynamic, occupied / 100);
}

// DISABLED, known limit of the grid without the scan pair: 272 of 570 occupied static cells in
// view read faster than 0.5 m/s with confidence >= known_confidence after 15 cycles (the
// issue's bound is 1 %; 82 of 570 with the paper's velocity form). Solid static boxes revealed
// by the window's leading edge find the rest of their box on one side only, and inside a solid
// box nothing corrects the velocity that gives (docs/grid.md, known faults). Run with
// --gtest_also_run_disabled_tests.
TEST(ExtendedGridTest, DISABLED_StaticWorldStaysStaticWhileTheWindowScrollsWithoutScanFlow) {
  FilterOptions options;
  options.scan_flow.enabled = false;
  const auto [occupied, dynamic] = ScrollThroughStaticWorld(options);
  EXPECT_GT(occupied, 50);
  EXPECT_LE(dynamic, occupied / 100);
}

GridClass ArgmaxClassIn(const ExtendedGrid& grid, const BoxM& box) {
  std::array<double, kGridClassCount> sum{};
  const auto& g = grid.geometry();
  for (std::size_t i = 0; i < g.CellCount(); ++i) {
    const Eigen::Vector2d c = g.CellCenterM(g.GlobalFromStorage(i));
    if (c.x() < box.x0_m || c.x() >= box.x0_m + box.width_m || c.y() < box.y0_m ||
        c.y() >= box.y0_m + box.height_m) {
      continue;
    }
    if (Layer(grid, grid.ids().occupancy)[i] < 0.6f) continue;
    for (std::size_t k = 0; k < kGridClassCount; ++k) {
      sum[k] += static_cast<double>(Layer(grid, grid.ids().class_pmf[k])[i]);
    }
  }
  return static_cast<GridClass>(std::max_element(sum.begin(), sum.end()) - sum.begin());
}

TEST(ExtendedGridTest, SlowSmallClusterTendsToPedestrian) {
  const Eigen::Vector2d v(1.5, 0.0);
  constexpr int kCycles = 25;
  const ExtendedGrid grid = TrackBox(64, 24, {0.9, 1.5}, {0.45, 0.45}, v, kCycles);
  const Eigen::Vector2d p = Eigen::Vector2d(0.9, 1.5) + v * ((kCycles - 1) * kDtS);
  EXPECT_EQ(ArgmaxClassIn(grid, BoxM{p.x(), p.y(), 0.45, 0.45}), GridClass::kPedestrian);
}

TEST(ExtendedGridTest, FastLongClusterTendsToVehicle) {
  const Eigen::Vector2d v(12.0, 0.0);
  constexpr int kCycles = 20;
  FilterOptions without_flow;
  without_flow.scan_flow.enabled = false;
  for (const FilterOptions& options : {FilterOptions{}, without_flow}) {
    SCOPED_TRACE(options.scan_flow.enabled ? "scan flow on" : "scan flow off");
    const ExtendedGrid grid = TrackBox(260, 24, {0.9, 1.2}, {4.5, 1.8}, v, kCycles, options);
    const Eigen::Vector2d p = Eigen::Vector2d(0.9, 1.2) + v * ((kCycles - 1) * kDtS);
    EXPECT_EQ(ArgmaxClassIn(grid, BoxM{p.x(), p.y(), 4.5, 1.8}), GridClass::kVehicle);
  }
}

// A body the grid holds by hand: `footprint` believed occupied (0.95) and moving at vx along x
// with full confidence (and `pmf` as its class, when given), the rest believed free (0.02);
// everything seen.
void HoldFootprint(ExtendedGrid& grid, const BoxM& footprint, double vx,
                   const std::optional<ClassPmf>& pmf = std::nullopt) {
  GridLayers& l = grid.mutable_layers();
  const auto& g = grid.geometry();
  for (std::size_t i = 0; i < g.CellCount(); ++i) {
    const Eigen::Vector2d c = g.CellCenterM(g.GlobalFromStorage(i));
    const bool in = c.x() >= footprint.x0_m && c.x() < footprint.x0_m + footprint.width_m &&
                    c.y() >= footprint.y0_m && c.y() < footprint.y0_m + footprint.height_m;
    l.Values(grid.ids().occupancy)[i] = in ? 0.95f : 0.02f;
    l.Values(grid.ids().seen)[i] = 1.0f;
    if (!in) continue;
    l.Values(grid.ids().velocity_x_mps)[i] = static_cast<float>(vx);
    l.Values(grid.ids().velocity_confidence)[i] = 1.0f;
    for (std::size_t k = 0; pmf && k < kGridClassCount; ++k) {
      l.Values(grid.ids().class_pmf[k])[i] = (*pmf)[k];
    }
  }
}

// A car gone out of view (FilterOptions::unobserved_mover_speed_mps): a 4.5 x 1.8 m body at
// 8 m/s held as a vehicle, then a scan that observes none of it. Its cells have no hits around
// them, which the extent cue reads as a small footprint, at 8 m/s a cyclist's (the speed cue
// cannot tell the two apart there). Without the cue on unobserved movers it keeps its class.
TEST(ExtendedGridTest, ACarGoneOutOfViewKeepsItsClass) {
  const double vx = 8.0;
  const BoxM footprint{1.2, 1.2, 4.5, 1.8};
  for (const bool cue_hidden : {false, true}) {
    SCOPED_TRACE(cue_hidden ? "extent cue on hidden movers" : "no extent cue on hidden movers");
    FilterOptions options;
    if (cue_hidden) options.unobserved_mover_speed_mps = 1e9;
    ExtendedGrid grid(Geometry(64, 24), options);
    const auto& g = grid.geometry();
    HoldFootprint(grid, footprint, vx, ClassPmf{0.05f, 0.05f, 0.1f, 0.7f, 0.1f});
    grid.Update(Measure(g, {}, /*observed=*/false), kDtS);
    const BoxM moved{footprint.x0_m + vx * kDtS, footprint.y0_m, footprint.width_m,
                     footprint.height_m};
    const GridClass hidden = ArgmaxClassIn(grid, moved);
    if (cue_hidden) {
      EXPECT_EQ(hidden, GridClass::kCyclist);
    } else {
      EXPECT_EQ(hidden, GridClass::kVehicle);
    }
  }
}

// The extent cue reads the scan's hits: a tracked cyclist (1.8 x 0.6 m) whose whole footprint
// the grid holds occupied, seen on its near side only, fills about one box side of hits (a
// cyclist's or a walker's), not its footprint's 48 cells (3.7 box sides, a car's). Its speed,
// 5 m/s, rules out a walker; the cue must not rule out a cyclist.
TEST(ExtendedGridTest, TheExtentCueCountsTheScansHitsNotTheTrackedFootprint) {
  ExtendedGrid grid(Geometry(48, 24));
  const auto& g = grid.geometry();
  const double vx = 5.0;
  const BoxM footprint{1.2, 1.5, 1.8, 0.6};
  HoldFootprint(grid, footprint, vx);
  // The next scan: the near side (the lowest row) hit where the body has moved, the rest of
  // the footprint behind it unknown, everything else free.
  const BoxM moved{footprint.x0_m + vx * kDtS, footprint.y0_m, footprint.width_m,
                   footprint.height_m};
  MeasurementGrid z = Measure(g, {BoxM{moved.x0_m, moved.y0_m, moved.width_m, kCellM}});
  for (int y = 0; y < g.height(); ++y) {
    for (int x = 0; x < g.width(); ++x) {
      const Eigen::Vector2d c = g.CellCenterM(g.GlobalFromLocal({x, y}));
      if (c.x() >= moved.x0_m && c.x() < moved.x0_m + moved.width_m &&
          c.y() >= moved.y0_m + kCellM && c.y() < moved.y0_m + moved.height_m) {
        z.p_occupied[g.StorageIndexOfLocal({x, y})] = kUnknownProbability;
      }
    }
  }
  z.touched.clear();
  for (std::size_t i = 0; i < z.p_occupied.size(); ++i) {
    if (z.p_occupied[i] != kUnknownProbability) z.touched.push_back(i);
  }
  grid.Update(z, kDtS);
  EXPECT_EQ(ArgmaxClassIn(grid, BoxM{moved.x0_m, moved.y0_m, moved.width_m, kCellM}),
            GridClass::kCyclist);
}

TEST(ExtendedGridTest, StereoEvidenceShiftsTheClass) {
  const std::vector<BoxM> world = {BoxM{1.5, 1.5, 0.45, 0.45}};
  ExtendedGrid grid(Geometry(24, 24));
  for (int k = 0; k < 3; ++k) grid.Update(Measure(grid.geometry(), world), kDtS);
  StereoClassRegion region;
  region.polygon_m = {{1.4, 1.4}, {2.1, 1.4}, {2.1, 2.1}, {1.4, 2.1}};
  region.likelihood = {0.05f, 0.9f, 0.05f, 0.05f, 0.2f};
  grid.SetStereoClassEvidence({region});
  grid.Update(Measure(grid.geometry(), world), kDtS);
  EXPECT_EQ(ArgmaxClassIn(grid, world[0]), GridClass::kPedestrian);
}

TEST(FilterOptionsTest, ValidateNamesTheField) {
  FilterOptions options;
  EXPECT_NO_THROW(options.Validate());
  options.window_size_cells = 6;
  try {
    options.Validate("test");
    FAIL() << "even window accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("window_size_cells"), std::string::npos);
  }
  options = {};
  options.unobserved_mover_speed_mps = std::numeric_limits<double>::quiet_NaN();
  try {
    options.Validate("test");
    FAIL() << "NaN speed accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unobserved_mover_speed_mps"), std::string::npos);
  }
  options.unobserved_mover_speed_mps = -1.0;
  EXPECT_THROW(options.Validate(), InputError);
}

}  // namespace
}  // namespace lookout::grid
