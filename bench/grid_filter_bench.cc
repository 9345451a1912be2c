// The extended grid's filter (docs/extended-grid.md steps 2-8): one ExtendedGrid::Update of the
// 400 x 400 grid of 0.15 m cells (60 m x 60 m) on a junction scene, M = 7, against the slow
// literal reference of steps 2-7 (reference_filter.h) side by side on the same input, and on a
// 100 x 100 window of the same scene. Figures go in docs/PERFORMANCE.md.
//
// The scene: an analytic four-way junction (building blocks on the corners, parked and queued
// cars, poles, pedestrians; as grid_foundation_bench.cc) with traffic: a car ahead of the ego at
// 10 m/s, a car crossing at 15 m/s, an oncoming car at 12 m/s, two pedestrians crossing at
// 1.5 m/s. A 641-beam 160 deg lidar 20 m west of the junction centre, 12.5 Hz. The filter is
// warmed up for 25 scans, so the timed update sees a steady state (tracked static structure,
// tracked movers, newly revealed occupancy at their edges), as on the road.

#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "bench_scans.h"
#include "lookout/app/stage_benchmarks.h"
#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/grid/association_prediction.h"
#include "lookout/grid/cluster_motion.h"
#include "lookout/grid/extended_grid.h"
#include "lookout/grid/inverse_sensor_model.h"
#include "lookout/grid/measurement_weighting.h"
#include "lookout/grid/reference_filter.h"
#include "lookout/grid/scrolling_grid.h"
#include "lookout/io/scenario_loader.h"

namespace lookout::grid {
namespace {

using Eigen::Vector2d;

constexpr double kDtS = 0.08;
constexpr int kWarmupScans = 25;

struct Mover {
  Vector2d lo, hi;  // the box at t = 0
  Vector2d velocity_mps;
};

std::vector<sim::Shape> StaticBoxes() {
  std::vector<sim::Shape> boxes;
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      const Vector2d corner(10.0 * sx, 10.0 * sy);
      const Vector2d far(200.0 * sx, 200.0 * sy);
      boxes.push_back(bench::AxisBox(corner.cwiseMin(far), corner.cwiseMax(far)));
      const Vector2d pole(10.8 * sx, 10.8 * sy);
      boxes.push_back(bench::AxisBox(pole - Vector2d(0.15, 0.15), pole + Vector2d(0.15, 0.15)));
    }
  }
  for (int k = 0; k < 6; ++k) {
    const double x = -45.0 + 6.0 * k + (k >= 3 ? 58.0 : 0.0);
    boxes.push_back(bench::AxisBox(Vector2d(x, 6.0), Vector2d(x + 4.5, 7.8)));
  }
  boxes.push_back(bench::AxisBox(Vector2d(-8.0, 0.3), Vector2d(-3.5, 2.1)));
  boxes.push_back(bench::AxisBox(Vector2d(3.0, -9.5), Vector2d(4.8, -5.0)));
  return boxes;
}

std::vector<Mover> Movers() {
  return {
      {Vector2d(-14.0, -3.6), Vector2d(-9.5, -1.8), Vector2d(10.0, 0.0)},  // ahead of the ego
      {Vector2d(0.8, -26.0), Vector2d(2.6, -21.5), Vector2d(0.0, 15.0)},   // crossing
      {Vector2d(12.0, 2.3), Vector2d(16.5, 4.1), Vector2d(-12.0, 0.0)},    // oncoming
      {Vector2d(-6.0, 11.0), Vector2d(-5.5, 11.5), Vector2d(1.5, 0.0)},    // pedestrians
      {Vector2d(6.0, -11.5), Vector2d(6.5, -11.0), Vector2d(-1.5, 0.0)},
  };
}

LidarScan ScanAt(int k, const Pose2& sensor_pose) {
  std::vector<sim::Shape> shapes = StaticBoxes();
  for (const Mover& m : Movers()) {
    const Vector2d shift = m.velocity_mps * (k * kDtS);
    shapes.push_back(bench::AxisBox(m.lo + shift, m.hi + shift));
  }
  return bench::CastDefaultScan(shapes, sensor_pose, Pose2(2.2, 0.0, 0.0));
}

// A warmed-up grid of `side` cells centred on the junction and the next measurement.
struct WarmGrid {
  ExtendedGrid grid;
  MeasurementGrid next;
};

