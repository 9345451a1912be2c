#include "lookout/app/tracking_stage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lookout/core/input_error.h"

namespace lookout::app {
namespace {

std::array<double, kAllObjectClasses.size()> Certain(ObjectClass c, double p = 1.0) {
  std::array<double, kAllObjectClasses.size()> pmf{};
  const double rest = (1.0 - p) / static_cast<double>(pmf.size() - 1);
  for (std::size_t i = 0; i < pmf.size(); ++i) {
    pmf[i] = kAllObjectClasses[i] == c ? p : rest;
  }
  return pmf;
}

// An object whose seen side runs from `a` to `b` (vehicle frame), seen by the camera.
fusion::FusedObject Object(ObjectClass c, Eigen::Vector2d a, Eigen::Vector2d b) {
  fusion::FusedObject o;
  o.front_start_m = a;
  o.front_end_m = b;
  o.point_m = 0.5 * (a + b);
  o.point_covariance = 0.01 * Eigen::Matrix2d::Identity();
  o.class_pmf = Certain(c);
  o.sensor_count = 2;
  o.stereo_id = 7;
  o.dynamic = true;
  return o;
}

fusion::FusedObjectFrame Frame(TimeNs stamp, std::vector<fusion::FusedObject> objects,
                               Pose2 ego = Pose2()) {
  fusion::FusedObjectFrame f;
  f.stamp = stamp;
  f.ego_pose = ego;
  f.objects = std::move(objects);
  return f;
}

// A car broadside on, 20 m ahead: its long side faces the lidar, the centre is half a width
// behind it. End on, the short side faces the lidar: half a length behind.
TEST(DetectionsFromFusedObjectsTest, CentreIsHalfTheDepthBehindTheSeenSide) {
  const DetectionOptions options;
  const auto side_on = DetectionsFromFusedObjects(
      Frame(0, {Object(ObjectClass::kCar, {20.0, -2.25}, {20.0, 2.25})}), options);
  ASSERT_EQ(side_on.size(), 1u);
  EXPECT_NEAR(side_on[0].position_m.x(), 20.9, 1e-12);
  EXPECT_NEAR(side_on[0].position_m.y(), 0.0, 1e-12);
  const auto end_on = DetectionsFromFusedObjects(
      Frame(0, {Object(ObjectClass::kCar, {20.0, 0.9}, {20.0, -0.9})}), options);
  ASSERT_EQ(end_on.size(), 1u);
  EXPECT_NEAR(end_on[0].position_m.x(), 22.25, 1e-12);
  // Behind the ego (a side seen from the other direction) the centre is further behind.
  const auto behind = DetectionsFromFusedObjects(
      Frame(0, {Object(ObjectClass::kCar, {-20.0, 0.9}, {-20.0, -0.9})}), options);
  EXPECT_NEAR(behind[0].position_m.x(), -22.25, 1e-12);
  // A pedestrian: a radius behind, along the line of sight (its segment is its width).
  const auto walker = DetectionsFromFusedObjects(
      Frame(0, {Object(ObjectClass::kPedestrian, {3.0, 4.3}, {3.0, 3.7})}), options);
  EXPECT_NEAR(walker[0].position_m.x(), 3.3, 1e-12);
  EXPECT_EQ(walker[0].object_class, ObjectClass::kPedestrian);
  EXPECT_EQ(walker[0].sensors, 2);
}

// A car crossing 20 m ahead, its long side seen in part (2.7 m of 4.5 m: shorter than the rule's
// 3.15 m). Without a velocity it is taken for the front, 2.25 m deep; moving along the side at
// 8 m/s (0.5 m/s sigma) it is the long side, 0.9 m deep. Moving across the side, the front.
// A velocity too uncertain or too slow to tell leaves the length to decide.
TEST(DetectionsFromFusedObjectsTest, TheObjectsMotionTellsWhichSideIsSeen) {
  const DetectionOptions options;
  const auto depth = [&](Eigen::Vector2d v, double sigma_mps) {
    fusion::FusedObject o = Object(ObjectClass::kCar, {20.0, -1.35}, {20.0, 1.35});
    o.velocity_mps = v;
    o.velocity_covariance = sigma_mps * sigma_mps * Eigen::Matrix2d::Identity();
    const auto d = DetectionsFromFusedObjects(Frame(0, {o}), options);
    EXPECT_EQ(d.size(), 1u);
    return d.empty() ? 0.0 : d[0].position_m.x() - 20.0;
  };
  EXPECT_NEAR(depth({0.0, 0.0}, 1.0), 2.25, 1e-12);
  EXPECT_NEAR(depth({0.0, 8.0}, 0.5), 0.9, 1e-12);
  EXPECT_NEAR(depth({3.0, -8.0}, 0.5), 0.9, 1e-12);   // 20.6 degrees off the side
  EXPECT_NEAR(depth({8.0, 0.0}, 0.5), 2.25, 1e-12);   // driving away: its rear
  EXPECT_NEAR(depth({0.0, 8.0}, 5.0), 2.25, 1e-12);   // not significantly moving
  EXPECT_NEAR(depth({0.0, 0.8}, 0.01), 2.25, 1e-12);  // slower than heading_min_speed_mps
}

// Where the motion cannot tell which side of a box is seen, the length decides the depth, and
// the covariance along the side's normal says the other depth is as likely: the two-point
// mixture's second moment about the chosen one, ((4.5 - 1.8) / 2)^2 / 2 for a car. Where the
// motion tells, no such term.
TEST(DetectionsFromFusedObjectsTest, ADepthTheMotionCannotTellIsUncertain) {
  const DetectionOptions options;
  const auto variance_along_normal = [&](Eigen::Vector2d v) {
    fusion::FusedObject o = Object(ObjectClass::kCar, {20.0, -1.35}, {20.0, 1.35});
    o.velocity_mps = v;
    o.velocity_covariance = 0.25 * Eigen::Matrix2d::Identity();
    const auto d = DetectionsFromFusedObjects(Frame(0, {o}), options);
    EXPECT_EQ(d.size(), 1u);
    return d.empty() ? 0.0 : d[0].covariance(0, 0);
  };
  const double known = variance_along_normal({0.0, 8.0});
  const double unknown = variance_along_normal({0.0, 0.0});
  EXPECT_NEAR(unknown - known, 0.5 * 1.35 * 1.35, 1e-9);
  // Across the normal (along the side) nothing changes.
  fusion::FusedObject still = Object(ObjectClass::kCar, {20.0, -1.35}, {20.0, 1.35});
  fusion::FusedObject moving = still;
  moving.velocity_mps = Eigen::Vector2d(0.0, 8.0);
  moving.velocity_covariance = 0.25 * Eigen::Matrix2d::Identity();
  EXPECT_NEAR(DetectionsFromFusedObjects(Frame(0, {still}), options)[0].covariance(1, 1),
              DetectionsFromFusedObjects(Frame(0, {moving}), options)[0].covariance(1, 1), 1e-12);
}

// The floor under a detection's covariance: centre_offset_sigma_two_m where both sensors saw
// the object (its fused covariance holds its errors), centre_offset_sigma_m where one did.
TEST(DetectionsFromFusedObjectsTest, AnObjectBothSensorsSawHasTheSmallerFloor) {
  const DetectionOptions options;
  ASSERT_LT(options.centre_offset_sigma_two_m, options.centre_offset_sigma_m);
  const fusion::FusedObject both = Object(ObjectClass::kPedestrian, {10.0, 0.3}, {10.0, -0.3});
  fusion::FusedObject camera_only = both;
  camera_only.sensor_count = 1;
  const auto d = DetectionsFromFusedObjects(Frame(0, {both, camera_only}), options);
  ASSERT_EQ(d.size(), 2u);
  // Across the side's normal the covariance is the point's and the floor alone.
  const double two = options.centre_offset_sigma_two_m * options.centre_offset_sigma_two_m;
  const double one = options.centre_offset_sigma_m * options.centre_offset_sigma_m;
  EXPECT_NEAR(d[0].covariance(1, 1), 0.01 + two, 1e-12);
  EXPECT_NEAR(d[1].covariance(1, 1), 0.01 + one, 1e-12);
  DetectionOptions bad;
  bad.centre_offset_sigma_two_m = -0.1;
  EXPECT_THROW(bad.Validate(), InputError);
}

// A lidar-only object of unknown class may be a walker (centre on its side) or a car (half a
// box behind): its centre is half the car's depth behind, with the variance of a uniform depth
// along the side's normal, and across it the covariance it had.
TEST(DetectionsFromFusedObjectsTest, AnUnknownObjectsCentreIsUncertainInDepth) {
  const DetectionOptions options;
  fusion::FusedObject head_on = Object(ObjectClass::kUnknown, {20.0, 0.9}, {20.0, -0.9});
  head_on.stereo_id.reset();
  head_on.sensor_count = 1;
  const auto d = DetectionsFromFusedObjects(Frame(0, {head_on}), options);
  ASSERT_EQ(d.size(), 1u);
  const double h =
      0.5 * options.footprints.car_length_m;  // the seen side is a car's front: 2.25 m deep
  EXPECT_NEAR(d[0].position_m.x(), 20.0 + 0.5 * h, 1e-12);
  EXPECT_NEAR(d[0].position_m.y(), 0.0, 1e-12);
  const double offset = options.centre_offset_sigma_m * options.centre_offset_sigma_m;
  EXPECT_NEAR(d[0].covariance(0, 0), 0.01 + h * h / 12.0 + offset, 1e-12);
  EXPECT_NEAR(d[0].covariance(1, 1), 0.01 + offset, 1e-12);
  EXPECT_NEAR(d[0].covariance(0, 1), 0.0, 1e-12);
  // Broadside (a side longer than a car's front), half a width deep: 0.45 m, variance 0.9^2/12.
  fusion::FusedObject side = Object(ObjectClass::kUnknown, {20.0, -2.25}, {20.0, 2.25});
  side.stereo_id.reset();
  side.sensor_count = 1;
  const auto s = DetectionsFromFusedObjects(Frame(0, {side}), options);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_NEAR(s[0].position_m.x(), 20.0 + 0.25 * options.footprints.car_width_m, 1e-12);
  EXPECT_NEAR(
      s[0].covariance(0, 0),
      0.01 + 0.25 * options.footprints.car_width_m * options.footprints.car_width_m / 12.0 + offset,
      1e-12);
}

// A lidar-only object of unknown class whose seen side is walker-sized (0.5 m, under
// walker_side_max_m) is centred a walker's radius behind it, with walker_depth_sigma_m along
// the side's normal; 0.8 m of side is taken for a car's as before.
TEST(DetectionsFromFusedObjectsTest, AWalkerSizedUnknownObjectIsCentredAWalkersRadiusBehind) {
  const DetectionOptions options;
  const auto detect = [&](double side_m) {
    fusion::FusedObject o =
        Object(ObjectClass::kUnknown, {10.0, 0.5 * side_m}, {10.0, -0.5 * side_m});
    o.stereo_id.reset();
    o.sensor_count = 1;
    const auto d = DetectionsFromFusedObjects(Frame(0, {o}), options);
    EXPECT_EQ(d.size(), 1u);
    return d.empty() ? tracking::Detection{} : d[0];
  };
  const double offset = options.centre_offset_sigma_m * options.centre_offset_sigma_m;
  const tracking::Detection walker = detect(0.5);
  EXPECT_NEAR(walker.position_m.x(), 10.0 + options.footprints.pedestrian_radius_m, 1e-12);
  EXPECT_NEAR(walker.covariance(0, 0),
              0.01 + options.walker_depth_sigma_m * options.walker_depth_sigma_m + offset, 1e-12);
  EXPECT_NEAR(walker.covariance(1, 1), 0.01 + offset, 1e-12);
  const double h = 0.5 * options.footprints.car_length_m;  // its front: 2.25 m deep
  EXPECT_NEAR(detect(0.8).position_m.x(), 10.0 + 0.5 * h, 1e-12);
}

// The same broadside object of unknown class holds each box class's centre for a track that
// knows its class: a cyclist's and a car's half a width behind the side, a truck's half a
// length (4.5 m is shorter than half a truck's length and width: its end), each with the
// covariance of the seen point alone; none for a walker, and none when the class is known.
TEST(DetectionsFromFusedObjectsTest, AnUnknownObjectHoldsEachBoxsCentre) {
  const DetectionOptions options;
  fusion::FusedObject side = Object(ObjectClass::kUnknown, {20.0, -2.25}, {20.0, 2.25});
  side.stereo_id.reset();
  side.sensor_count = 1;
  const auto d = DetectionsFromFusedObjects(Frame(0, {side}), options);
  ASSERT_EQ(d.size(), 1u);
  const double offset = options.centre_offset_sigma_m * options.centre_offset_sigma_m;
  for (const ObjectClass c : {ObjectClass::kCyclist, ObjectClass::kCar, ObjectClass::kTruck}) {
    const auto& centre = d[0].class_centres[static_cast<std::size_t>(c)];
    ASSERT_TRUE(centre.has_value());
    const ClassFootprints::Box box = options.footprints.BoxOf(c);
    const double depth = c == ObjectClass::kTruck ? box.length_m : box.width_m;
    EXPECT_NEAR(centre->position_m.x(), 20.0 + 0.5 * depth, 1e-12);
    EXPECT_NEAR(centre->position_m.y(), 0.0, 1e-12);
    // No velocity to tell which side is seen: the other depth is as likely, along the normal.
    const double half_gap = 0.5 * (box.length_m - box.width_m);
    Eigen::Matrix2d expected = (0.01 + offset) * Eigen::Matrix2d::Identity();
    expected(0, 0) += 0.5 * half_gap * half_gap;
    EXPECT_TRUE(centre->covariance.isApprox(expected)) << centre->covariance;
  }
  EXPECT_FALSE(d[0].class_centres[static_cast<std::size_t>(ObjectClass::kPedestrian)]);
  const auto car = DetectionsFromFusedObjects(
      Frame(0, {Object(ObjectClass::kCar, {20.0, -2.25}, {20.0, 2.25})}), options);
  for (const auto& centre : car[0].class_centres) EXPECT_FALSE(centre.has_value());
}

// Detections are in the odometry frame: the frame's ego pose carries point and covariance.
TEST(DetectionsFromFusedObjectsTest, MovesIntoTheOdometryFrame) {
  fusion::FusedObject o = Object(ObjectClass::kUnknown, {10.0, 0.9}, {10.0, -0.9});
  o.point_covariance << 4.0, 0.0, 0.0, 1.0;
  DetectionOptions options;
  options.centre_offset_sigma_m = 0.0;
  options.centre_offset_sigma_two_m = 0.0;
  const Pose2 ego(5.0, -3.0, kPi / 2.0);
  const auto d = DetectionsFromFusedObjects(Frame(0, {o}, ego), options);
  ASSERT_EQ(d.size(), 1u);
  // Unknown, a car's front wide: the centre 1.125 m behind the point along the side's normal
  // (vehicle x), with variance 2.25^2 / 12 there (AnUnknownObjectsCentreIsUncertainInDepth).
  const double depth = 1.125, depth_variance = 2.25 * 2.25 / 12.0;
  EXPECT_NEAR(d[0].position_m.x(), 5.0, 1e-12);
  EXPECT_NEAR(d[0].position_m.y(), 7.0 + depth, 1e-12);
  EXPECT_NEAR(d[0].covariance(0, 0), 1.0, 1e-12);  // the long axis now lies along y
  EXPECT_NEAR(d[0].covariance(1, 1), 4.0 + depth_variance, 1e-12);
}

TEST(DetectionsFromFusedObjectsTest, LeavesOutLidarOnlyObjectsInsideABuilding) {
  // A wall along x = 10 (the building beyond it), the ego at the origin looking along x. A
  // lidar-only "walker" seen on the wall has its centre a radius (0.3 m) behind it, inside: a
  // ghost of the wall. A walker beside the wall (its seen side 0.5 m before it) stays in, and
  // so does the same ghost's position when the camera saw it (fusion paired a camera object).
  const BuildingOutlines block = {{{10, -20}, {30, -20}, {30, 20}, {10, 20}}};
  fusion::FusedObject ghost = Object(ObjectClass::kPedestrian, {10.0, 2.0}, {10.0, 2.6});
  ghost.stereo_id.reset();
  ghost.sensor_count = 1;
  fusion::FusedObject walker = ghost;
  walker.front_start_m = {9.5, -2.0};
  walker.front_end_m = {9.5, -1.4};
  walker.point_m = {9.5, -1.7};
  const fusion::FusedObject seen = Object(ObjectClass::kPedestrian, {10.0, 5.0}, {10.0, 5.6});
  std::int64_t left_out = 0;
  const auto d = DetectionsFromFusedObjects(Frame(0, {ghost, walker, seen}), {}, {},
                                            std::nullopt, block, &left_out);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_NEAR(d[0].position_m.x(), 9.8, 1e-9);  // the walker, 0.2 m before the wall
  EXPECT_EQ(d[1].sensors, 2);
  EXPECT_EQ(left_out, 1);
  // Without a map, or in another frame where the block is elsewhere, the ghost is tracked.
  EXPECT_EQ(DetectionsFromFusedObjects(Frame(0, {ghost, walker, seen}), {}).size(), 3u);
  EXPECT_EQ(DetectionsFromFusedObjects(Frame(0, {ghost}, Pose2(0.0, 50.0, 0.0)), {}, {},
                                       std::nullopt, block)
                .size(),
            1u);
  // Deeper than the margin only: a margin of 0.4 m keeps the ghost (0.3 m inside).
  DetectionOptions wide;
  wide.building_margin_m = 0.4;
  EXPECT_EQ(DetectionsFromFusedObjects(Frame(0, {ghost}), wide, {}, std::nullopt, block).size(),
            1u);
}

TEST(DetectionsFromFusedObjectsTest, LeavesOutPolesAndStaticLidarOnlyObjects) {
  fusion::FusedObject pole = Object(ObjectClass::kPole, {5.0, 0.0}, {5.0, 0.2});
  fusion::FusedObject parked = Object(ObjectClass::kCar, {8.0, 3.0}, {12.0, 3.0});
  parked.stereo_id.reset();
  parked.sensor_count = 1;
  parked.dynamic = false;
  fusion::FusedObject standing = Object(ObjectClass::kPedestrian, {6.0, 1.0}, {6.0, 1.6});
  standing.dynamic = false;  // seen by the camera: a road user standing still stays in
  const auto d = DetectionsFromFusedObjects(Frame(0, {pole, parked, standing}), {});
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].object_class, ObjectClass::kPedestrian);
  DetectionOptions keep;
  keep.keep_static_lidar_objects = true;
  EXPECT_EQ(DetectionsFromFusedObjects(Frame(0, {pole, parked, standing}), keep).size(), 2u);
}

