// One risk step (seed 004 section VIII): the ego and 30 tracks, 5 s horizon at 0.1 s, 1000
// Monte Carlo samples per track: the benchmark and `lookout bench`'s risk figure.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "lookout/core/random.h"
#include "lookout/risk/risk_assessment.h"

namespace lookout::risk {
namespace {

// 30 road users around a junction: cars on the four arms, cyclists, pedestrians on the
// crosswalks, each with a track covariance; seeded, so every run measures the same scene.
std::vector<ObjectInput> JunctionTracks(int count) {
  Rng rng(20261122);
  std::vector<ObjectInput> out;
  for (int i = 0; i < count; ++i) {
    ObjectInput o;
    o.id = static_cast<std::uint32_t>(i);
    const int kind = i % 3;
    o.object_class = kind == 0 ? ObjectClass::kCar
                     : kind == 1 ? ObjectClass::kCyclist
                                 : ObjectClass::kPedestrian;
    const double heading = rng.Uniform(-3.14159, 3.14159);
    const double speed = kind == 0 ? rng.Uniform(5.0, 15.0) : kind == 1 ? rng.Uniform(3.0, 7.0)
                                                                         : rng.Uniform(0.5, 2.0);
    o.position_m = {rng.Uniform(-5.0, 60.0), rng.Uniform(-20.0, 20.0)};
    o.velocity_mps = speed * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    o.position_covariance = Eigen::Matrix2d::Identity() * rng.Uniform(0.01, 0.5);
    o.velocity_covariance = Eigen::Matrix2d::Identity() * rng.Uniform(0.01, 1.0);
    out.push_back(o);
  }
  return out;
}

void BM_RiskStep(benchmark::State& state) {
  RiskOptions options;
  options.collision_samples = static_cast<int>(state.range(1));
  const std::vector<ObjectInput> tracks = JunctionTracks(static_cast<int>(state.range(0)));
  EgoInput ego;
  ego.speed_mps = 11.1;
  ego.yaw_rate_radps = 0.05;
  for (auto _ : state) {
    benchmark::DoNotOptimize(AssessRisk(ego, tracks, options));
  }
  state.counters["tracks"] = static_cast<double>(tracks.size());
}
BENCHMARK(BM_RiskStep)->Args({30, 1000})->Args({30, 0})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lookout::risk
