#include "lookout/sim/simulator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <optional>
#include <utility>

#include "lookout/core/random.h"
#include "lookout/sim/contact.h"
#include "lookout/sim/footprint.h"
#include "lookout/sim/lidar_sensor.h"
#include "lookout/sim/odometry_sensor.h"
#include "lookout/sim/raycast.h"
#include "lookout/sim/stereo_sensor.h"
#include "lookout/sim/world_builder.h"

namespace lookout::sim {
namespace {

// Frame k of a sensor at rate_hz is taken at k / rate_hz for every k with k / rate_hz within
// [0, duration]; the tolerance keeps the last frame when duration x rate is an integer that
// rounding made a hair smaller (12 s at 12.5 Hz: 150 intervals, 151 frames).
int FrameCount(double duration_s, double rate_hz) {
  assert(duration_s >= 0.0 && rate_hz > 0.0);
  return static_cast<int>(std::floor(duration_s * rate_hz + 1e-9)) + 1;
}

// Integer nanoseconds, rounded once: 12.5 Hz is exactly 80 ms per frame, with no drift.
TimeNs FrameStamp(int k, double rate_hz) {
  return static_cast<TimeNs>(
      std::llround(static_cast<double>(k) * static_cast<double>(kNanosPerSecond) / rate_hz));
}

// Everything that moves, at one instant: the ego and the actors present, with their shapes.
struct Scene {
  KinematicState ego;
  std::vector<int> actor_index;        // present actors, in index order
  std::vector<KinematicState> states;  // parallel to actor_index
  std::vector<Shape> footprints;       // parallel to actor_index, owned by the actor index
};

Scene SceneAt(const Simulator& sim, double t_s) {
  Scene scene;
  scene.ego = sim.ego_trajectory().At(t_s);
  const std::vector<Trajectory>& trajectories = sim.actor_trajectories();
  for (std::size_t i = 0; i < trajectories.size(); ++i) {
    if (!trajectories[i].Present(t_s)) continue;
    const int index = static_cast<int>(i);
    const KinematicState state = trajectories[i].At(t_s);
    scene.actor_index.push_back(index);
    scene.states.push_back(state);
    scene.footprints.push_back(
        FootprintAt(Footprint::ForActor(sim.scenario().actors[i]), state.pose, index));
  }
  return scene;
}

int ActorCount(const Simulator& sim) { return static_cast<int>(sim.scenario().actors.size()); }

FanHits CastLidar(const Simulator& sim, const Scene& scene) {
  return CastFan(LidarFan(sim.scenario().sensors.lidar, scene.ego.pose), sim.static_world(),
                 scene.footprints, ActorCount(sim));
}

Pose2 CameraPose(const Simulator& sim, const Scene& scene) {
  return scene.ego.pose * StereoMount(sim.scenario().sensors.stereo);
}

// The noise model is not part of the scenario format; the simulator uses its defaults.
const StereoNoiseModel& NoiseModel() {
  static const StereoNoiseModel model;
  return model;
}

FanHits CastCamera(const Simulator& sim, const Scene& scene) {
  return CastFan(StereoFan(sim.scenario().sensors.stereo, NoiseModel(), CameraPose(sim, scene)),
                 sim.static_world(), scene.footprints, ActorCount(sim));
}

TruthFrame MakeTruth(const Simulator& sim, TimeNs stamp, const Scene& scene,
                     const FanHits& lidar, const FanHits& camera,
                     const std::vector<std::optional<double>>& contact_times) {
  const Scenario& scenario = sim.scenario();
  TruthFrame truth;
  truth.stamp = stamp;
  truth.ego.state = scene.ego;
  truth.ego.footprint =
      FootprintAt(Footprint::ForEgo(scenario.ego), scene.ego.pose, kStaticOwner);
  truth.actors.reserve(scene.actor_index.size());
  for (std::size_t j = 0; j < scene.actor_index.size(); ++j) {
    const int index = scene.actor_index[j];
    const auto i = static_cast<std::size_t>(index);
    ActorTruth actor;
    actor.index = index;
    actor.id = scenario.actors[i].id;
    actor.object_class = scenario.actors[i].object_class;
    actor.state = scene.states[j];
    actor.footprint = scene.footprints[j];
    actor.visible_fraction_lidar = lidar.VisibleFraction(index);
    actor.visible_fraction_stereo = camera.VisibleFraction(index);
    actor.contact_time_s = contact_times[i];
    truth.actors.push_back(std::move(actor));
  }
  truth.lidar_beam_owner = lidar.owner;
  return truth;
}

LidarScan MakeScan(const Simulator& sim, int k, TimeNs stamp, const FanHits& hits) {
  Rng rng(DeriveSeed(sim.scenario().seed, "lidar", static_cast<std::uint64_t>(k)));
  return MakeLidarScan(sim.scenario().sensors.lidar, stamp, hits, rng);
}

// Counts, per actor id, the consecutive frames up to and including each one in which the
// camera reported it. False objects keep their history of 1.
void FillStereoHistory(std::vector<StereoFrame>& frames, int actor_count) {
  std::vector<std::uint32_t> previous(static_cast<std::size_t>(actor_count), 0);
  std::vector<std::uint32_t> current(previous.size(), 0);
  for (StereoFrame& frame : frames) {
    std::fill(current.begin(), current.end(), 0u);
    for (StereoObject& object : frame.objects) {
      if (object.id >= kFalseObjectIdBase) continue;
      const std::size_t actor = object.id - 1u;
      current[actor] = previous[actor] + 1u;
      object.history = current[actor];
    }
    std::swap(previous, current);
  }
}

}  // namespace

Simulator::Simulator(Scenario scenario)
    : scenario_(std::move(scenario)),
      static_world_(BuildStaticWorld(scenario_.world)),
      ego_(Trajectory::Vehicle(scenario_.ego.path, scenario_.ego.speed, scenario_.ego.length_m,
                               0.0, scenario_.duration_s)) {
  actors_.reserve(scenario_.actors.size());
  for (const ActorSpec& a : scenario_.actors) {
    if (a.object_class == ObjectClass::kPedestrian) {
      actors_.push_back(Trajectory::Walker(a.path, a.speed, a.start_s, a.stop_s));
    } else {
      const double length_m = a.length_m > 0.0 ? a.length_m : DefaultLength(a.object_class);
      actors_.push_back(Trajectory::Vehicle(a.path, a.speed, length_m, a.start_s, a.stop_s));
    }
  }
  contact_time_s_.reserve(actors_.size());
  for (std::size_t i = 0; i < actors_.size(); ++i) {
    contact_time_s_.push_back(FirstContactTime(ego_, scenario_.ego.length_m,
                                               scenario_.ego.width_m, actors_[i],
                                               Footprint::ForActor(scenario_.actors[i]), 0.0,
                                               scenario_.duration_s));
  }
}

TruthFrame Simulator::Truth(TimeNs t) const {
  const Scene scene = SceneAt(*this, ToSeconds(t));
  return MakeTruth(*this, t, scene, CastLidar(*this, scene), CastCamera(*this, scene),
                   contact_time_s_);
}

LidarScan Simulator::SimulateLidar(int k) const {
  const TimeNs stamp = FrameStamp(k, scenario_.sensors.lidar.rate_hz);
  const Scene scene = SceneAt(*this, ToSeconds(stamp));
  return MakeScan(*this, k, stamp, CastLidar(*this, scene));
}

StereoFrame Simulator::SimulateStereo(int k) const {
  const StereoOptions& options = scenario_.sensors.stereo;
  const TimeNs stamp = FrameStamp(k, options.rate_hz);
  const Scene scene = SceneAt(*this, ToSeconds(stamp));
  const FanHits hits = CastCamera(*this, scene);
  std::vector<StereoTarget> targets;
  targets.reserve(scene.actor_index.size());
  for (std::size_t j = 0; j < scene.actor_index.size(); ++j) {
    const int index = scene.actor_index[j];
    const ActorSpec& spec = scenario_.actors[static_cast<std::size_t>(index)];
    const Footprint footprint = Footprint::ForActor(spec);
    StereoTarget target;
    target.actor_index = index;
    target.object_class = spec.object_class;
    target.pose = scene.states[j].pose;
    target.velocity_mps = scene.states[j].Velocity();
    const bool circle = footprint.kind == Footprint::Kind::kCircle;
    target.length_m = circle ? 2.0 * footprint.radius_m : footprint.length_m;
    target.width_m = circle ? 2.0 * footprint.radius_m : footprint.width_m;
    target.visible_fraction = hits.VisibleFraction(index);
    targets.push_back(target);
  }
  return MakeStereoFrame(options, NoiseModel(), stamp, k, CameraPose(*this, scene), targets,
                         DeriveSeed(scenario_.seed, "stereo", static_cast<std::uint64_t>(k)));
}

EgoOdometry Simulator::SimulateOdometry(int k) const {
  const OdometryOptions& options = scenario_.sensors.odometry;
  const TimeNs stamp = FrameStamp(k, options.rate_hz);
  Rng rng(DeriveSeed(scenario_.seed, "odometry", static_cast<std::uint64_t>(k)));
  return MakeOdometry(options, stamp, ego_.At(ToSeconds(stamp)), rng);
}

SensorLog Simulator::Run(int threads) const {
  assert(threads >= 1);
  const Sensors& sensors = scenario_.sensors;
  const int lidar_count = FrameCount(scenario_.duration_s, sensors.lidar.rate_hz);
  const int stereo_count = FrameCount(scenario_.duration_s, sensors.stereo.rate_hz);
  const int odometry_count = FrameCount(scenario_.duration_s, sensors.odometry.rate_hz);

  SensorLog log;
  log.lidar.resize(static_cast<std::size_t>(lidar_count));
  log.truth.resize(static_cast<std::size_t>(lidar_count));
  log.stereo.resize(static_cast<std::size_t>(stereo_count));
  log.odometry.resize(static_cast<std::size_t>(odometry_count));

  // One index space over every frame of every stream, so the threads balance across streams.
  // Each task writes only its own preallocated slot and every frame's randomness is seeded by
  // its own index, so the bytes cannot depend on the thread count or the schedule.
  const auto simulate = [&](int task) {
    if (task < lidar_count) {
      // A lidar frame and its truth frame share the scene and the lidar cast.
      const TimeNs stamp = FrameStamp(task, sensors.lidar.rate_hz);
      const Scene scene = SceneAt(*this, ToSeconds(stamp));
      const FanHits lidar_hits = CastLidar(*this, scene);
      const auto slot = static_cast<std::size_t>(task);
      log.lidar[slot] = MakeScan(*this, task, stamp, lidar_hits);
      log.truth[slot] =
          MakeTruth(*this, stamp, scene, lidar_hits, CastCamera(*this, scene), contact_time_s_);
    } else if (task < lidar_count + stereo_count) {
      const int k = task - lidar_count;
      log.stereo[static_cast<std::size_t>(k)] = SimulateStereo(k);
    } else {
      const int k = task - lidar_count - stereo_count;
      log.odometry[static_cast<std::size_t>(k)] = SimulateOdometry(k);
    }
  };
  const int task_count = lidar_count + stereo_count + odometry_count;
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, task_count),
                      [&](const tbb::blocked_range<int>& range) {
                        for (int task = range.begin(); task != range.end(); ++task) {
                          simulate(task);
                        }
                      });
  });

  FillStereoHistory(log.stereo, ActorCount(*this));
  return log;
}

}  // namespace lookout::sim
