#pragma once

// Importance weights and resampling of the particle filter: normalisation in the log domain,
// the effective sample size, and the low-variance (systematic) resampler (Probabilistic
// Robotics table 4.4), which draws one random number per resampling and keeps every particle
// whose weight exceeds 1/N.

#include <cstddef>
#include <span>
#include <vector>

namespace lookout::lidar {

// Normalised weights exp(log_w - max) / sum. Uniform when every log-weight is -infinity or the
// span is empty-valued; NaN log-weights count as -infinity.
std::vector<double> NormaliseLogWeights(std::span<const double> log_weights);

// 1 / sum(w^2) of normalised weights: N for uniform weights, 1 when one particle holds all.
double EffectiveSampleSize(std::span<const double> weights);

// Indices of the particles kept: N draws at u0 / N, (u0 + 1) / N, ... along the cumulative
// weights, u0 in [0, 1). Sorted ascending; particle i appears floor or ceil of N w_i times.
std::vector<std::size_t> LowVarianceResample(std::span<const double> weights, double u0);

}  // namespace lookout::lidar
