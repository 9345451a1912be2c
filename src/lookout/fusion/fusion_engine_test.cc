#include "lookout/fusion/fusion_engine.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "lookout/fusion/fusion_test_support.h"
#include "lookout/stereo/oriented_box.h"

namespace lookout::fusion {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

using testing::kCameraMount;
using testing::kLidarMount;

// The ego drives east at 10 m/s from the odometry origin; a car crosses northwards at 8 m/s,
// 25 m ahead of where the ego starts. Everything exact (no noise), so the engine's stereo
// point at the lidar stamp must land on the true front point.
constexpr double kEgoSpeed = 10.0;
const Vector2d kCarStart(25.0, -3.0);
const Vector2d kCarVelocity(0.0, 8.0);

Pose2 EgoAt(TimeNs t) { return Pose2(kEgoSpeed * ToSeconds(t), 0.0, 0.0); }
stereo::OrientedBox CarAt(TimeNs t) {
  return {kCarStart + kCarVelocity * ToSeconds(t), kPi / 2.0, 4.5, 1.8};
}

StereoFrame StereoAt(TimeNs t) {
  const Pose2 camera = EgoAt(t) * kCameraMount;
  const Pose2 camera_from_odom = camera.Inverse();
  StereoObject o;
  o.id = 9;
  o.object_class = ObjectClass::kCar;
  o.center_m = camera_from_odom * CarAt(t).center_m;
  o.yaw_rad = kPi / 2.0;
  o.length_m = 4.5;
  o.width_m = 1.8;
  o.speed_longitudinal_mps = kCarVelocity.x();
  o.speed_lateral_mps = kCarVelocity.y();
  o.center_covariance = Vector2d(0.3, 0.003).asDiagonal();
  o.yaw_variance = 0.0025;
  o.speed_variance = 0.1;
  StereoFrame frame;
  frame.stamp = t;
  frame.mount = kCameraMount;
  frame.objects = {o};
  return frame;
}

Vector2d TrueFrontPoint(TimeNs t) {
  // Vehicle frame at t.
  const Pose2 vehicle_from_odom = EgoAt(t).Inverse();
  stereo::OrientedBox box = CarAt(t);
  box.center_m = vehicle_from_odom * box.center_m;
  return stereo::FrontSegmentFacing(box, kLidarMount.translation)->midpoint_m;
}

LidarObjectFrame LidarAt(TimeNs t) {
  LidarObjectFrame frame;
  frame.stamp = t;
  frame.mount = kLidarMount;
  frame.ego_pose = EgoAt(t);
  LidarObject o;
  o.id = 3;
  o.point_m = TrueFrontPoint(t);
  o.point_covariance = 0.01 * Matrix2d::Identity();
  o.velocity_mps = kCarVelocity;
  o.velocity_covariance = 0.5 * Matrix2d::Identity();
  o.class_pmf = {1.0, 0, 0, 0, 0, 0};
  o.dynamic = true;
  frame.objects = {o};
  return frame;
}

TEST(FusionEngineTest, StereoIsBroughtToTheLidarStamp) {
  FusionEngine engine;
  // Lidar at 0 and 80 ms; stereo at 50 ms, 30 ms older than the second lidar frame, when the
  // ego has moved 0.3 m and the car 0.24 m.
  const FusedObjectFrame first = engine.Fuse(LidarAt(0), StereoAt(0));
  EXPECT_EQ(first.objects.size(), 1u);
  const FusedObjectFrame second = engine.Fuse(LidarAt(80'000'000), StereoAt(50'000'000));
  ASSERT_EQ(engine.stereo_at_lidar_time().size(), 1u);
  const Vector2d truth = TrueFrontPoint(80'000'000);
  EXPECT_LT((engine.stereo_at_lidar_time()[0].point.point_m - truth).norm(), 1e-9);
  ASSERT_EQ(second.objects.size(), 1u);
  EXPECT_EQ(second.objects[0].sensor_count, 2);
  EXPECT_LT((second.objects[0].point_m - truth).norm(), 1e-9);
  EXPECT_EQ(engine.stats().stereo_frames_used, 2);
  EXPECT_EQ(engine.stats().pairs, 2);
}

TEST(FusionEngineTest, StaleAndUnplaceableStereoFramesAreCounted) {
  FusionEngine engine;
  // First frame, stereo 30 ms older: no ego pose to interpolate with yet.
  FusedObjectFrame f = engine.Fuse(LidarAt(80'000'000), StereoAt(50'000'000));
  EXPECT_EQ(engine.stats().stereo_frames_without_ego_pose, 1);
  ASSERT_EQ(f.objects.size(), 1u);
  EXPECT_EQ(f.objects[0].sensor_count, 1);
  // 160 ms lidar with the 0 ms stereo frame: too old.
  f = engine.Fuse(LidarAt(160'000'000), StereoAt(0));
  EXPECT_EQ(engine.stats().stereo_frames_stale, 1);
  EXPECT_TRUE(engine.stereo_at_lidar_time().empty());
  // Time going backwards: counted, fused without stereo from another stamp.
  f = engine.Fuse(LidarAt(80'000'000), StereoAt(50'000'000));
  EXPECT_EQ(engine.stats().lidar_stamps_not_increasing, 1);
  EXPECT_EQ(engine.stats().stereo_frames_without_ego_pose, 2);
  EXPECT_EQ(engine.stats().frames, 3);
}

TEST(FusionEngineTest, BadStereoObjectsAreDroppedAndLogged) {
  FusionEngine engine;
  StereoFrame stereo = StereoAt(0);
  StereoObject bad = stereo.objects[0];
  bad.id = 12;
  bad.center_covariance(0, 0) = std::numeric_limits<double>::quiet_NaN();
  stereo.objects.push_back(bad);
  const FusedObjectFrame f = engine.Fuse(LidarAt(0), stereo);
  EXPECT_EQ(f.objects.size(), 1u);
  ASSERT_EQ(engine.last_stereo_drops().size(), 1u);
  EXPECT_EQ(stereo::Describe(engine.last_stereo_drops()[0]),
            "stereo object 12 dropped: a field is NaN or infinite");
  EXPECT_EQ(engine.stats().stereo_drops.Count(stereo::DropReason::kNonFinite), 1);
}

TEST(FusionEngineTest, InvalidOptionsNameTheField) {
  const auto expect_rejected = [](const FusionOptions& options, const std::string& field) {
    try {
      FusionEngine engine(options);
      ADD_FAILURE() << "accepted " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  FusionOptions gate;
  gate.gate_probability = 1.0;
  expect_rejected(gate, "gate_probability");
  FusionOptions disagreement;
  disagreement.disagreement_probability = 0.0;
  expect_rejected(disagreement, "disagreement_probability");
  FusionOptions history;
  history.history_disagreement_probability = 1.5;
  expect_rejected(history, "history_disagreement_probability");
  FusionOptions two_bodies;
  two_bodies.two_bodies_probability = 0.0;
  expect_rejected(two_bodies, "two_bodies_probability");
}

// Two walkers standing one behind the other on the camera's ray, A at 22.5 m and B 0.9 m
// beyond, both seen by both sensors; then A's segment is hidden and B's camera object missed.
// A's camera object, its depth uncertain by 0.45 m, still has B's segment in its gate: paired
// afresh each frame, A would be fused with B's body. B's last pair holds B's segment, A's does
// not: the pair is refused, A is the camera's alone and B the lidar's.
TEST(FusionEngineTest, ACameraTrackKeepsItsBody) {
  const auto walker_camera = [](std::uint32_t id, const Vector2d& centre_vehicle) {
    StereoObject o;
    o.id = id;
    o.object_class = ObjectClass::kPedestrian;
    o.center_m = kCameraMount.Inverse() * centre_vehicle;
    o.length_m = 0.6;
    o.width_m = 0.6;
    o.center_covariance = Vector2d(0.2, 0.0025).asDiagonal();
    o.yaw_variance = 0.0025;
    o.speed_variance = 0.1;
    o.history = 5;
    return o;
  };
  const auto walker_lidar = [](std::uint32_t id, const Vector2d& front) {
    LidarObject o;
    o.id = id;
    o.point_m = front;
    o.point_covariance = 0.002 * Matrix2d::Identity();
    o.front_start_m = front + Vector2d(0.0, -0.2);
    o.front_end_m = front + Vector2d(0.0, 0.2);
    o.velocity_covariance = Matrix2d::Identity();
    o.class_pmf = {1.0, 0, 0, 0, 0, 0};
    o.dynamic = true;
    return o;
  };
  const Vector2d a(22.5, 0.0), b(23.4, 0.1);
  const auto frame = [&](TimeNs t, std::vector<LidarObject> lidar,
                         std::vector<StereoObject> camera) {
    LidarObjectFrame l;
    l.stamp = t;
    l.mount = kLidarMount;
    l.objects = std::move(lidar);
    StereoFrame s;
    s.stamp = t;
    s.mount = kCameraMount;
    s.objects = std::move(camera);
    return std::pair{l, s};
  };
  const auto first =
      frame(0, {walker_lidar(1, a - Vector2d(0.3, 0.0)), walker_lidar(2, b - Vector2d(0.3, 0.0))},
            {walker_camera(11, a), walker_camera(12, b)});
  const auto second =
      frame(80'000'000, {walker_lidar(2, b - Vector2d(0.3, 0.0))}, {walker_camera(11, a)});
  const auto stereo_of_lidar_2 = [](const FusedObjectFrame& f) {
    for (const FusedObject& o : f.objects) {
      if (o.lidar_id == 2u) return o.stereo_id;
    }
    return std::optional<std::uint32_t>{};
  };
  FusionOptions afresh;
  afresh.pair_memory_s = 0.0;
  for (const bool memory : {false, true}) {
    FusionEngine engine(memory ? FusionOptions{} : afresh);
    const FusedObjectFrame f1 = engine.Fuse(first.first, first.second);
    EXPECT_EQ(stereo_of_lidar_2(f1), 12u);
    const FusedObjectFrame f2 = engine.Fuse(second.first, second.second);
    if (memory) {
      EXPECT_FALSE(stereo_of_lidar_2(f2).has_value());
      EXPECT_EQ(f2.objects.size(), 2u);  // B the lidar's, A the camera's
    } else {
      EXPECT_EQ(stereo_of_lidar_2(f2), 11u);  // A's camera object on B's body
    }
  }
}

// Same input, same bytes out.
TEST(FusionEngineTest, Deterministic) {
  FusionEngine a, b;
  for (TimeNs t = 0; t <= 400'000'000; t += 80'000'000) {
    const FusedObjectFrame fa = a.Fuse(LidarAt(t), StereoAt(t - t % 50'000'000));
    const FusedObjectFrame fb = b.Fuse(LidarAt(t), StereoAt(t - t % 50'000'000));
    ASSERT_EQ(fa.objects.size(), fb.objects.size());
    for (std::size_t i = 0; i < fa.objects.size(); ++i) {
      EXPECT_EQ(fa.objects[i].point_m, fb.objects[i].point_m);
      EXPECT_EQ(fa.objects[i].point_covariance, fb.objects[i].point_covariance);
    }
  }
}

}  // namespace
}  // namespace lookout::fusion
