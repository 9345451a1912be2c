#include "lookout/app/stage_benchmarks.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "lookout/app/grid_stage.h"
#include "lookout/app/wall_clock.h"
#include "lookout/eval/statistics.h"
#include "lookout/grid/reference_filter.h"
#include "lookout/risk/junction_scene.h"
#include "lookout/risk/risk_assessment.h"
#include "lookout/sim/simulator.h"
#include "lookout/tracking/benchmark_scene.h"
#include "lookout/tracking/mht_tracker.h"

namespace lookout::app {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

GridCycleInput PrepareGridCycle(const sim::Scenario& scenario, double at_s,
                                const grid::FilterOptions& filter) {
  const sim::Simulator simulator(scenario);
  const sim::SensorLog log = simulator.Run(1);
  GridStage stage(grid::GridOptions{}, filter);
  std::size_t next_odometry = 0;
  std::optional<std::size_t> timed;
  for (std::size_t k = 0; k < log.lidar.size(); ++k) {
    while (next_odometry < log.odometry.size() &&
           log.odometry[next_odometry].stamp <= log.lidar[k].stamp) {
      stage.OnOdometry(log.odometry[next_odometry++]);
    }
    if (k > 0 && ToSeconds(log.lidar[k].stamp) >= at_s && stage.last_sensor_pose()) {
      timed = k;
      break;
    }
    stage.OnLidar(log.lidar[k]);
  }
  if (!timed) throw std::invalid_argument("PrepareGridCycle: no lidar frame after at_s");
  const std::size_t k = *timed;
  grid::ExtendedGrid before = stage.grid();  // the state the timed update starts from
  stage.OnLidar(log.lidar[k]);               // computes the measurement in this cycle's window
  const grid::MeasurementGrid& z = stage.last_measurement();
  // The window of the measurement: recentre the state on the centre cell of z's window.
  const grid::ScrollingGridGeometry& zg = z.geometry;
  const CellIndex centre{zg.window_origin().ix + zg.width() / 2,
                         zg.window_origin().iy + zg.height() / 2};
  before.Recenter(zg.CellCenterM(centre));
  assert(before.geometry().window_origin() == zg.window_origin());
  return GridCycleInput{std::move(before), z,
                        ToSeconds(log.lidar[k].stamp - log.lidar[k - 1].stamp)};
}

GridCycleFigures MeasureGridCycle(const sim::Scenario& scenario, double at_s, int repetitions,
                                  int reference_repetitions) {
  const GridCycleInput input = PrepareGridCycle(scenario, at_s);
  const grid::MeasurementGrid& z = input.z;
  const double dt_s = input.dt_s;
  auto fresh_copy = [&] { return input.before; };

  GridCycleFigures out;
  std::vector<double> fast_ms, motion_ms, reference_ms;
  const auto time_fast_path = [&] {
    grid::ExtendedGrid g = fresh_copy();
    const Clock::time_point start = Clock::now();
    g.Update(z, dt_s);
    fast_ms.push_back(MsSince(start));
    motion_ms.push_back(g.last_stats().motion_ms);
    out.sources = g.last_stats().sources;
  };
  // The reference computes the stages of the fast path's motion_ms, on the same scan pair: its
  // preparation is timed on both sides.
  const auto time_reference = [&] {
    grid::ExtendedGrid g = fresh_copy();
    grid::ScanFlow flow = g.scan_flow();
    const Clock::time_point start = Clock::now();
    flow.Prepare(z);
    grid::ReferenceUpdate(g.mutable_layers(), g.ids(), z, dt_s, g.options(), &flow);
    reference_ms.push_back(MsSince(start));
  };
  // Side by side: the reference's runs spread among the fast path's, so that both medians come
  // from the same stretch of time. On a shared machine a burst of another tenant's load lasts
  // tens of milliseconds: the fast path's runs all in one block (2 ms each), then the reference's
  // (100 ms each), could each fall in a different machine state.
  const int every = std::max(1, repetitions / std::max(1, reference_repetitions));
  const auto reference_left = [&] {
    return static_cast<int>(reference_ms.size()) < reference_repetitions;
  };
  for (int r = 0; r < repetitions; ++r) {
    time_fast_path();
    if ((r + 1) % every == 0 && reference_left()) time_reference();
  }
  while (reference_left()) time_reference();
  out.cycle_ms_median = eval::Median(fast_ms);
  out.motion_ms_median = eval::Median(motion_ms);
  out.reference_ms_median = eval::Median(reference_ms);
  out.reference_speedup = out.reference_ms_median / out.motion_ms_median;
  return out;
}

double MeasureRiskStepMs(int tracks, int samples, int repetitions) {
  const std::vector<risk::ObjectInput> objects = risk::JunctionRoadUsers(tracks, 20261122);
  risk::RiskOptions options;
  options.collision_samples = samples;
  risk::EgoInput ego;
  ego.speed_mps = 11.1;
  ego.yaw_rate_radps = 0.05;
  std::vector<double> ms;
  double sink = 0.0;
  for (int r = 0; r < repetitions; ++r) {
    const Clock::time_point start = Clock::now();
    const risk::RiskAssessment a = risk::AssessRisk(ego, objects, options);
    ms.push_back(MsSince(start));
    sink += a.risk;
  }
  if (!std::isfinite(sink)) throw std::logic_error("risk step gave a non-finite risk");
  return eval::Median(ms);
}

double MeasureMhtStepMs(int targets, int false_objects, int hypotheses_m, int n_scan,
                        int repetitions) {
  constexpr int kWarmUpScans = 20;  // 2 s: every target tracked, the hypotheses branched
  const tracking::BenchmarkScene scene =
      tracking::MakeBenchmarkScene(targets, false_objects, kWarmUpScans + 1, 20261201);
  tracking::MhtOptions options;
  options.hypotheses_m = hypotheses_m;
  options.n_scan = n_scan;
  options.clutter_density_per_m2 = scene.clutter_density_per_m2;
  options.new_track_density_per_m2 = 2.0 * scene.clutter_density_per_m2;
  tracking::MhtTracker warm(options);
  for (std::size_t k = 0; k < kWarmUpScans; ++k) warm.Step(scene.stamps[k], scene.scans[k]);
  std::vector<double> ms;
  std::size_t sink = 0;
  for (int r = 0; r < repetitions; ++r) {
    tracking::MhtTracker tracker = warm;
    const Clock::time_point start = Clock::now();
    tracker.Step(scene.stamps[kWarmUpScans], scene.scans[kWarmUpScans]);
    ms.push_back(MsSince(start));
    sink += tracker.ConfirmedTracks().size();
  }
  if (sink == 0) throw std::logic_error("MHT benchmark: no confirmed track");
  return eval::Median(ms);
}

}  // namespace lookout::app