// What the camera says about each object: with a camera frame, a lidar-only object in its view
// with no camera object near is unseen; one beside a camera object that fusion did not pair,
// or outside the view (to the side, or beyond its depth), is no evidence; a camera object is
// seen from its camera track's second frame on; without a camera frame nothing is evidence.
TEST(DetectionsFromFusedObjectsTest, TheCameraSpeaksForAndAgainstObjects) {
  const auto lidar_only = [](Eigen::Vector2d a, Eigen::Vector2d b) {
    fusion::FusedObject o = Object(ObjectClass::kCar, a, b);
    o.stereo_id.reset();
    o.sensor_count = 1;
    return o;
  };
  const fusion::FusedObject ghost = lidar_only({15.0, 4.0}, {15.0, 5.0});       // in view
  const fusion::FusedObject beside = lidar_only({8.0, -12.0}, {8.0, -11.0});    // 55 deg off
  const fusion::FusedObject far = lidar_only({40.0, 0.0}, {40.0, 1.0});         // beyond 35 m
  const fusion::FusedObject unpaired = lidar_only({20.0, -3.0}, {20.0, -2.0});  // camera beside
  fusion::FusedObject camera = Object(ObjectClass::kCar, {20.1, -2.9}, {20.1, -1.9});
  camera.sensor_count = 1;
  const fusion::FusedObjectFrame frame = Frame(0, {ghost, beside, far, unpaired, camera});
  const Pose2 mount(0.8, 0.0, 0.0);
  std::vector<CameraHistory> history(5);
  history[4] = {ObjectClass::kCar, 2};
  using tracking::CameraEvidence;
  const auto d = DetectionsFromFusedObjects(frame, {}, history, mount);
  ASSERT_EQ(d.size(), 5u);
  EXPECT_EQ(d[0].camera, CameraEvidence::kUnseen);
  EXPECT_EQ(d[1].camera, CameraEvidence::kNone);
  EXPECT_EQ(d[2].camera, CameraEvidence::kNone);
  EXPECT_EQ(d[3].camera, CameraEvidence::kNone);
  EXPECT_EQ(d[4].camera, CameraEvidence::kSeen);
  history[4].frames = 1;  // a camera object seen once may be one of its false objects
  EXPECT_EQ(DetectionsFromFusedObjects(frame, {}, history, mount)[4].camera, CameraEvidence::kNone);
  for (const auto& x : DetectionsFromFusedObjects(frame, {}, history, std::nullopt)) {
    EXPECT_NE(x.camera, CameraEvidence::kUnseen) << "no camera frame, no silence";
  }
}

