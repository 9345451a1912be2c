// One tracker step on the tracking issue's benchmark scene (tracking/benchmark_scene.h): 30
// targets (cars, cyclists, pedestrians), 10 false objects a scan, 10 Hz. The MHT with m = 10
// global hypotheses and N = 3 scans, and the GNN baseline, each timed on the scan after 2 s of
// tracking (a steady state: every target tracked, hypotheses branched); each repetition steps a
// fresh copy of the same state, and copying is not timed. Figures in docs/PERFORMANCE.md.

#include <benchmark/benchmark.h>

#include "lookout/tracking/benchmark_scene.h"
#include "lookout/tracking/gnn_tracker.h"
#include "lookout/tracking/mht_tracker.h"

namespace lookout::tracking {
namespace {

constexpr int kWarmUpScans = 20;

const BenchmarkScene& Scene() {
  static const BenchmarkScene scene = MakeBenchmarkScene(30, 10, kWarmUpScans + 1, 20261201);
  return scene;
}

MhtOptions BenchOptions(int m, int n) {
  MhtOptions o;
  o.hypotheses_m = m;
  o.n_scan = n;
  o.clutter_density_per_m2 = Scene().clutter_density_per_m2;
  o.new_track_density_per_m2 = 2.0 * Scene().clutter_density_per_m2;
  return o;
}

template <typename T>
void TimeStep(benchmark::State& s, const T& warm) {
  const BenchmarkScene& scene = Scene();
  for (auto _ : s) {
    s.PauseTiming();
    T tracker = warm;
    s.ResumeTiming();
    tracker.Step(scene.stamps[kWarmUpScans], scene.scans[kWarmUpScans]);
    benchmark::DoNotOptimize(tracker.ConfirmedTracks().size());
  }
}

template <typename T>
T WarmedUp(T tracker) {
  for (int k = 0; k < kWarmUpScans; ++k) {
    tracker.Step(Scene().stamps[static_cast<std::size_t>(k)],
                 Scene().scans[static_cast<std::size_t>(k)]);
  }
  return tracker;
}

void BM_MhtStep(benchmark::State& s) {
  const MhtTracker warm = WarmedUp(
      MhtTracker(BenchOptions(static_cast<int>(s.range(0)), static_cast<int>(s.range(1)))));
  TimeStep(s, warm);
  s.counters["hypotheses"] = static_cast<double>(warm.HypothesisProbabilities().size());
  s.counters["track_hypotheses"] = static_cast<double>(warm.TrackHypothesisCount());
  s.counters["confirmed"] = static_cast<double>(warm.ConfirmedTracks().size());
}
BENCHMARK(BM_MhtStep)->Args({10, 3})->Args({1, 3})->Args({30, 3})->Unit(benchmark::kMillisecond);

void BM_GnnStep(benchmark::State& s) {
  const GnnTracker warm = WarmedUp(GnnTracker());
  TimeStep(s, warm);
  s.counters["confirmed"] = static_cast<double>(warm.ConfirmedTracks().size());
}
BENCHMARK(BM_GnnStep)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lookout::tracking
