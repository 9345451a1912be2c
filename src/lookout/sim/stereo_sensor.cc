#include "lookout/sim/stereo_sensor.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lookout/core/random.h"

namespace lookout::sim {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

// More than this many false objects in one frame is never drawn at sane rates; the cap bounds
// the id range a frame uses.
constexpr int kMaxFalseObjectsPerFrame = 64;

// Poisson by multiplying uniforms (Knuth): exact, and fast for the small means used here.
int DrawPoisson(Rng& rng, double mean) {
  const double limit = std::exp(-mean);
  int k = 0;
  double product = rng.Uniform();
  while (product > limit && k < kMaxFalseObjectsPerFrame) {
    ++k;
    product *= rng.Uniform();
  }
  return k;
}

ObjectClass ConfuseClass(Rng& rng, ObjectClass truth, double class_accuracy) {
  if (rng.Bernoulli(class_accuracy)) return truth;
  // One of the other classes, uniformly.
  auto pick = rng.UniformIndex(kAllObjectClasses.size() - 1);
  for (const ObjectClass c : kAllObjectClasses) {
    if (c == truth) continue;
    if (pick-- == 0) return c;
  }
  return truth;  // unreachable: truth is one of kAllObjectClasses
}

// A Gaussian sample with covariance L L^T.
Vector2d DrawCorrelated(Rng& rng, const Matrix2d& cholesky) {
  const double n0 = rng.Normal();
  const double n1 = rng.Normal();
  return cholesky * Vector2d(n0, n1);
}

struct CenterNoise {
  Matrix2d covariance;
  Matrix2d cholesky;
};

// The centre covariance and a square root of it, built together from the line-of-sight axes.
CenterNoise CenterNoiseAt(const StereoNoiseModel& model, const Vector2d& center_camera_m) {
  const double depth_m = center_camera_m.x();
  const double range_m = center_camera_m.norm();
  const double along_m = model.DepthSigma(depth_m) * range_m / depth_m;
  const double across_m =
      std::hypot(range_m * model.bearing_sigma_rad, model.position_sigma_floor_m);
  const double bearing = std::atan2(center_camera_m.y(), center_camera_m.x());
  const Matrix2d rotation = Pose2(0.0, 0.0, bearing).Rotation();
  CenterNoise noise;
  noise.cholesky = rotation * Vector2d(along_m, across_m).asDiagonal();
  noise.covariance = noise.cholesky * noise.cholesky.transpose();
  return noise;
}

// Fills the noisy part of an object whose true centre, heading and velocity are given in the
// camera frame; draws centre (2), yaw (1), speeds (2) in that order.
void AddMeasurementNoise(const StereoNoiseModel& model, const Vector2d& center_camera_m,
                         double yaw_camera_rad, const Vector2d& velocity_camera_mps, Rng& rng,
                         StereoObject& object) {
  const CenterNoise noise = CenterNoiseAt(model, center_camera_m);
  object.center_m = center_camera_m + DrawCorrelated(rng, noise.cholesky);
  object.center_covariance = noise.covariance;
  object.yaw_rad = WrapAngle(rng.Normal(yaw_camera_rad, model.yaw_sigma_rad));
  object.yaw_variance = model.yaw_sigma_rad * model.yaw_sigma_rad;
  const double speed_sigma = model.SpeedSigma(center_camera_m.x());
  object.speed_longitudinal_mps = rng.Normal(velocity_camera_mps.x(), speed_sigma);
  object.speed_lateral_mps = rng.Normal(velocity_camera_mps.y(), speed_sigma);
  object.speed_variance = speed_sigma * speed_sigma;
}

void Require(bool ok, const char* field, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("StereoNoiseModel.") + field + ": " + what);
}

}  // namespace

void StereoNoiseModel::Validate() const {
  Require(focal_length_px > 0.0, "focal_length_px", "must be > 0");
  Require(baseline_m > 0.0, "baseline_m", "must be > 0");
  Require(disparity_sigma_px >= 0.0, "disparity_sigma_px", "must be >= 0");
  Require(bearing_sigma_rad >= 0.0, "bearing_sigma_rad", "must be >= 0");
  // A strictly positive floor keeps every covariance invertible, even at zero depth noise.
  Require(position_sigma_floor_m > 0.0, "position_sigma_floor_m", "must be > 0");
  Require(yaw_sigma_rad >= 0.0, "yaw_sigma_rad", "must be >= 0");
  Require(speed_sigma_mps >= 0.0, "speed_sigma_mps", "must be >= 0");
  Require(speed_sigma_per_depth_per_s >= 0.0, "speed_sigma_per_depth_per_s", "must be >= 0");
  Require(visibility_fan_resolution_rad > 0.0, "visibility_fan_resolution_rad", "must be > 0");
  Require(false_min_depth_m > 0.0, "false_min_depth_m", "must be > 0");
  Require(false_length_min_m > 0.0 && false_length_min_m <= false_length_max_m,
          "false_length_min_m", "must be in (0, false_length_max_m]");
  Require(false_width_min_m > 0.0 && false_width_min_m <= false_width_max_m,
          "false_width_min_m", "must be in (0, false_width_max_m]");
}