tracking::Track TrackWith(Eigen::Vector2d velocity, double velocity_sigma, double log_odds) {
  tracking::Track t;
  t.status = tracking::TrackStatus::kConfirmed;
  t.state.mean = Eigen::Vector4d(10.0, 0.0, velocity.x(), velocity.y());
  t.state.cov = Eigen::Matrix4d::Identity() * 0.01;
  t.state.cov.bottomRightCorner<2, 2>() *= velocity_sigma * velocity_sigma / 0.01;
  t.existence_log_odds = log_odds;
  return t;
}

// Tracks without the camera's support are road users only while they move, surely: the grid's
// ghosts on static structure stand still.
// occluded-pedestrian: a walker 17.5 m away behind a nearer one (8 m) on the camera's line of
// sight. The camera cannot see it, so its silence says nothing; without the near walker, or
// with the near one only 1.5 m ahead (a second segment of one road user), it does.
TEST(DetectionsFromFusedObjectsTest, TheCameraSaysNothingOfWhatItCannotSee) {
  const auto walker = [](double x, bool camera) {
    fusion::FusedObject o = Object(ObjectClass::kPedestrian, {x, 0.2}, {x, -0.2});
    o.lidar_id = 1;
    if (!camera) {
      o.stereo_id.reset();
      o.sensor_count = 1;
    }
    return o;
  };
  const Pose2 mount(0.8, 0.0, 0.0);
  const auto far_evidence = [&](std::vector<fusion::FusedObject> objects) {
    const auto d = DetectionsFromFusedObjects(Frame(0, objects), {}, {}, mount);
    return d.empty() ? tracking::CameraEvidence::kSeen : d.front().camera;
  };
  using tracking::CameraEvidence;
  EXPECT_EQ(far_evidence({walker(17.5, false)}), CameraEvidence::kUnseen);
  EXPECT_EQ(far_evidence({walker(17.5, false), walker(8.0, true)}), CameraEvidence::kNone);
  EXPECT_EQ(far_evidence({walker(17.5, false), walker(16.0, true)}), CameraEvidence::kUnseen);
  // Beside the line of sight (2 m off at 8 m: 14 degrees), the near one hides nothing.
  fusion::FusedObject aside = walker(8.0, true);
  aside.front_start_m.y() += 2.0;
  aside.front_end_m.y() += 2.0;
  EXPECT_EQ(far_evidence({walker(17.5, false), aside}), CameraEvidence::kUnseen);
  // An occluder the lidar did not see (the camera's own object) is not taken for one.
  fusion::FusedObject camera_only = walker(8.0, true);
  camera_only.lidar_id.reset();
  EXPECT_EQ(far_evidence({walker(17.5, false), camera_only}), CameraEvidence::kUnseen);
}

