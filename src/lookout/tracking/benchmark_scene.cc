#include "lookout/tracking/benchmark_scene.h"

#include <array>
#include <cmath>
#include <numbers>

#include "lookout/core/random.h"

namespace lookout::tracking {

BenchmarkScene MakeBenchmarkScene(int targets, int false_objects, int scans, std::uint64_t seed) {
  constexpr double kHalf = BenchmarkScene::kSideM / 2.0;
  constexpr double kSigmaM = 0.2, kMissProbability = 0.1;
  struct Kind {
    ObjectClass object_class;
    double speed_mps;
  };
  constexpr std::array<Kind, 3> kKinds = {Kind{ObjectClass::kCar, 10.0},
                                          Kind{ObjectClass::kCyclist, 5.0},
                                          Kind{ObjectClass::kPedestrian, 1.4}};
  Rng rng(seed);
  struct Mover {
    Eigen::Vector2d start, velocity;
    ObjectClass object_class;
  };
  std::vector<Mover> movers;
  for (int i = 0; i < targets; ++i) {
    const Kind& kind = kKinds[static_cast<std::size_t>(i) % kKinds.size()];
    const double heading = rng.Uniform(-std::numbers::pi, std::numbers::pi);
    // Starting inside the square's inner 60 %, so that nobody leaves it within a few seconds.
    movers.push_back(
        {{rng.Uniform(-0.6 * kHalf, 0.6 * kHalf), rng.Uniform(-0.6 * kHalf, 0.6 * kHalf)},
         kind.speed_mps * Eigen::Vector2d(std::cos(heading), std::sin(heading)),
         kind.object_class});
  }
  BenchmarkScene scene;
  scene.clutter_density_per_m2 =
      static_cast<double>(false_objects) / (BenchmarkScene::kSideM * BenchmarkScene::kSideM);
  for (int k = 0; k < scans; ++k) {
    const TimeNs stamp = k * BenchmarkScene::kScanPeriod;
    const double t = ToSeconds(stamp);
    std::vector<Detection>& scan = scene.scans.emplace_back();
    std::vector<Eigen::Vector2d>& truth = scene.truth.emplace_back();
    scene.stamps.push_back(stamp);
    for (const Mover& m : movers) {
      const Eigen::Vector2d p = m.start + t * m.velocity;
      truth.push_back(p);
      if (rng.Bernoulli(kMissProbability)) continue;
      Detection d;
      // The y draw first, in its own statement: the order GCC happened to take when this scene's
      // figures were written (two draws in one call's arguments are unsequenced).
      const double noise_y = rng.Normal();
      const double noise_x = rng.Normal();
      d.position_m = p + kSigmaM * Eigen::Vector2d(noise_x, noise_y);
      d.covariance = Eigen::Matrix2d::Identity() * kSigmaM * kSigmaM;
      d.object_class = m.object_class;
      d.sensors = rng.Bernoulli(0.5) ? 2 : 1;
      scan.push_back(d);
    }
    for (int f = 0; f < false_objects; ++f) {
      Detection d;
      d.position_m = {rng.Uniform(-kHalf, kHalf), rng.Uniform(-kHalf, kHalf)};
      d.covariance = Eigen::Matrix2d::Identity() * kSigmaM * kSigmaM;
      scan.push_back(d);
    }
  }
  return scene;
}

}  // namespace lookout::tracking
