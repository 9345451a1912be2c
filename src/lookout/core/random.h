#pragma once

#include <cstdint>
#include <random>
#include <string_view>

namespace lookout {

// Deterministic random numbers. Every draw in Lookout comes from an Rng whose seed is derived
// from the scenario seed, a stream name and an index (a sensor frame, say), never from a
// shared generator: so a frame's noise does not depend on which thread made it, or in which
// order, and the same scenario and seed give the same bytes on any number of threads.
//
// The engine is std::mt19937_64, whose output the C++ standard fixes; the distributions are
// written here because the standard library's are implementation-defined.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  std::uint64_t NextU64() { return engine_(); }
  double Uniform();                          // [0, 1), 53 random bits
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  double Normal();                           // standard normal (Box-Muller)
  double Normal(double mean, double sigma) { return mean + sigma * Normal(); }
  bool Bernoulli(double p) { return Uniform() < p; }
  std::uint64_t UniformIndex(std::uint64_t n);  // [0, n), n > 0, unbiased

 private:
  std::mt19937_64 engine_;
  double spare_normal_ = 0.0;
  bool has_spare_ = false;
};

// SplitMix64 finaliser: a bijective 64-bit mix with good avalanche.
std::uint64_t Mix64(std::uint64_t x);

// The seed of stream `stream` (a short name such as "lidar") at `index`, under `seed`.
std::uint64_t DeriveSeed(std::uint64_t seed, std::string_view stream, std::uint64_t index);

}  // namespace lookout
