// One IMM cycle (mixing, mode-matched prediction, measurement update) of the paper's four models
// (CV, CA, left and right turn), and its parts, on a target at 10 m/s; plus one Kalman filter
// cycle of CV alone for scale. Figures in docs/PERFORMANCE.md.

#include <benchmark/benchmark.h>

#include "lookout/tracking/imm.h"

namespace lookout::tracking {
namespace {

struct Fixture {
  ImmOptions options = FourModelImm(0.1, 0.01, 0.15, 2.0, 0.8);
  Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * 100.0;
  ImmState state;

  Fixture() {
    state = InitImm(
        options,
        {Eigen::Vector4d(0.0, 0.0, 10.0, 0.0), Eigen::Vector4d(100, 100, 4, 4).asDiagonal()},
        {kX, kY, kVx, kVy}, 1.0, 0);
    // A few cycles so that the modes differ, as in a running track.
    for (int k = 1; k <= 5; ++k) {
      state = PredictTo(options, state, k * kNanosPerSecond);
      state = Update(options, state, Eigen::Vector2d(10.0 * k, 0.3 * k * k), R).state;
    }
  }
};

void BM_ImmPredictUpdate(benchmark::State& s) {
  const Fixture f;
  const Eigen::Vector2d z(61.0, 11.0);
  for (auto _ : s) {
    const ImmState predicted = PredictTo(f.options, f.state, f.state.time + kNanosPerSecond);
    ImmUpdate u = Update(f.options, predicted, z, f.R);
    benchmark::DoNotOptimize(u.state.probabilities.data());
  }
}
BENCHMARK(BM_ImmPredictUpdate);

void BM_ImmMixing(benchmark::State& s) {
  const Fixture f;
  for (auto _ : s) {
    Mixing m = MixInto(f.options, f.state);
    benchmark::DoNotOptimize(m.mixed.data());
  }
}
BENCHMARK(BM_ImmMixing);

void BM_ImmGate(benchmark::State& s) {
  const Fixture f;
  const ImmState predicted = PredictTo(f.options, f.state, f.state.time + kNanosPerSecond);
  for (auto _ : s) {
    ImmMeasurementPrediction p = PredictMeasurement(predicted, f.R);
    benchmark::DoNotOptimize(p.combined.S.data());
  }
}
BENCHMARK(BM_ImmGate);

void BM_KalmanCvPredictUpdate(benchmark::State& s) {
  const Fixture f;
  const MotionModel cv = ConstantVelocity(0.1);
  const Gaussian g = f.state.modes[0];
  const Eigen::Vector2d z(61.0, 11.0);
  for (auto _ : s) {
    UpdateResult u = UpdateState(PredictState(cv, g, 1.0), z, f.R);
    benchmark::DoNotOptimize(u.posterior.mean.data());
  }
}
BENCHMARK(BM_KalmanCvPredictUpdate);

}  // namespace
}  // namespace lookout::tracking