TEST(RoadUserTest, TracksWithoutTheCameraMustMove) {
  const DetectionOptions o;
  EXPECT_FALSE(IsRoadUser(TrackWith({0.2, 0.1}, 0.1, 0.0), o)) << "standing";
  EXPECT_FALSE(IsRoadUser(TrackWith({1.5, 0.0}, 1.0, 0.0), o)) << "not surely moving";
  EXPECT_TRUE(IsRoadUser(TrackWith({1.5, 0.0}, 0.3, 0.0), o));
  EXPECT_TRUE(IsRoadUser(TrackWith({8.0, 0.0}, 2.0, -1.0), o));
  EXPECT_TRUE(IsRoadUser(TrackWith({0.0, 0.0}, 0.1, 2.9), o)) << "a walker the camera sees waiting";
}

// A hidden track keeps the motion it showed when it was last detected: its prediction's
// growing velocity covariance is no evidence that it stopped. A missed one is judged afresh.
TEST(RoadUserTest, AHiddenTrackKeepsTheMotionItShowed) {
  const DetectionOptions o;
  tracking::Track hidden = TrackWith({1.3, 0.0}, 1.0, 0.0);  // not surely moving by itself
  hidden.coasting = true;
  EXPECT_FALSE(ShowsMotion(hidden, o, false));
  EXPECT_TRUE(ShowsMotion(hidden, o, true)) << "moved when last detected";
  EXPECT_TRUE(IsRoadUser(hidden, o, true));
  tracking::Track missed = hidden;
  missed.misses = 1;
  EXPECT_FALSE(ShowsMotion(missed, o, true)) << "missed where it could be seen";
  tracking::Track detected = hidden;
  detected.coasting = false;
  EXPECT_FALSE(ShowsMotion(detected, o, true)) << "a detection is judged afresh";
  tracking::Track standing = TrackWith({0.2, 0.1}, 0.1, 0.0);
  standing.coasting = true;
  EXPECT_FALSE(ShowsMotion(standing, o, false));
}

