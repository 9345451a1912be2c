#pragma once

// The simulated stereo camera of the seed 004 vehicle (section V): a list of objects per frame,
// each an oriented box on the ground plane with class, speed and variances, in the camera
// frame (x along the optical axis, y left).
//
// Which actors it reports: an actor is a candidate when its true centre lies within the field
// of view (|bearing| <= fov/2), its depth x is in (0, max_depth], and some of it is visible
// (visible fraction > 0 in StereoFan). A candidate is reported unless a miss draw (miss_rate)
// drops it. Reported with the actor's index + 1 as its id, a camera track id that stays the
// same for as long as the actor is tracked.
//
// NOISE MODEL (StereoNoiseModel, defaults below). The noise of every reported quantity is
// drawn from exactly the covariance reported with it, evaluated at the true position, so a
// consumer's NEES is chi-square distributed and consistency tests downstream are meaningful.
// - Centre. Stereo triangulation: depth z = f B / d for disparity d (px), focal length f (px)
//   and baseline B (m), so a disparity error sigma_d gives a depth error
//       sigma_z(z) = z^2 sigma_d / (f B)      (+ a floor, in quadrature)
//   which moves the point along its line of sight (the pixel, hence the ray, is fixed): along
//   the ray the error is sigma_z r / z = sigma_z / cos(bearing), r the range. The image
//   position error sigma_theta (rad) moves it across the ray by r sigma_theta (+ the floor).
//   The covariance is diagonal in (along the ray, across the ray) axes and rotated by the
//   bearing into the camera frame. Defaults f = 800 px, B = 0.3 m, sigma_d = 0.25 px give
//   sigma_z = 1.28 m at 35 m and 0.026 m at 5 m; sigma_theta = 0.002 rad gives 7 cm at 35 m.
// - Yaw: Gaussian, yaw_sigma_rad.
// - Speeds: the object's velocity over the ground (world frame), expressed in the camera
//   frame's axes, each component with Gaussian noise of sigma_v(z) = speed_sigma_mps and
//   speed_sigma_per_depth (1/s) times z in quadrature. Over the ground, not relative to the
//   ego: the seed's 6D stereo estimates its own ego motion and reports object motion in the
//   scene (section V.B), and a still pole then reports zero speed whatever the ego does.
// - Length and width: the truth (pedestrians, circles of radius r: 2r by 2r); the seed
//   reports no size variance, so no size noise is added.
// - Class: the true class with probability class_accuracy, otherwise one of the other five
//   of {unknown, pedestrian, cyclist, car, truck, pole}, uniformly.
// False objects: Poisson(false_rate) per frame, uniform in bearing over the field of view
// and in depth over [false_min_depth_m, max_depth], of a uniformly random class, a random
// small box and heading, and zero true speed (clutter does not move); their noise and
// covariances follow the same model. Their ids start at kFalseObjectIdBase and are new each
// frame (a false object is never tracked over frames).
//
// Randomness: frame k draws from DeriveSeed(seed, "stereo", k) split into one stream per actor
// (by its index) and one for false objects, so an actor's noise does not depend on which other
// actors are present.
//
// History: each object's tracking history is 1 here; Simulator::Run counts the consecutive
// frames in which an id was reported (an actor missed for a frame starts again at 1).

#include <Eigen/Core>
#include <cstdint>
#include <span>

#include "lookout/core/messages.h"
#include "lookout/core/object_class.h"
#include "lookout/core/pose2.h"
#include "lookout/core/time.h"
#include "lookout/sim/raycast.h"
#include "lookout/sim/scenario.h"

namespace lookout::sim {

struct StereoNoiseModel {
  double focal_length_px = 800.0;
  double baseline_m = 0.3;
  double disparity_sigma_px = 0.25;
  double bearing_sigma_rad = 0.002;
  double position_sigma_floor_m = 0.02;  // calibration and box-fitting error at short range
  double yaw_sigma_rad = 0.05;
  double speed_sigma_mps = 0.3;
  double speed_sigma_per_depth_per_s = 0.02;  // (m/s) per metre of depth
  double visibility_fan_resolution_rad = 0.1 * kPi / 180.0;
  double false_min_depth_m = 2.0;
  double false_length_min_m = 0.5, false_length_max_m = 3.0;
  double false_width_min_m = 0.5, false_width_max_m = 2.0;

  // Throws std::invalid_argument naming the first field out of range.
  void Validate() const;

  double DepthSigma(double depth_m) const;  // sigma_z(z), floor included
  double SpeedSigma(double depth_m) const;  // sigma_v(z), each component
  // Covariance (m^2) of a centre reported at `center_camera_m` (camera frame, depth > 0).
  Eigen::Matrix2d CenterCovariance(const Eigen::Vector2d& center_camera_m) const;
};

// Ids of false objects: at and above this, below it an actor's index + 1.
inline constexpr std::uint32_t kFalseObjectIdBase = 0x80000000u;

// What the camera could see of one actor at the frame's time (world frame).
struct StereoTarget {
  int actor_index = 0;
  ObjectClass object_class = ObjectClass::kCar;
  Pose2 pose;                                            // footprint centre and heading
  Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();  // over the ground
  double length_m = 0.0;
  double width_m = 0.0;
  double visible_fraction = 0.0;  // from CastFan(StereoFan(...))
};

// The camera frame in the vehicle frame.
Pose2 StereoMount(const StereoOptions& options);
// The visibility fan of a camera at `camera_pose` (world frame): the whole field of view at
// the model's resolution, out to the range of the field's far corners
// (max_depth / cos(fov/2)), so that every point of depth <= max_depth is covered.
Fan StereoFan(const StereoOptions& options, const StereoNoiseModel& model,
              const Pose2& camera_pose);

// Frame `frame_index` at `stamp` of a camera at `camera_pose` (world frame). `frame_seed` is
// DeriveSeed(scenario seed, "stereo", frame_index). Pure.
StereoFrame MakeStereoFrame(const StereoOptions& options, const StereoNoiseModel& model,
                            TimeNs stamp, int frame_index, const Pose2& camera_pose,
                            std::span<const StereoTarget> targets, std::uint64_t frame_seed);

}  // namespace lookout::sim
