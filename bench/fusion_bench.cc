// Lidar/stereo fusion (docs/fusion.md): one lidar frame of N objects fused with a stereo frame
// of N objects, N = 10 and 100. Two measurements: the whole stage (FusionEngine::Fuse:
// validation, projection, prediction to the lidar stamp, gate, optimal assignment, fusion)
// and the association and fusion alone on points already projected (FuseObjects). Figures go
// in docs/PERFORMANCE.md.
//
// The scene: N objects spread over the camera's field (70 degrees, 3 to 35 m), each seen by
// the camera and, 0.1 m from the camera's point, by the lidar, so that every stereo object has its
// partner and its neighbours in the gate; fixed seed. BM_FuseObjectsWithPieces adds a second
// lidar object 1 m from each partner that no stereo object pairs: the fragment test (fusion.md,
// "A paired body's fragments") then runs for N unpaired lidar objects against N stereo objects.

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <variant>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/core/random.h"
#include "lookout/fusion/fuse_objects.h"
#include "lookout/fusion/fusion_engine.h"
#include "lookout/stereo/stereo_point.h"

namespace lookout::fusion {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

const Pose2 kCameraMount(0.8, 0.0, 0.0);
const Pose2 kLidarMount(2.2, 0.0, 0.0);

struct Scene {
  LidarObjectFrame lidar;
  StereoFrame stereo;
};

Scene MakeScene(int count, bool pieces = false) {
  Rng rng(2026);
  Scene scene;
  scene.lidar.stamp = 80'000'000;
  scene.lidar.mount = kLidarMount;
  scene.lidar.ego_pose = Pose2(0.8, 0.0, 0.0);
  scene.stereo.stamp = 50'000'000;
  scene.stereo.mount = kCameraMount;
  for (int i = 0; i < count; ++i) {
    const double depth = rng.Uniform(3.0, 35.0);
    const double bearing = rng.Uniform(-0.6, 0.6);
    StereoObject s;
    s.id = static_cast<std::uint32_t>(i + 1);
    s.object_class = ObjectClass::kCar;
    s.center_m = Vector2d(depth, depth * std::tan(bearing));
    s.yaw_rad = rng.Uniform(-kPi, kPi);
    s.length_m = 4.5;
    s.width_m = 1.8;
    s.speed_longitudinal_mps = rng.Normal(0.0, 5.0);
    s.speed_lateral_mps = rng.Normal(0.0, 5.0);
    const double sigma = 0.02 + depth * depth * 0.25 / 240.0;
    s.center_covariance = Vector2d(sigma * sigma, 0.01).asDiagonal();
    s.yaw_variance = 0.0025;
    s.speed_variance = 0.25;
    scene.stereo.objects.push_back(s);
    LidarObject l;
    l.id = static_cast<std::uint32_t>(i);
    // Beside the camera's own point (its front side's middle), where a lidar would see it.
    const auto projected = stereo::ProjectStereoObject(s, kCameraMount, kLidarMount, {});
    l.point_m = std::get<stereo::StereoPoint>(projected).point.point_m + Vector2d(0.1, 0.05);
    l.point_covariance = 0.02 * Matrix2d::Identity();
    l.velocity_mps = Vector2d(s.speed_longitudinal_mps, s.speed_lateral_mps);
    l.velocity_covariance = 0.5 * Matrix2d::Identity();
    l.class_pmf[static_cast<std::size_t>(ObjectClass::kCar)] = 1.0;
    l.dynamic = true;
    scene.lidar.objects.push_back(l);
    if (pieces) {
      LidarObject piece = l;
      piece.id = static_cast<std::uint32_t>(count + i);
      piece.point_m += Vector2d(0.0, 1.0);
      piece.front_start_m = piece.point_m - Vector2d(0.0, 0.3);
      piece.front_end_m = piece.point_m + Vector2d(0.0, 0.3);
      scene.lidar.objects.push_back(piece);
    }
  }
  return scene;
}

void BM_FusionEngineFuse(benchmark::State& state) {
  const Scene scene = MakeScene(static_cast<int>(state.range(0)));
  FusionEngine engine;
  std::size_t fused = 0;
  for (auto _ : state) {
    // The overload with the ego pose at the stereo stamp given: the same frame can be fused
    // again and again (the other one would count the repeated stamp as time not advancing).
    const FusedObjectFrame frame = engine.Fuse(scene.lidar, scene.stereo, scene.lidar.ego_pose);
    fused = frame.objects.size();
    benchmark::DoNotOptimize(frame.objects.data());
  }
  state.counters["fused_objects"] = static_cast<double>(fused);
  state.counters["pairs_per_frame"] =
      static_cast<double>(engine.stats().pairs) / static_cast<double>(engine.stats().frames);
}
BENCHMARK(BM_FusionEngineFuse)->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);

void BM_FuseObjects(benchmark::State& state) {
  const Scene scene = MakeScene(static_cast<int>(state.range(0)));
  const FusionOptions options;
  const stereo::ProjectedStereoFrame projected =
      stereo::ProjectStereoFrame(scene.stereo, kLidarMount, options.stereo);
  for (auto _ : state) {
    const FuseObjectsResult result = FuseObjects(scene.lidar, projected.objects, options);
    benchmark::DoNotOptimize(result.frame.objects.data());
  }
}
BENCHMARK(BM_FuseObjects)->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);

// With each camera track's last pair as a prior (pair_memory.h), one per stereo object at its
// own point, as on every frame after the first.
void BM_FuseObjectsWithPriors(benchmark::State& state) {
  const Scene scene = MakeScene(static_cast<int>(state.range(0)));
  const FusionOptions options;
  const stereo::ProjectedStereoFrame projected =
      stereo::ProjectStereoFrame(scene.stereo, kLidarMount, options.stereo);
  std::vector<PairPrior> priors;
  for (std::size_t i = 0; i < projected.objects.size(); ++i) {
    priors.push_back({i, projected.objects[i].point});
  }
  std::size_t pairs = 0;
  for (auto _ : state) {
    const FuseObjectsResult result = FuseObjects(scene.lidar, projected.objects, options, priors);
    pairs = result.pairs;
    benchmark::DoNotOptimize(result.frame.objects.data());
  }
  state.counters["pairs"] = static_cast<double>(pairs);
}
BENCHMARK(BM_FuseObjectsWithPriors)->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);

void BM_FuseObjectsWithPieces(benchmark::State& state) {
  const Scene scene = MakeScene(static_cast<int>(state.range(0)), true);
  const FusionOptions options;
  const stereo::ProjectedStereoFrame projected =
      stereo::ProjectStereoFrame(scene.stereo, kLidarMount, options.stereo);
  std::size_t fragments = 0;
  for (auto _ : state) {
    const FuseObjectsResult result = FuseObjects(scene.lidar, projected.objects, options);
    fragments = result.fragment_lidar_ids.size();
    benchmark::DoNotOptimize(result.frame.objects.data());
  }
  state.counters["fragments"] = static_cast<double>(fragments);
}
BENCHMARK(BM_FuseObjectsWithPieces)->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace lookout::fusion
