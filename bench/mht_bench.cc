// One tracker step on the tracking issue's benchmark scene (tracking/benchmark_scene.h): 30
// targets (cars, cyclists, pedestrians), 10 false objects a scan, 10 Hz. The MHT with m = 10
// global hypotheses and N = 3 scans, and the GNN baseline, each timed on the scan after 2 s of
// tracking (a steady state: every target tracked, hypotheses branched); each repetition steps a
// fresh copy of the same state, and copying is not timed. The MHT also with a lidar scan's view
// (tracking/scan_visibility.h: a 360-degree scan of 0.25-degree beams from the square's centre,
// walls 30 m out on half of them, hiding the targets behind), and the view's own cost. Figures
// in docs/PERFORMANCE.md.

#include <benchmark/benchmark.h>

#include <limits>
#include <vector>

#include "lookout/tracking/benchmark_scene.h"
#include "lookout/tracking/gnn_tracker.h"
#include "lookout/tracking/mht_tracker.h"
#include "lookout/tracking/scan_visibility.h"

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
void TimeStep(benchmark::State& s, const T& warm, const SensorView& view = OpenView{}) {
  const BenchmarkScene& scene = Scene();
  for (auto _ : s) {
    s.PauseTiming();
    T tracker = warm;
    s.ResumeTiming();
    tracker.Step(scene.stamps[kWarmUpScans], scene.scans[kWarmUpScans], view);
    benchmark::DoNotOptimize(tracker.ConfirmedTracks().size());
  }
}

// The scan: 1440 beams round the square's centre; beams in alternate 10-degree sectors stop at
// a wall 30 m out, the others return nothing.
LidarScan WalledScan() {
  LidarScan scan;
  scan.angle_min_rad = -kPi;
  scan.angle_increment_rad = 0.25 * kPi / 180.0;
  scan.max_range_m = 150.0;
  scan.ranges_m.resize(1440);
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    scan.ranges_m[i] = (i / 40) % 2 == 0 ? 30.0f : std::numeric_limits<float>::infinity();
  }
  return scan;
}

// Where the timed scan's detections lie: the view's overrule.
std::vector<Eigen::Vector2d> SceneDetectionPositions() {
  std::vector<Eigen::Vector2d> out;
  for (const Detection& d : Scene().scans[kWarmUpScans]) out.push_back(d.position_m);
  return out;
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

void BM_MhtStepWithScanView(benchmark::State& s) {
  const MhtTracker warm = WarmedUp(MhtTracker(BenchOptions(10, 3)));
  TimeStep(s, warm, ScanVisibility(WalledScan(), Pose2{}, {}, SceneDetectionPositions()));
}
BENCHMARK(BM_MhtStepWithScanView)->Unit(benchmark::kMillisecond);

// Building the view from the scan and the scan's 40 detections, and asking it about 30 tracks:
// what the tracking stage adds to a cycle besides the trackers' own queries.
void BM_ScanViewBuildAndQuery(benchmark::State& s) {
  const LidarScan scan = WalledScan();
  const std::vector<Eigen::Vector2d> detections = SceneDetectionPositions();
  const std::vector<Eigen::Vector2d>& targets = Scene().truth[kWarmUpScans];
  for (auto _ : s) {
    const ScanVisibility view(scan, Pose2{}, {}, detections);
    double seen = 0.0;
    for (const Eigen::Vector2d& p : targets) seen += view.View(p, ObjectClass::kCar).seen;
    benchmark::DoNotOptimize(seen);
  }
}
BENCHMARK(BM_ScanViewBuildAndQuery)->Unit(benchmark::kMicrosecond);

void BM_GnnStep(benchmark::State& s) {
  const GnnTracker warm = WarmedUp(GnnTracker());
  TimeStep(s, warm);
  s.counters["confirmed"] = static_cast<double>(warm.ConfirmedTracks().size());
}
BENCHMARK(BM_GnnStep)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lookout::tracking
