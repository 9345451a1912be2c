// The extended grid's foundation: the inverse sensor model (docs/extended-grid.md step 1) on a
// 641-beam scan in the 400 x 400 grid of 0.15 m cells, and moving the scrolling window (a
// circular buffer) against the naive alternative of copying every layer. Figures go in
// docs/PERFORMANCE.md.
//
// Two scans: a synthetic one, ray cast here against an analytic four-way junction (building
// blocks on the corners, parked cars, poles, pedestrians), which stays fixed whatever the
// simulator becomes; and the simulator's own lidar frame on its four_way world with traffic.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench_scans.h"
#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/grid/grid_options.h"
#include "lookout/grid/inverse_sensor_model.h"
#include "lookout/grid/scrolling_grid.h"
#include "lookout/sim/scenario.h"
#include "lookout/sim/simulator.h"

namespace lookout::grid {
namespace {

using Eigen::Vector2d;

// A four-way junction centred on the origin: roads 20 m wide between building faces, cars
// parked along the kerbs and queued at the stop lines, poles at the corners, pedestrians on
// the sidewalks.
std::vector<sim::Shape> MakeJunction() {
  std::vector<sim::Shape> j;
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      const Vector2d corner(10.0 * sx, 10.0 * sy);
      const Vector2d far(200.0 * sx, 200.0 * sy);
      j.push_back(bench::AxisBox(corner.cwiseMin(far), corner.cwiseMax(far)));
      j.push_back(sim::Shape::Circle(Vector2d(10.8 * sx, 10.8 * sy), 0.15, sim::kStaticOwner));
      j.push_back(sim::Shape::Circle(Vector2d(14.0 * sx, 8.5 * sy), 0.3, sim::kStaticOwner));
    }
  }
  for (int k = 0; k < 6; ++k) {  // parked cars along the west and east arms, north kerb
    const double x = -45.0 + 6.0 * k + (k >= 3 ? 58.0 : 0.0);
    j.push_back(bench::AxisBox(Vector2d(x, 6.0), Vector2d(x + 4.5, 7.8)));
  }
  j.push_back(bench::AxisBox(Vector2d(-8.0, 0.3), Vector2d(-3.5, 2.1)));    // queued, oncoming
  j.push_back(bench::AxisBox(Vector2d(3.0, -9.5), Vector2d(4.8, -5.0)));    // on the south arm
  j.push_back(bench::AxisBox(Vector2d(-2.1, 12.0), Vector2d(-0.3, 16.5)));  // on the north arm
  return j;
}

// The default lidar (641 beams over 160 deg at 0.25 deg, 150 m) on an ego 20 m west of the
// junction centre heading east, mounted 2.2 m ahead of the footprint centre. Every 211th beam
// is a dropout (+inf), as the simulator's 0.5 % rate would give about three per scan.
struct BenchScene {
  LidarScan scan;
  Pose2 ego_pose;
  Pose2 sensor_pose;
};

BenchScene MakeScene() {
  BenchScene s;
  s.ego_pose = Pose2(-20.0, -1.75, 0.0);
  s.scan.mount = Pose2(2.2, 0.0, 0.0);
  s.sensor_pose = s.ego_pose * s.scan.mount;
  s.scan = bench::CastDefaultScan(MakeJunction(), s.sensor_pose, s.scan.mount);
  for (std::size_t i = 100; i < s.scan.ranges_m.size(); i += 211) {
    s.scan.ranges_m[i] = std::numeric_limits<float>::infinity();  // dropouts
  }
  return s;
}

// Steady state: one MeasurementGrid reused scan after scan (the pipeline's way).
void MeasureInverseSensorModel(benchmark::State& state, const BenchScene& scene) {
  const GridOptions options;
  const ScrollingGridGeometry geometry(options, scene.ego_pose.translation);
  MeasurementGrid out;
  for (auto _ : state) {
    ComputeInverseSensorModel(scene.scan, scene.sensor_pose, geometry, options.inverse_sensor_model,
                              out);
    benchmark::DoNotOptimize(out.p_occupied.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(scene.scan.ranges_m.size()));
  state.counters["cell_visits"] = static_cast<double>(out.stats.cell_visits);
  state.counters["touched_cells"] = static_cast<double>(out.touched.size());
  state.counters["hit_beams"] = out.stats.hit_beams;
  state.SetLabel("items = beams");
}

void BM_InverseSensorModel(benchmark::State& state) {
  MeasureInverseSensorModel(state, MakeScene());
}
BENCHMARK(BM_InverseSensorModel)->Unit(benchmark::kMicrosecond);

// The pure function: allocates and fills the 160,000-cell grid each call.
void BM_InverseSensorModelFresh(benchmark::State& state) {
  const BenchScene scene = MakeScene();
  const GridOptions options;
  const ScrollingGridGeometry geometry(options, scene.ego_pose.translation);
  for (auto _ : state) {
    MeasurementGrid out = ComputeInverseSensorModel(scene.scan, scene.sensor_pose, geometry,
                                                    options.inverse_sensor_model);
    benchmark::DoNotOptimize(out.p_occupied.data());
  }
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(scene.scan.ranges_m.size()));
  state.SetLabel("items = beams");
}
BENCHMARK(BM_InverseSensorModelFresh)->Unit(benchmark::kMicrosecond);

