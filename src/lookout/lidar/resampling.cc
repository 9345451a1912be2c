#include "lookout/lidar/resampling.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lookout::lidar {

std::vector<double> NormaliseLogWeights(std::span<const double> log_weights) {
  const std::size_t n = log_weights.size();
  std::vector<double> w(n, 0.0);
  if (n == 0) return w;
  double max_log = -std::numeric_limits<double>::infinity();
  for (double lw : log_weights) {
    if (!std::isnan(lw)) max_log = std::max(max_log, lw);
  }
  if (!std::isfinite(max_log)) {
    std::fill(w.begin(), w.end(), 1.0 / static_cast<double>(n));
    return w;
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    w[i] = std::isnan(log_weights[i]) ? 0.0 : std::exp(log_weights[i] - max_log);
    sum += w[i];
  }
  for (double& x : w) x /= sum;  // sum >= 1: the maximum contributes exp(0)
  return w;
}

double EffectiveSampleSize(std::span<const double> weights) {
  double sum_sq = 0.0;
  for (double x : weights) sum_sq += x * x;
  return sum_sq > 0.0 ? 1.0 / sum_sq : 0.0;
}

std::vector<std::size_t> LowVarianceResample(std::span<const double> weights, double u0) {
  const std::size_t n = weights.size();
  std::vector<std::size_t> kept;
  kept.reserve(n);
  if (n == 0) return kept;
  const double step = 1.0 / static_cast<double>(n);
  double cumulative = weights[0];
  std::size_t i = 0;
  for (std::size_t m = 0; m < n; ++m) {
    const double u = (u0 + static_cast<double>(m)) * step;
    // Rounding can leave the cumulative sum a hair below 1: the last particle takes the rest.
    while (u > cumulative && i + 1 < n) {
      ++i;
      cumulative += weights[i];
    }
    kept.push_back(i);
  }
  return kept;
}

}  // namespace lookout::lidar