// One frame in which the camera calls its pedestrian a car does not change the class.
TEST(CameraTrackHistoryTest, OneConfusedFrameKeepsTheClassOfTheCamerasTrack) {
  CameraTrackHistory history;
  fusion::FusedObject o = Object(ObjectClass::kPedestrian, {6.0, 1.0}, {6.0, 1.6});
  o.class_pmf = Certain(ObjectClass::kPedestrian, 0.9);
  for (int k = 0; k < 3; ++k) {
    const std::vector<CameraHistory> h = history.Update(Frame(FromSeconds(0.05 * k), {o}));
    EXPECT_EQ(h[0].object_class, ObjectClass::kPedestrian);
    EXPECT_EQ(h[0].frames, k + 1);
  }
  o.class_pmf = Certain(ObjectClass::kCar, 0.9);
  EXPECT_EQ(history.Update(Frame(FromSeconds(0.15), {o}))[0].object_class,
            ObjectClass::kPedestrian);
  // Another camera track id has its own history; a lidar-only object keeps its own class.
  o.stereo_id = 8;
  EXPECT_EQ(history.Update(Frame(FromSeconds(0.2), {o}))[0].object_class, ObjectClass::kCar);
  o.stereo_id.reset();
  const CameraHistory lidar_only = history.Update(Frame(FromSeconds(0.25), {o}))[0];
  EXPECT_EQ(lidar_only.object_class, ObjectClass::kCar);
  EXPECT_EQ(lidar_only.frames, 0);
  // An id unseen for longer than the memory starts afresh.
  o.stereo_id = 7;
  const CameraHistory again = history.Update(Frame(FromSeconds(2.0), {o}))[0];
  EXPECT_EQ(again.object_class, ObjectClass::kCar);
  EXPECT_EQ(again.frames, 1);
}

