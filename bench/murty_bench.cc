// The assignment solvers the tracker and the tracking metrics use: one optimal linear
// assignment (Jonker-Volgenant shortest augmenting path), and Murty's m = 10 best assignments
// on 50 x 50, the size the MHT meets with 30 targets and clutter. Figures go in
// docs/PERFORMANCE.md.

#include <benchmark/benchmark.h>

#include <cstdint>

#include "lookout/assignment/linear_assignment.h"
#include "lookout/assignment/murty.h"
#include "lookout/core/random.h"

namespace lookout::assignment {
namespace {

// Uniform costs in [0, 100) from a fixed seed: dense, no structure to exploit.
Eigen::MatrixXd DenseCost(Eigen::Index n, std::uint64_t seed) {
  Rng rng(seed);
  Eigen::MatrixXd cost(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) cost(i, j) = rng.Uniform(0.0, 100.0);
  }
  return cost;
}

// The MHT's shape: n measurements against n tracks (gated: each measurement sees about 4
// tracks), then one "false alarm" column per measurement and one "new track" column per
// measurement, each allowed only on its own row.
Eigen::MatrixXd GatedCost(Eigen::Index n, std::uint64_t seed) {
  Rng rng(seed);
  Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(n, 3 * n, kForbidden);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      if (rng.Bernoulli(4.0 / static_cast<double>(n))) cost(i, j) = rng.Uniform(0.0, 10.0);
    }
    cost(i, n + i) = 12.0;      // false alarm
    cost(i, 2 * n + i) = 14.0;  // new track
  }
  return cost;
}

void BM_LinearAssignmentDense(benchmark::State& state) {
  const Eigen::MatrixXd cost = DenseCost(state.range(0), 1);
  for (auto _ : state) benchmark::DoNotOptimize(SolveLinearAssignment(cost));
}
BENCHMARK(BM_LinearAssignmentDense)->Arg(50)->Arg(200)->Unit(benchmark::kMicrosecond);

void BM_MurtyDense(benchmark::State& state) {
  const Eigen::MatrixXd cost = DenseCost(50, 1);
  const auto m = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(MurtyBestAssignments(cost, m));
}
BENCHMARK(BM_MurtyDense)->Arg(1)->Arg(10)->Unit(benchmark::kMillisecond);

void BM_MurtyGated(benchmark::State& state) {
  const Eigen::MatrixXd cost = GatedCost(50, 2);
  const auto m = static_cast<std::size_t>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(MurtyBestAssignments(cost, m));
}
BENCHMARK(BM_MurtyGated)->Arg(1)->Arg(10)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lookout::assignment
