// Ray casting and sensor simulation speed. The goal these hold: the default scenario's
// sensors simulate at least 200x faster than real time on one core (BM_RunScenario's
// sim_s_per_wall_s counter). Figures go in docs/PERFORMANCE.md.

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "lookout/core/pose2.h"
#include "lookout/io/scenario_loader.h"
#include "lookout/sim/lidar_sensor.h"
#include "lookout/sim/raycast.h"
#include "lookout/sim/scenario.h"
#include "lookout/sim/simulator.h"
#include "lookout/sim/world_builder.h"

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

// Cars queued on the four approaches (both lanes, every 9 m from 8 m out) and pedestrians on
// the sidewalks: `count` actors around the four_way junction, indices 0..count-1.
std::vector<Shape> JunctionActors(int count) {
  std::vector<Shape> shapes;
  for (int i = 0; i < count; ++i) {
    const double arm = 0.5 * kPi * (i % 4);  // east, north, west, south
    const int rank = i / 4;
    const Pose2 arm_frame(0.0, 0.0, arm);
    if (i % 3 == 2) {  // a pedestrian on the arm's sidewalk
      const Vector2d p(7.0 + 6.0 * rank, (rank % 2 == 0 ? 1.0 : -1.0) * 4.8);
      shapes.push_back(Shape::Circle(arm_frame * p, 0.3, i));
    } else {
      const Vector2d p(8.0 + 9.0 * (rank / 2), (rank % 2 == 0 ? 1.0 : -1.0) * 1.75);
      shapes.push_back(Shape::Box(Pose2(arm_frame * p, arm + (rank % 2 == 0 ? kPi : 0.0)), 4.5,
                                  1.8, i));
    }
  }
  return shapes;
}

struct LidarWorld {
  std::vector<Shape> static_world;
  std::vector<Shape> actors;
  Fan fan;
};

// The default lidar on an ego 20 m west of the junction centre, heading east.
LidarWorld FourWayWithActors(int actor_count) {
  World world;
  world.preset = "four_way";
  return {BuildStaticWorld(world), JunctionActors(actor_count),
          LidarFan(LidarOptions{}, Pose2(-20.0, -1.75, 0.0))};
}

void BM_CastLidarFan(benchmark::State& state) {
  const int actors = static_cast<int>(state.range(0));
  const LidarWorld w = FourWayWithActors(actors);
  for (auto _ : state) {
    FanHits hits = CastFan(w.fan, w.static_world, w.actors, actors);
    benchmark::DoNotOptimize(hits);
  }
  state.SetItemsProcessed(state.iterations() * w.fan.count);
  state.SetLabel("beams");
}
BENCHMARK(BM_CastLidarFan)->Arg(0)->Arg(30);

// The literal reference, one ray against every shape: what CastFan's angular culling saves.
void BM_CastLidarFanBruteForce(benchmark::State& state) {
  const int actors = static_cast<int>(state.range(0));
  const LidarWorld w = FourWayWithActors(actors);
  std::vector<Shape> all = w.static_world;
  all.insert(all.end(), w.actors.begin(), w.actors.end());
  for (auto _ : state) {
    for (int i = 0; i < w.fan.count; ++i) {
      RayHit hit = CastRayBruteForce(w.fan.origin_m, w.fan.BeamDirection(i),
                                     w.fan.max_range_m, all);
      benchmark::DoNotOptimize(hit);
    }
  }
  state.SetItemsProcessed(state.iterations() * w.fan.count);
  state.SetLabel("beams");
}
BENCHMARK(BM_CastLidarFanBruteForce)->Arg(30);

ActorSpec Actor(std::string id, ObjectClass c, std::vector<Vector2d> path, double speed_mps,
                double duration_s) {
  ActorSpec a;
  a.id = std::move(id);
  a.object_class = c;
  a.path = std::move(path);
  a.speed = SpeedProfile::Constant(speed_mps);
  a.stop_s = duration_s;
  return a;
}

// The built-in default scenario (scenarios/left-turn-across-path.yaml); `extra_actors` adds
// traffic through the junction.
Scenario DefaultLikeScenario(int extra_actors) {
  Scenario s = io::LoadDefaultScenario();
  for (int i = 0; i < extra_actors; ++i) {
    const Pose2 arm(0.0, 0.0, 0.5 * kPi * (i % 4));
    const double back = 15.0 + 8.0 * (i / 4);
    const std::string id = "extra" + std::to_string(i);
    if (i % 3 == 2) {
      s.actors.push_back(Actor(id, ObjectClass::kPedestrian,
                               {arm * Vector2d(back, 4.8), arm * Vector2d(-60.0, 4.8)}, 1.4,
                               12.0));
    } else {
      s.actors.push_back(Actor(id, ObjectClass::kCar,
                               {arm * Vector2d(back, 1.75), arm * Vector2d(-80.0, 1.75)}, 7.0,
                               12.0));
    }
  }
  return s;
}

void BM_SimulateLidarFrame(benchmark::State& state) {
  const Simulator sim(DefaultLikeScenario(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    LidarScan scan = sim.SimulateLidar(50);
    benchmark::DoNotOptimize(scan);
  }
}
BENCHMARK(BM_SimulateLidarFrame)->Arg(0)->Arg(29);

void BM_SimulateStereoFrame(benchmark::State& state) {
  const Simulator sim(DefaultLikeScenario(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    StereoFrame frame = sim.SimulateStereo(80);
    benchmark::DoNotOptimize(frame);
  }
}
BENCHMARK(BM_SimulateStereoFrame)->Arg(0)->Arg(29);

void BM_Truth(benchmark::State& state) {
  const Simulator sim(DefaultLikeScenario(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    TruthFrame truth = sim.Truth(4 * kNanosPerSecond);
    benchmark::DoNotOptimize(truth);
  }
}
BENCHMARK(BM_Truth)->Arg(0)->Arg(29);

// Every sensor frame and truth frame of the 12 s scenario on one thread. The counter is
// simulated seconds per wall-clock second (the real-time factor).
void BM_RunScenario(benchmark::State& state) {
  const Simulator sim(DefaultLikeScenario(static_cast<int>(state.range(0))));
  for (auto _ : state) {
    SensorLog log = sim.Run(1);
    benchmark::DoNotOptimize(log);
  }
  state.counters["sim_s_per_wall_s"] = benchmark::Counter(
      sim.scenario().duration_s * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RunScenario)->Arg(0)->Arg(29)->Unit(benchmark::kMillisecond)->UseRealTime();

// Building the simulator: trajectories and contact times, paid once per scenario.
void BM_ConstructSimulator(benchmark::State& state) {
  const Scenario scenario = DefaultLikeScenario(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    Simulator sim(scenario);
    benchmark::DoNotOptimize(sim);
  }
}
BENCHMARK(BM_ConstructSimulator)->Arg(0)->Arg(29)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lookout::sim