// A walker crossing at 1.5 m/s, seen by both sensors every 80 ms: confirmed at its first update
// after the one that started it, then followed; time going backwards and NaN objects are
// refused or dropped with a warning, never a crash; empty frames make the track coast.
// Both trackers, each as the stage's tracker.
class TrackingStageTest : public ::testing::TestWithParam<TrackerKind> {};

TEST_P(TrackingStageTest, TracksAWalkerAndRefusesBadInputWithAWarning) {
  TrackingStageOptions options;
  options.tracker = GetParam();
  TrackingStage stage(options);
  auto walker_at = [](double t) {
    const double y = -5.0 + 1.5 * t;
    return Object(ObjectClass::kPedestrian, {10.0, y - 0.3}, {10.0, y + 0.3});
  };
  for (int k = 0; k < 10; ++k) {
    const double t = 0.08 * k;
    stage.Step(Frame(FromSeconds(t), {walker_at(t)}));
  }
  ASSERT_EQ(stage.tracks().size(), 1u);
  const tracking::Track track = stage.tracks()[0];
  EXPECT_NEAR(track.Position().x(), 10.3, 0.1);
  EXPECT_NEAR(track.Position().y(), -5.0 + 1.5 * 0.72, 0.1);
  EXPECT_NEAR(track.Velocity().y(), 1.5, 0.3);
  EXPECT_EQ(stage.warning_count(), 0);

  stage.Step(Frame(FromSeconds(0.5), {walker_at(0.5)}));  // back in time
  EXPECT_EQ(stage.warning_count(), 1);
  ASSERT_EQ(stage.warnings().size(), 1u);
  EXPECT_NE(stage.warnings()[0].find("refused"), std::string::npos) << stage.warnings()[0];
  EXPECT_EQ(stage.last_stamp(), FromSeconds(0.72));
  ASSERT_EQ(stage.tracks().size(), 1u);
  EXPECT_EQ(stage.tracks()[0].stamp, track.stamp) << "a refused frame changes nothing";

  fusion::FusedObject broken = walker_at(0.8);
  broken.point_m.x() = std::numeric_limits<double>::quiet_NaN();
  stage.Step(Frame(FromSeconds(0.8), {broken, walker_at(0.8)}));
  EXPECT_EQ(stage.warning_count(), 2);
  EXPECT_NE(stage.warnings()[1].find("dropped"), std::string::npos) << stage.warnings()[1];
  EXPECT_EQ(stage.tracker().dropped_detections(), 1);
  ASSERT_EQ(stage.tracks().size(), 1u);

  stage.Step(Frame(FromSeconds(0.88), {}));
  ASSERT_EQ(stage.tracks().size(), 1u);
  EXPECT_TRUE(stage.tracks()[0].coasting);
  EXPECT_EQ(stage.step_ms().size(), 13u);
  if (GetParam() == TrackerKind::kGnn) {
    EXPECT_EQ(stage.baseline(), nullptr) << "the GNN needs no GNN beside it";
  } else {
    ASSERT_NE(stage.baseline(), nullptr);
    ASSERT_EQ(stage.baseline_tracks().size(), 1u);
    EXPECT_NEAR(stage.baseline_tracks()[0].Position().y(), -5.0 + 1.5 * 0.88, 0.2);
    EXPECT_EQ(stage.baseline_step_ms().size(), 13u);
  }
}

