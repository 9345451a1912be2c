// Objects out of the extended grid (grid/grid_objects.h): one ExtractGridObjects on the 400 x 400
// grid of 0.15 m cells (60 m x 60 m), the size of the pipeline's grid. Figures go in
// docs/PERFORMANCE.md.
//
// The state is seeded, not filtered, so the benchmark measures the extraction alone and its
// input is exactly known: occupancy 0.9 on a junction's static structure (four building fronts
// along the roads, 1.2 m deep; parked cars), every cell with a rigidity link, and Arg movers
// (4.5 m x 1.8 m boxes, 360 cells each, tracked at 8 m/s in varied directions) spread over the
// window. Everything else holds the priors. Cost: one pass over the window for the dynamic
// mask, one for the search, then the movers' cells (hull and moments).

#include <benchmark/benchmark.h>

#include <cmath>

#include "lookout/grid/extended_grid.h"
#include "lookout/grid/grid_objects.h"

namespace lookout::grid {
namespace {

using Eigen::Vector2d;

constexpr int kSide = 400;
constexpr double kCellM = 0.15;

void Fill(ExtendedGrid& grid, const Vector2d& lo, const Vector2d& hi, const Vector2d& v) {
  const ScrollingGridGeometry& g = grid.geometry();
  GridLayers& layers = grid.mutable_layers();
  const FilterLayerIds& ids = grid.ids();
  const CellIndex a = g.GlobalCellAt(lo), b = g.GlobalCellAt(hi);
  for (int y = a.iy; y < b.iy; ++y) {
    for (int x = a.ix; x < b.ix; ++x) {
      if (!g.Contains({x, y})) continue;
      const std::size_t i = g.StorageIndex({x, y});
      layers.Values(ids.occupancy)[i] = 0.9f;
      layers.Values(ids.velocity_x_mps)[i] = static_cast<float>(v.x());
      layers.Values(ids.velocity_y_mps)[i] = static_cast<float>(v.y());
      layers.Values(ids.velocity_confidence)[i] = 0.9f;
      for (const LayerId d : ids.rigidity) layers.Values(d)[i] = 0.3f;
    }
  }
}

ExtendedGrid Scene(int movers) {
  ExtendedGrid grid(ScrollingGridGeometry(kCellM, kSide, kSide, {-kSide / 2, -kSide / 2}));
  const Vector2d zero = Vector2d::Zero();
  for (const double s : {-1.0, 1.0}) {  // building fronts along both roads
    Fill(grid, Vector2d(-30.0, 10.0 * s - 0.6), Vector2d(-10.0, 10.0 * s + 0.6), zero);
    Fill(grid, Vector2d(10.0, 10.0 * s - 0.6), Vector2d(30.0, 10.0 * s + 0.6), zero);
    Fill(grid, Vector2d(10.0 * s - 0.6, -30.0), Vector2d(10.0 * s + 0.6, -10.0), zero);
    Fill(grid, Vector2d(10.0 * s - 0.6, 10.0), Vector2d(10.0 * s + 0.6, 30.0), zero);
  }
  for (int k = 0; k < 8; ++k) {  // parked cars
    const double x = -28.0 + 7.0 * k;
    Fill(grid, Vector2d(x, 6.5), Vector2d(x + 4.5, 8.3), zero);
  }
  // Movers on a 7 x 8 lattice of slots over the window, 4.5 m x 1.8 m each.
  for (int m = 0; m < movers; ++m) {
    const double x = -27.0 + 7.5 * (m % 7), y = -27.0 + 7.0 * (m / 7);
    const double heading = 0.7 * m;
    Fill(grid, Vector2d(x, y), Vector2d(x + 4.5, y + 1.8),
         8.0 * Vector2d(std::cos(heading), std::sin(heading)));
  }
  return grid;
}

void BM_ExtractGridObjects(benchmark::State& state) {
  const int movers = static_cast<int>(state.range(0));
  const ExtendedGrid grid = Scene(movers);
  ObjectFrameContext context;
  context.ego_pose = Pose2(1.0, -2.0, 0.3);
  context.lidar_mount = Pose2(2.2, 0.0, 0.0);
  const GridObjectOptions options;
  std::size_t objects = 0;
  for (auto _ : state) {
    const LidarObjectFrame frame = ExtractGridObjects(grid, context, options);
    objects = frame.objects.size();
    benchmark::DoNotOptimize(frame.objects.data());
  }
  state.counters["objects"] = static_cast<double>(objects);
  state.counters["cells_per_s"] = benchmark::Counter(
      static_cast<double>(grid.geometry().CellCount()) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ExtractGridObjects)->Arg(0)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace lookout::grid