sim::ActorSpec Actor(std::string id, ObjectClass c, std::vector<Vector2d> path, double speed_mps) {
  sim::ActorSpec a;
  a.id = std::move(id);
  a.object_class = c;
  a.path = std::move(path);
  a.speed = sim::SpeedProfile::Constant(speed_mps);
  a.stop_s = 12.0;
  return a;
}

// The built-in default scenario (left-turn-across-path: ego east at 11.1 m/s through the
// four_way junction) with 16 more cars and pedestrians on the four arms. Lidar frame 50 (4 s):
// the ego is 16 m before the junction centre, the junction inside the 60 m grid.
BenchScene SimulatedScene() {
  sim::Scenario s;
  s.name = "left-turn-across-path-with-traffic";
  s.duration_s = 12.0;
  s.seed = 7;
  s.world.preset = "four_way";
  s.ego.path = {{-60, -1.75}, {60, -1.75}};
  s.ego.speed = sim::SpeedProfile::Constant(11.1);
  s.actors.push_back(
      Actor("car1", ObjectClass::kCar, {{45, 1.75}, {5, 1.75}, {-1.75, -5}, {-1.75, -60}}, 8.0));
  for (int i = 0; i < 16; ++i) {
    const Pose2 arm(0.0, 0.0, 0.5 * kPi * (i % 4));
    const double back = 15.0 + 8.0 * (i / 4);
    const std::string id = "extra" + std::to_string(i);
    if (i % 3 == 2) {
      s.actors.push_back(Actor(id, ObjectClass::kPedestrian,
                               {arm * Vector2d(back, 4.8), arm * Vector2d(-60.0, 4.8)}, 1.4));
    } else {
      s.actors.push_back(Actor(id, ObjectClass::kCar,
                               {arm * Vector2d(back, 1.75), arm * Vector2d(-80.0, 1.75)}, 7.0));
    }
  }
  const sim::Simulator simulator(s);
  BenchScene scene;
  scene.scan = simulator.SimulateLidar(50);
  scene.ego_pose = simulator.ego_trajectory().At(ToSeconds(scene.scan.stamp)).pose;
  scene.sensor_pose = scene.ego_pose * scene.scan.mount;
  return scene;
}

void BM_InverseSensorModelSimulated(benchmark::State& state) {
  MeasureInverseSensorModel(state, SimulatedScene());
}
BENCHMARK(BM_InverseSensorModelSimulated)->Unit(benchmark::kMicrosecond);

constexpr int kLayers = 16;  // about what the full filter carries (occupancy, velocity, class...)

GridLayers MakeLayers() {
  GridLayers layers(ScrollingGridGeometry(GridOptions{}));
  for (int k = 0; k < kLayers; ++k) layers.Add("layer" + std::to_string(k), 0.5f);
  return layers;
}

// Moving the window by `shift` cells diagonally, back and forth, resetting the new cells of
// 16 layers. 11 m/s at 12.5 Hz is 6 cells of 0.15 m per scan; 400 is a jump past the window.
void BM_Recenter(benchmark::State& state) {
  const int shift = static_cast<int>(state.range(0));
  GridLayers layers = MakeLayers();
  const double step_m = shift * 0.15;
  bool forward = true;
  for (auto _ : state) {
    const double x = forward ? step_m : 0.0;
    VacatedCells v = layers.Recenter(Vector2d(x + 0.01, x + 0.01));
    forward = !forward;
    benchmark::DoNotOptimize(v);
    benchmark::ClobberMemory();
  }
  state.SetLabel("16 layers, 400 x 400");
}
BENCHMARK(BM_Recenter)->Arg(1)->Arg(6)->Arg(50)->Arg(400)->Unit(benchmark::kMicrosecond);

// The naive alternative the circular buffer avoids: shift every layer by copying each cell
// into a second buffer (and resetting the new ones), for the same moves.
void BM_ShiftByCopy(benchmark::State& state) {
  const int shift = static_cast<int>(state.range(0));
  const int n = 400;
  std::vector<std::vector<float>> layers(kLayers, std::vector<float>(n * n, 0.5f));
  std::vector<float> scratch(n * n);
  bool forward = true;
  for (auto _ : state) {
    const int d = forward ? shift : -shift;
    for (auto& layer : layers) {
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          const int sx = x + d;
          const int sy = y + d;
          const bool inside = sx >= 0 && sx < n && sy >= 0 && sy < n;
          scratch[static_cast<std::size_t>(y * n + x)] =
              inside ? layer[static_cast<std::size_t>(sy * n + sx)] : 0.5f;
        }
      }
      layer.swap(scratch);
    }
    forward = !forward;
    benchmark::ClobberMemory();
  }
  state.SetLabel("16 layers, 400 x 400");
}
BENCHMARK(BM_ShiftByCopy)->Arg(6)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace lookout::grid