double StereoNoiseModel::DepthSigma(double depth_m) const {
  const double disparity_term =
      depth_m * depth_m * disparity_sigma_px / (focal_length_px * baseline_m);
  return std::hypot(disparity_term, position_sigma_floor_m);
}

double StereoNoiseModel::SpeedSigma(double depth_m) const {
  return std::hypot(speed_sigma_mps, speed_sigma_per_depth_per_s * depth_m);
}

Matrix2d StereoNoiseModel::CenterCovariance(const Vector2d& center_camera_m) const {
  return CenterNoiseAt(*this, center_camera_m).covariance;
}

Pose2 StereoMount(const StereoOptions& options) {
  return Pose2(options.x_m, options.y_m, options.yaw_rad);
}

Fan StereoFan(const StereoOptions& options, const StereoNoiseModel& model,
              const Pose2& camera_pose) {
  const int intervals = std::max(
      1, static_cast<int>(std::ceil(options.fov_rad / model.visibility_fan_resolution_rad - 1e-9)));
  const double increment_rad = options.fov_rad / static_cast<double>(intervals);
  return Fan{camera_pose.translation, camera_pose.yaw - 0.5 * options.fov_rad, increment_rad,
             intervals + 1, options.max_depth_m / std::cos(0.5 * options.fov_rad)};
}

StereoFrame MakeStereoFrame(const StereoOptions& options, const StereoNoiseModel& model,
                            TimeNs stamp, int frame_index, const Pose2& camera_pose,
                            std::span<const StereoTarget> targets, std::uint64_t frame_seed) {
  assert(frame_index >= 0);
  StereoFrame frame;
  frame.stamp = stamp;
  frame.mount = StereoMount(options);
  const Pose2 world_to_camera = camera_pose.Inverse();
  const Matrix2d world_to_camera_rotation = world_to_camera.Rotation();
  const double half_fov_rad = 0.5 * options.fov_rad;

  for (const StereoTarget& target : targets) {
    const Vector2d center = world_to_camera * target.pose.translation;
    const bool candidate = center.x() > 0.0 && center.x() <= options.max_depth_m &&
                           std::abs(std::atan2(center.y(), center.x())) <= half_fov_rad &&
                           target.visible_fraction > 0.0;
    if (!candidate) continue;
    Rng rng(DeriveSeed(frame_seed, "stereo_actor",
                       static_cast<std::uint64_t>(target.actor_index)));
    if (rng.Bernoulli(options.miss_rate)) continue;
    StereoObject object;
    object.id = static_cast<std::uint32_t>(target.actor_index) + 1u;
    object.object_class = ConfuseClass(rng, target.object_class, options.class_accuracy);
    object.length_m = target.length_m;
    object.width_m = target.width_m;
    object.history = 1;
    AddMeasurementNoise(model, center, WrapAngle(target.pose.yaw - camera_pose.yaw),
                        world_to_camera_rotation * target.velocity_mps, rng, object);
    frame.objects.push_back(object);
  }

  Rng rng(DeriveSeed(frame_seed, "stereo_false", 0));
  const int false_count = DrawPoisson(rng, options.false_rate);
  for (int j = 0; j < false_count; ++j) {
    const double depth_m = rng.Uniform(model.false_min_depth_m, options.max_depth_m);
    const double bearing = rng.Uniform(-half_fov_rad, half_fov_rad);
    const Vector2d center(depth_m, depth_m * std::tan(bearing));
    StereoObject object;
    // Wraps only after 2^25 frames (about 19 days at 20 Hz).
    object.id = kFalseObjectIdBase +
                ((static_cast<std::uint32_t>(frame_index) *
                      static_cast<std::uint32_t>(kMaxFalseObjectsPerFrame) +
                  static_cast<std::uint32_t>(j)) &
                 (kFalseObjectIdBase - 1u));
    object.object_class = kAllObjectClasses[rng.UniformIndex(kAllObjectClasses.size())];
    object.length_m = rng.Uniform(model.false_length_min_m, model.false_length_max_m);
    object.width_m = rng.Uniform(model.false_width_min_m, model.false_width_max_m);
    object.history = 1;
    AddMeasurementNoise(model, center, rng.Uniform(-kPi, kPi), Vector2d::Zero(), rng, object);
    frame.objects.push_back(object);
  }
  return frame;
}

}  // namespace lookout::sim
