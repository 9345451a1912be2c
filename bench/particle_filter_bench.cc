// One particle-filter update of the lidar localiser (lidar/localiser.h: predict, match,
// refine, weigh, resample, map the scan), per scan of a simulated drive round the hall of the
// lidar tests (360 beams, one scan per metre), with 30 and 100 particles and either motion
// model. Each iteration is the next scan of a long drive, so the map grows as in a real run.
// Figures in docs/PERFORMANCE.md.

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "lookout/lidar/lidar_test_support.h"
#include "lookout/lidar/localiser.h"

namespace lookout::lidar {
namespace {

struct DriveData {
  std::vector<Pose2> odometry;
  std::vector<LidarScan> scans;
};

// 600 one-metre steps round an ellipse (10 laps), odometry with a 2 % scale error.
const DriveData& Drive() {
  static const DriveData* drive = [] {
    auto* d = new DriveData;
    const std::vector<sim::Shape> world = testing::Hall();
    Pose2 previous;
    Pose2 odometry;
    double s = 0.0;
    for (int k = 0; k < 600; ++k) {
      const Eigen::Vector2d p(12.0 * std::cos(s), 7.0 * std::sin(s));
      const Eigen::Vector2d v(-12.0 * std::sin(s), 7.0 * std::cos(s));
      const Pose2 truth(p, std::atan2(v.y(), v.x()));
      if (k == 0) {
        odometry = truth;
      } else {
        const Pose2 inc = previous.Inverse() * truth;
        odometry = odometry * Pose2(1.02 * inc.x(), inc.y(), 1.02 * inc.yaw);
      }
      previous = truth;
      d->odometry.push_back(odometry);
      d->scans.push_back(testing::CastScan(world, truth, FromSeconds(0.5 * k)));
      s += 1.0 / v.norm();
    }
    return d;
  }();
  return *drive;
}

void BM_ParticleFilterUpdate(benchmark::State& state) {
  const DriveData& drive = Drive();
  SlamOptions options;
  options.filter.particle_count = static_cast<int>(state.range(0));
  options.motion.kind =
      state.range(1) == 0 ? MotionModelKind::kBicycle : MotionModelKind::kDifferentialDrive;
  std::size_t k = 0;
  LidarLocaliser localiser(options);
  for (auto _ : state) {
    if (k == drive.scans.size()) {  // a new drive: rebuild outside the timing
      state.PauseTiming();
      localiser = LidarLocaliser(options);
      k = 0;
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(localiser.AddScan(drive.scans[k], drive.odometry[k]));
    ++k;
  }
  state.counters["scans_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ParticleFilterUpdate)
    ->ArgsProduct({{30, 100}, {0, 1}})
    ->ArgNames({"particles", "diff_drive"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lookout::lidar