// A walker crossing 8 m ahead of the lidar at 1.5 m/s goes behind a wall 4 m ahead for 3 s
// (37 scans, more than a walker's 25 misses). Given the cycle's scans, the stage knows it was
// hidden, and the same track picks it up again; without them the track is deleted behind the
// wall and the walker comes out under a new one. The ego stands at (100, 50) facing north, the
// lidar 2 m ahead of its origin: the view maps the odometry frame through both.
TEST_P(TrackingStageTest, AWalkerHiddenBehindAWallInTheScanKeepsItsTrack) {
  const Pose2 ego(100.0, 50.0, kPi / 2.0);
  const auto walker_at = [](double t) {
    const double y = -4.0 + 1.5 * t;
    return Object(ObjectClass::kPedestrian, {10.0, y - 0.3}, {10.0, y + 0.3});
  };
  const auto hidden = [](double t) { return t > 1.0 && t < 4.0; };
  const auto scan_at = [&](double t) {
    LidarScan scan;
    scan.stamp = FromSeconds(t);
    scan.mount = Pose2(2.0, 0.0, 0.0);
    scan.angle_min_rad = -80.0 * kPi / 180.0;
    scan.angle_increment_rad = 0.25 * kPi / 180.0;
    scan.max_range_m = 100.0;
    scan.ranges_m.assign(641, std::numeric_limits<float>::infinity());
    for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
      const double bearing = scan.BeamAngle(i);
      if (hidden(t) && std::abs(bearing) < 35.0 * kPi / 180.0) {
        scan.ranges_m[i] = static_cast<float>(4.0 / std::cos(bearing));  // the wall x = 6
      }
    }
    return scan;
  };
  const auto run = [&](bool with_scans) {
    TrackingStageOptions options;
    options.tracker = GetParam();
    TrackingStage stage(options);
    std::uint32_t before = 0;
    for (int k = 0; k <= 60; ++k) {
      const double t = 0.08 * k;
      std::vector<fusion::FusedObject> objects;
      if (!hidden(t)) objects.push_back(walker_at(t));
      const LidarScan scan = scan_at(t);
      stage.Step(Frame(FromSeconds(t), objects, ego), std::nullopt, with_scans ? &scan : nullptr);
      if (k == 12) {
        EXPECT_EQ(stage.tracks().size(), 1u);
        if (!stage.tracks().empty()) before = stage.tracks()[0].id;
      }
    }
    EXPECT_EQ(stage.tracks().size(), 1u);
    return std::pair(before, stage.tracks().empty() ? 0u : stage.tracks()[0].id);
  };
  const auto [before, after] = run(true);
  EXPECT_NE(before, 0u);
  EXPECT_EQ(after, before) << "the same track on both sides of the wall";
  const auto [before_open, after_open] = run(false);
  EXPECT_NE(after_open, before_open) << "deleted behind the wall without the scans";
}