WarmGrid Warm(int side_cells) {
  const Pose2 sensor_pose = Pose2(-20.0, -1.75, 0.0) * Pose2(2.2, 0.0, 0.0);
  const ScrollingGridGeometry geometry(0.15, side_cells, side_cells,
                                       CellIndex{-side_cells / 2, -side_cells / 2});
  WarmGrid w{ExtendedGrid(geometry), MeasurementGrid{}};
  const InverseSensorModelOptions ism;
  for (int k = 0; k < kWarmupScans; ++k) {
    w.grid.Update(ComputeInverseSensorModel(ScanAt(k, sensor_pose), sensor_pose, geometry, ism),
                  kDtS);
  }
  w.next = ComputeInverseSensorModel(ScanAt(kWarmupScans, sensor_pose), sensor_pose, geometry, ism);
  return w;
}

void Counters(benchmark::State& state, const ExtendedGrid& after) {
  const auto& s = after.last_stats();
  state.counters["sources"] = static_cast<double>(s.sources);
  state.counters["associations"] = static_cast<double>(s.associations);
  state.counters["updated_cells"] = static_cast<double>(s.updated_cells);
  // Cell-updates per second over the whole window (what the paper's GPU figure counts).
  state.counters["cell_updates_per_s"] = benchmark::Counter(
      static_cast<double>(after.geometry().CellCount()) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
  state.counters["sources_per_s"] =
      benchmark::Counter(static_cast<double>(s.sources) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
}

// One update of the full 400 x 400 grid; Arg = TBB threads.
void BM_ExtendedGridUpdate(benchmark::State& state) {
  static const WarmGrid warm = Warm(400);
  tbb::task_arena arena(static_cast<int>(state.range(0)));
  ExtendedGrid grid = warm.grid;
  for (auto _ : state) {
    state.PauseTiming();
    grid = warm.grid;
    state.ResumeTiming();
    arena.execute([&] { grid.Update(warm.next, kDtS); });
  }
  Counters(state, grid);
}
BENCHMARK(BM_ExtendedGridUpdate)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The literal reference on the same 400 x 400 input, side by side with BM_ExtendedGridUpdate.
void MeasureReferenceUpdate(benchmark::State& state, const WarmGrid& warm) {
  GridLayers layers = warm.grid.layers();
  for (auto _ : state) {
    state.PauseTiming();
    layers = warm.grid.layers();
    state.ResumeTiming();
    ReferenceUpdate(layers, warm.grid.ids(), warm.next, kDtS, warm.grid.options());
  }
  ExtendedGrid after = warm.grid;
  after.Update(warm.next, kDtS);
  Counters(state, after);
}

void BM_ReferenceUpdate(benchmark::State& state) {
  static const WarmGrid warm = Warm(400);
  MeasureReferenceUpdate(state, warm);
}
BENCHMARK(BM_ReferenceUpdate)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// The same pair on the simulator's junction (the default scenario at t = 4 s, the grid having
// run every earlier scan: the input of `lookout bench`): real scans give thousands of sources
// along the building walls. Arg = TBB threads; the output of every thread count is checked
// against the one-thread output, byte for byte (the benchmark fails if they differ).
const app::GridCycleInput& SimJunction() {
  static const app::GridCycleInput input = app::PrepareGridCycle(io::LoadDefaultScenario(), 4.0);
  return input;
}

std::vector<float> AllLayers(const ExtendedGrid& grid) {
  std::vector<float> out;
  const GridLayers& layers = grid.layers();
  for (int id = 0; id < layers.LayerCount(); ++id) {
    const auto v = layers.Values(LayerId{id});
    out.insert(out.end(), v.begin(), v.end());
  }
  return out;
}

// The timed call, out of line so that a profiler can count exactly the timed updates
// (valgrind --tool=callgrind --toggle-collect='*TimedSimJunctionUpdate*').
[[gnu::noinline]] void TimedSimJunctionUpdate(ExtendedGrid& grid,
                                              const app::GridCycleInput& input) {
  grid.Update(input.z, input.dt_s);
}

// Times the update of `input` on state.range(0) TBB threads, and fails the benchmark when its
// output differs from the one-thread output.
void TimeJunctionUpdates(benchmark::State& state, const app::GridCycleInput& input) {
  tbb::task_arena one(1);
  ExtendedGrid reference = input.before;
  one.execute([&] { reference.Update(input.z, input.dt_s); });
  tbb::task_arena arena(static_cast<int>(state.range(0)));
  ExtendedGrid grid = input.before;
  double motion_ms = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    grid = input.before;
    state.ResumeTiming();
    arena.execute([&] { TimedSimJunctionUpdate(grid, input); });
    motion_ms += grid.last_stats().motion_ms;
  }
  if (AllLayers(grid) != AllLayers(reference)) {
    state.SkipWithError("the output differs from the one-thread output");
    return;
  }
  Counters(state, grid);
  // The part of the update the literal reference computes too (BM_ReferenceUpdateSimJunction).
  state.counters["motion_ms"] = motion_ms / static_cast<double>(state.iterations());
}

void BM_ExtendedGridUpdateSimJunction(benchmark::State& state) {
  TimeJunctionUpdates(state, SimJunction());
}
BENCHMARK(BM_ExtendedGridUpdateSimJunction)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The same cycle without the scan pair's windows (grid/scan_flow.h, on by default;
// --grid-scan-flow off): what its measurement of every source that would get the wide window,
// and their fine windows after, cost.
void BM_ExtendedGridUpdateSimJunctionNoScanFlow(benchmark::State& state) {
  static const app::GridCycleInput input = [] {
    FilterOptions filter;
    filter.scan_flow.enabled = false;
    return app::PrepareGridCycle(io::LoadDefaultScenario(), 4.0, filter);
  }();
  TimeJunctionUpdates(state, input);
}
BENCHMARK(BM_ExtendedGridUpdateSimJunctionNoScanFlow)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The stage after step 7 alone (grid/cluster_motion.h: every rigid cluster measured whole from
// the scan pair), on the junction cycle's state after its steps 2-7: what it adds to the update.
void BM_ClusterMotionSimJunction(benchmark::State& state) {
  const app::GridCycleInput& input = SimJunction();
  ExtendedGrid after = input.before;
  after.Update(input.z, input.dt_s);
  ScanFlow flow = input.before.scan_flow();
  flow.Prepare(input.z);
  const FilterOptions& options = input.before.options();
  GridLayers layers = after.layers();
  for (auto _ : state) {
    state.PauseTiming();
    layers = after.layers();
    state.ResumeTiming();
    ApplyClusterMotion(layers, after.ids(), input.z, flow, input.dt_s, options.known_confidence,
                       options.cluster_motion);
  }
}
BENCHMARK(BM_ClusterMotionSimJunction)->Unit(benchmark::kMillisecond)->UseRealTime();

// The target index alone (filter_state.h: each entry filed under its target, in source order),
// on the junction cycle's associations: the serial part between steps 3 and 4.
void BM_TargetIndexSimJunction(benchmark::State& state) {
  const app::GridCycleInput& input = SimJunction();
  const ExtendedGrid& grid = input.before;
  ScanFlow flow = grid.scan_flow();
  flow.Prepare(input.z);
  const WindowIndexer indexer(grid.geometry());
  Associations associations = PredictAssociations(grid.layers(), grid.ids(), indexer, input.z,
                                                  input.dt_s, grid.options(), &flow);
  WeightByMeasurement(input.z, associations);
  FilterWorkspace workspace;
  workspace.Resize(grid.geometry().CellCount());
  std::size_t targets = 0;
  for (auto _ : state) {
    const TargetIndex index = BuildTargetIndex(associations, workspace);
    targets = index.targets.size();
    benchmark::DoNotOptimize(index.entries.data());
  }
  state.counters["entries"] = static_cast<double>(associations.EntryCount());
  state.counters["targets"] = static_cast<double>(targets);
}
BENCHMARK(BM_TargetIndexSimJunction)->Unit(benchmark::kMicrosecond)->UseRealTime();

// The literal reference of the same stages as the fast path's motion_ms, on the same scan pair
// (its preparation timed, as in the fast path).
void BM_ReferenceUpdateSimJunction(benchmark::State& state) {
  const app::GridCycleInput& input = SimJunction();
  GridLayers layers = input.before.layers();
  for (auto _ : state) {
    state.PauseTiming();
    layers = input.before.layers();
    ScanFlow flow = input.before.scan_flow();
    state.ResumeTiming();
    flow.Prepare(input.z);
    ReferenceUpdate(layers, input.before.ids(), input.z, input.dt_s, input.before.options(), &flow);
  }
  ExtendedGrid after = input.before;
  after.Update(input.z, input.dt_s);
  Counters(state, after);
}
BENCHMARK(BM_ReferenceUpdateSimJunction)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);

// The side-by-side pair on a 100 x 100 window (15 m, centred on the junction) of the same scene.
constexpr int kSmallSide = 100;

void BM_ExtendedGridUpdateSmall(benchmark::State& state) {
  static const WarmGrid warm = Warm(kSmallSide);
  tbb::task_arena arena(1);
  ExtendedGrid grid = warm.grid;
  for (auto _ : state) {
    state.PauseTiming();
    grid = warm.grid;
    state.ResumeTiming();
    arena.execute([&] { grid.Update(warm.next, kDtS); });
  }
  Counters(state, grid);
}
BENCHMARK(BM_ExtendedGridUpdateSmall)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ReferenceUpdateSmall(benchmark::State& state) {
  static const WarmGrid warm = Warm(kSmallSide);
  MeasureReferenceUpdate(state, warm);
}
BENCHMARK(BM_ReferenceUpdateSmall)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace
}  // namespace lookout::grid
