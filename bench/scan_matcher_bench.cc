// One scan match against the local map (lidar/scan_matcher.h): the correlative search and the
// Gauss-Newton refinement, alone and together, for the search window of a CARMEN-style step
// (car_step 0: 1 m and 0.3 rad between scans) and of a car's lidar at 12.5 Hz (car_step 1:
// 0.1 m, 0.02 rad). The hall
// of the lidar tests, scans cast by the simulator. Figures in docs/PERFORMANCE.md.

#include <benchmark/benchmark.h>

#include <vector>

#include "lookout/lidar/lidar_test_support.h"
#include "lookout/lidar/local_map.h"
#include "lookout/lidar/scan_matcher.h"

namespace lookout::lidar {
namespace {

struct MatchInput {
  LocalMap map;
  std::vector<Eigen::Vector2d> points;
  Pose2 guess;
};

const MatchInput& Input() {
  static const MatchInput* input = [] {
    auto* in = new MatchInput{LocalMap(), {}, Pose2()};
    const std::vector<sim::Shape> world = testing::Hall();
    const MatcherOptions o;
    for (const Pose2& pose : {Pose2(0.0, 0.0, 0.0), Pose2(-10.0, -1.0, 2.0),
                              Pose2(10.0, 1.0, -1.0), Pose2(0.0, -6.0, 1.5)}) {
      const LidarScan scan = testing::CastScan(world, pose);
      std::vector<Eigen::Vector2d> hits;
      for (const Eigen::Vector2d& p : ExtractScanPoints(scan, o).all) hits.push_back(pose * p);
      in->map.InsertScan(pose * scan.mount.translation, hits, {});
    }
    const Pose2 truth(1.0, 2.0, 0.4);
    in->points = ExtractScanPoints(testing::CastScan(world, truth), o).match;
    in->guess = truth * Pose2(0.12, -0.08, 0.04);
    return in;
  }();
  return *input;
}

SearchWindow WindowOf(int kind) {
  return SearchWindowFor(kind == 0 ? Pose2(1.0, 0.0, 0.3) : Pose2(0.1, 0.0, 0.02),
                         MatcherOptions{});
}

void BM_CorrelativeSearch(benchmark::State& state) {
  const MatchInput& in = Input();
  const SearchWindow window = WindowOf(static_cast<int>(state.range(0)));
  const MatcherOptions o;
  for (auto _ : state) {
    benchmark::DoNotOptimize(CorrelativeSearch(in.map, in.points, in.guess, window, o));
  }
  state.counters["points"] = static_cast<double>(in.points.size());
}
BENCHMARK(BM_CorrelativeSearch)->Arg(0)->Arg(1)->ArgName("car_step")->Unit(benchmark::kMicrosecond);

void BM_GaussNewton(benchmark::State& state) {
  const MatchInput& in = Input();
  const MatcherOptions o;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        RefineGaussNewton(in.map, in.points, in.guess, o.gauss_newton_iterations, o));
  }
}
BENCHMARK(BM_GaussNewton)->Unit(benchmark::kMicrosecond);

void BM_MatchScan(benchmark::State& state) {
  const MatchInput& in = Input();
  const SearchWindow window = WindowOf(static_cast<int>(state.range(0)));
  const MatcherOptions o;
  for (auto _ : state) benchmark::DoNotOptimize(MatchScan(in.map, in.points, in.guess, window, o));
}
BENCHMARK(BM_MatchScan)->Arg(0)->Arg(1)->ArgName("car_step")->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace lookout::lidar
