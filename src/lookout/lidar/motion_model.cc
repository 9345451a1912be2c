#include "lookout/lidar/motion_model.h"

#include <algorithm>
#include <cmath>

namespace lookout::lidar {

Arc ArcOfIncrement(const Pose2& increment) {
  const double chord = increment.translation.norm();
  const double dtheta = increment.yaw;
  // Along an arc of heading change dtheta the chord is s * sin(dtheta/2) / (dtheta/2) and
  // points at dtheta / 2 from the start heading: invert for s, signed by the direction.
  const double half = 0.5 * dtheta;
  const double ratio = std::abs(half) < 1e-6 ? 1.0 - half * half / 6.0 : std::sin(half) / half;
  const double sign = increment.translation.x() < 0.0 ? -1.0 : 1.0;
  return {sign * chord / ratio, dtheta};
}

Pose2 IncrementOfArc(const Arc& arc) {
  const double s = arc.length_m;
  const double a = arc.heading_change_rad;
  // Forward s sin(a)/a, left s (1 - cos a)/a; the small-angle limits by Taylor series.
  const double sinc = std::abs(a) < 1e-6 ? 1.0 - a * a / 6.0 : std::sin(a) / a;
  const double cosc = std::abs(a) < 1e-6 ? a / 2.0 - a * a * a / 24.0 : (1.0 - std::cos(a)) / a;
  return Pose2(s * sinc, s * cosc, WrapAngle(a));
}

RotTransRot DecomposeIncrement(const Pose2& increment) {
  RotTransRot m;
  const double trans = increment.translation.norm();
  if (trans < 1e-9) {
    m.rot2_rad = WrapAngle(increment.yaw);
    return m;
  }
  double rot1 = std::atan2(increment.y(), increment.x());
  double signed_trans = trans;
  if (std::abs(rot1) > kPi / 2.0) {  // backwards
    rot1 = WrapAngle(rot1 + kPi);
    signed_trans = -trans;
  }
  m.rot1_rad = rot1;
  m.trans_m = signed_trans;
  m.rot2_rad = WrapAngle(increment.yaw - rot1);
  return m;
}

Pose2 ComposeIncrement(const RotTransRot& m) {
  return Pose2(m.trans_m * std::cos(m.rot1_rad), m.trans_m * std::sin(m.rot1_rad),
               WrapAngle(m.rot1_rad + m.rot2_rad));
}

Pose2 SampleDifferentialDrive(const Pose2& pose, const Pose2& increment,
                              const MotionModelOptions& o, Rng& rng) {
  const RotTransRot m = DecomposeIncrement(increment);
  const double r1 = m.rot1_rad * m.rot1_rad;
  const double r2 = m.rot2_rad * m.rot2_rad;
  const double t2 = m.trans_m * m.trans_m;
  RotTransRot s;
  s.rot1_rad = m.rot1_rad + rng.Normal() * std::sqrt(o.alpha1 * r1 + o.alpha2 * t2);
  s.trans_m = m.trans_m + rng.Normal() * std::sqrt(o.alpha3 * t2 + o.alpha4 * (r1 + r2));
  s.rot2_rad = m.rot2_rad + rng.Normal() * std::sqrt(o.alpha1 * r2 + o.alpha2 * t2);
  return pose * ComposeIncrement(s);
}

Pose2 SampleBicycle(const Pose2& pose, const Pose2& increment, const MotionModelOptions& o,
                    Rng& rng) {
  const Arc arc = ArcOfIncrement(increment);
  const double s = arc.length_m;
  // Steering angle of the measured arc (the curvature a car of this wheelbase drove), clamped:
  // an increment that turns on the spot is read as the tightest turn the car can make.
  double steering = 0.0;
  if (std::abs(s) > 1e-9) {
    steering = std::atan(o.wheelbase_m * arc.heading_change_rad / s);
  } else if (arc.heading_change_rad != 0.0) {
    steering = std::copysign(o.max_steering_rad, arc.heading_change_rad);
  }
  steering = std::clamp(steering, -o.max_steering_rad, o.max_steering_rad);
  const double s_sample = s + rng.Normal() * o.arc_length_noise * std::abs(s);
  const double steering_sample =
      std::clamp(steering + rng.Normal() * o.steering_noise_rad, -o.max_steering_rad,
                 o.max_steering_rad);
  const double dtheta = s_sample * std::tan(steering_sample) / o.wheelbase_m;
  return pose * IncrementOfArc({s_sample, dtheta});
}

Pose2 SampleMotion(const Pose2& pose, const Pose2& increment, const MotionModelOptions& options,
                   Rng& rng) {
  return options.kind == MotionModelKind::kBicycle
             ? SampleBicycle(pose, increment, options, rng)
             : SampleDifferentialDrive(pose, increment, options, rng);
}

}  // namespace lookout::lidar