INSTANTIATE_TEST_SUITE_P(Trackers, TrackingStageTest,
                         ::testing::Values(TrackerKind::kMht, TrackerKind::kGnn),
                         [](const auto& param_info) {
                           return std::string(ToString(param_info.param));
                         });

TEST(TrackingStageDefaultsTest, TheMhtTracksWithTheGnnBesideIt) {
  const TrackingStage stage;
  EXPECT_EQ(stage.kind(), TrackerKind::kMht);
  EXPECT_NE(dynamic_cast<const tracking::MhtTracker*>(&stage.tracker()), nullptr);
  EXPECT_NE(dynamic_cast<const tracking::GnnTracker*>(stage.baseline()), nullptr);
}

TEST(TrackingStageOptionsTest, OptionsNameTheBadField) {
  TrackingStageOptions o;
  o.detections.footprints.car_width_m = 0.0;
  try {
    o.Validate();
    FAIL() << "accepted a zero car width";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("car_width_m"), std::string::npos) << e.what();
  }
  o.detections.footprints.car_width_m = 1.8;
  o.detections.building_margin_m = -0.1;
  try {
    o.Validate();
    FAIL() << "accepted a negative building margin";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("building_margin_m"), std::string::npos) << e.what();
  }
  o.detections.building_margin_m = 0.15;
  o.mht.hypotheses_m = 0;
  try {
    o.Validate();
    FAIL() << "accepted m = 0";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hypotheses_m"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ParseTrackerKind("mht"), TrackerKind::kMht);
  EXPECT_EQ(ParseTrackerKind("gnn"), TrackerKind::kGnn);
  EXPECT_FALSE(ParseTrackerKind("kalman").has_value());
}

}  // namespace
}  // namespace lookout::app
