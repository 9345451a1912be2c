// One risk step (seed 004 section VIII): the ego and 30 tracks, 5 s horizon at 0.1 s, 1000
// Monte Carlo samples per track: the benchmark and `lookout bench`'s risk figure.
#include <benchmark/benchmark.h>

#include <vector>

#include "lookout/risk/junction_scene.h"

namespace lookout::risk {
namespace {

void BM_RiskStep(benchmark::State& state) {
  RiskOptions options;
  options.collision_samples = static_cast<int>(state.range(1));
  const std::vector<ObjectInput> tracks =
      JunctionRoadUsers(static_cast<int>(state.range(0)), 20261122);
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
