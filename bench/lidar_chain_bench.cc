// The lidar chain in the pipeline's setting (app/lidar_chain_stage.h): the default scenario's
// junction, a 641-beam scan at 12.5 Hz with the ego driving 11 m/s among moving actors.
//   BM_LidarChainScan   one whole stage step per scan (localise, classify, map, segment),
//                       each iteration the whole run from a fresh stage, so the map grows as
//                       in a run; the figure is ms_per_scan;
//   BM_LocaliseScan     the localisation alone (LidarLocaliser::LocaliseScan + MapScan of
//                       every return), the same scans;
//   BM_ClassifyHits     the moving/static classification of one scan at t = 4 s;
//   BM_SegmentScan      the segmentation of that scan (every cluster described, static too).
// Figures in docs/PERFORMANCE.md.

#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "lookout/app/lidar_chain_stage.h"
#include "lookout/io/scenario_loader.h"
#include "lookout/lidar/scan_matcher.h"
#include "lookout/sim/simulator.h"

namespace lookout::app {
namespace {

const sim::SensorLog& Log() {
  static const sim::SensorLog* log = [] {
    const sim::Simulator simulator(io::LoadDefaultScenario());
    return new sim::SensorLog(simulator.Run(1));
  }();
  return *log;
}

// Feeds the odometry up to scan k's stamp; returns the next odometry index.
std::size_t FeedOdometry(LidarChainStage& stage, const sim::SensorLog& log, std::size_t o,
                         std::size_t k) {
  while (o < log.odometry.size() && log.odometry[o].stamp <= log.lidar[k].stamp) {
    stage.OnOdometry(log.odometry[o++]);
  }
  return o;
}

// Argument: 1 with the default options, 0 with beams that saw nothing clearing nothing
// (no_return_clear_m = 0, as `lookout replay` runs it): what the empty beams' rays cost; 2
// without the far map (far_map_enabled = false): what the far map costs.
// Each iteration is the whole run, every scan in order from a fresh stage (made and freed
// outside the timing: its maps are 210 MB), so that every measurement covers the same scans;
// the figure is the time per scan. (Before 2026-12-03 an iteration was the next scan, and the
// mean covered however many scans fitted in the time budget: 7-10 ms from run to run.)
void BM_LidarChainScan(benchmark::State& state) {
  const sim::SensorLog& log = Log();
  lidar::LidarChainOptions options;
  if (state.range(0) == 0) options.no_return_clear_m = 0.0;
  if (state.range(0) == 2) options.far_map_enabled = false;
  for (auto _ : state) {
    state.PauseTiming();
    auto stage = std::make_unique<LidarChainStage>(options);
    state.ResumeTiming();
    std::size_t o = 0;
    for (std::size_t k = 0; k < log.lidar.size(); ++k) {
      o = FeedOdometry(*stage, log, o, k);
      stage->OnLidar(log.lidar[k]);
    }
    benchmark::DoNotOptimize(stage->last_objects());
    state.PauseTiming();
    stage.reset();
    state.ResumeTiming();
  }
  const auto scans = static_cast<double>(log.lidar.size());
  state.counters["ms_per_scan"] = benchmark::Counter(
      scans / 1e3, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_LidarChainScan)->Arg(1)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_LocaliseScan(benchmark::State& state) {
  const sim::SensorLog& log = Log();
  // The dead-reckoned odometry poses at each scan, as the stage gives them.
  static const std::vector<Pose2> odometry = [&] {
    std::vector<Pose2> poses;
    DeadReckoning dr;
    std::size_t o = 0;
    for (const LidarScan& scan : log.lidar) {
      while (o < log.odometry.size() && log.odometry[o].stamp <= scan.stamp) {
        dr.Add(log.odometry[o++]);
      }
      poses.push_back(dr.At(scan.stamp).pose);
    }
    return poses;
  }();
  const lidar::SlamOptions options = lidar::VehicleLocaliserOptions();
  auto localiser = std::make_unique<lidar::LidarLocaliser>(options);
  std::size_t k = 0;
  for (auto _ : state) {
    if (k == log.lidar.size()) {
      state.PauseTiming();
      localiser = std::make_unique<lidar::LidarLocaliser>(options);
      k = 0;
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(localiser->AddScan(log.lidar[k], odometry[k]));
    ++k;
  }
}
BENCHMARK(BM_LocaliseScan)->Unit(benchmark::kMillisecond);

// The stage after the scans up to t = 4 s: its map, and the classes of the 4 s scan.
struct AtFourSeconds {
  std::unique_ptr<LidarChainStage> stage;
  std::size_t scan = 0;
};
const AtFourSeconds& FourSeconds() {
  static const AtFourSeconds* at = [] {
    auto* a = new AtFourSeconds;
    const sim::SensorLog& log = Log();
    a->stage = std::make_unique<LidarChainStage>();
    std::size_t o = 0;
    for (std::size_t k = 0; k < log.lidar.size(); ++k) {
      o = FeedOdometry(*a->stage, log, o, k);
      a->stage->OnLidar(log.lidar[k]);
      if (log.lidar[k].stamp >= FromSeconds(4.0)) {
        a->scan = k;
        break;
      }
    }
    return a;
  }();
  return *at;
}

void BM_ClassifyHits(benchmark::State& state) {
  const AtFourSeconds& at = FourSeconds();
  const LidarScan& scan = Log().lidar[at.scan];
  for (auto _ : state) {
    benchmark::DoNotOptimize(lidar::ClassifyHits(at.stage->localiser().map(), scan,
                                                 at.stage->last_state()->pose, {}));
  }
}
BENCHMARK(BM_ClassifyHits)->Unit(benchmark::kMicrosecond);

void BM_SegmentScan(benchmark::State& state) {
  const AtFourSeconds& at = FourSeconds();
  const LidarScan& scan = Log().lidar[at.scan];
  lidar::SegmentationOptions options;
  options.dynamic_only = false;
  std::size_t objects = 0;
  for (auto _ : state) {
    const LidarObjectFrame f = lidar::SegmentScan(scan, at.stage->last_hits().beam, Pose2(),
                                                  options, 0.1);
    objects = f.objects.size();
    benchmark::DoNotOptimize(f);
  }
  state.counters["objects"] = static_cast<double>(objects);
}
BENCHMARK(BM_SegmentScan)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace lookout::app
