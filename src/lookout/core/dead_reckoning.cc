#include "lookout/core/dead_reckoning.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout {
namespace {

// Below this turn angle a = w dt the arc factors are evaluated by their Taylor series: the
// closed forms divide by a (and S'(a) cancels catastrophically as a -> 0). With four terms the
// truncation error at |a| = 1e-2 is below 1e-19, far under double rounding of the values.
constexpr double kSeriesBelowRad = 1e-2;

// The arc's factors: forward = v dt S(a), left = v dt C(a), and their derivatives in a.
struct ArcFactors {
  double s = 1.0;   // sin(a) / a
  double c = 0.0;   // (1 - cos a) / a
  double ds = 0.0;  // dS/da
  double dc = 0.5;  // dC/da
};

ArcFactors ComputeArcFactors(double a) {
  ArcFactors f;
  if (std::abs(a) < kSeriesBelowRad) {
    const double a2 = a * a;
    f.s = 1.0 - a2 / 6.0 * (1.0 - a2 / 20.0 * (1.0 - a2 / 42.0));
    f.c = a / 2.0 * (1.0 - a2 / 12.0 * (1.0 - a2 / 30.0 * (1.0 - a2 / 56.0)));
    f.ds = -a / 3.0 * (1.0 - a2 / 10.0 * (1.0 - a2 / 28.0 * (1.0 - a2 / 54.0)));
    f.dc = 0.5 - a2 / 8.0 * (1.0 - a2 / 18.0 * (1.0 - a2 / 40.0));
    return f;
  }
  const double sin_a = std::sin(a);
  const double cos_a = std::cos(a);
  const double half_sin = std::sin(0.5 * a);
  const double one_minus_cos = 2.0 * half_sin * half_sin;  // no cancellation, unlike 1 - cos a
  f.s = sin_a / a;
  f.c = one_minus_cos / a;
  f.ds = (a * cos_a - sin_a) / (a * a);
  f.dc = (a * sin_a - one_minus_cos) / (a * a);
  return f;
}

bool AllFinite(const Eigen::Matrix3d& m) { return m.allFinite(); }

void Require(bool ok, const std::string& source, const char* field, const char* problem) {
  if (!ok) throw InputError(source, 0, std::string("dead_reckoning.") + field, problem);
}

bool FiniteNonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

Pose2 IntegrateArc(const Pose2& start, double speed_mps, double yaw_rate_radps, double dt_s) {
  const double a = yaw_rate_radps * dt_s;
  const ArcFactors f = ComputeArcFactors(a);
  const double forward_m = speed_mps * dt_s * f.s;
  const double left_m = speed_mps * dt_s * f.c;
  const double cos_yaw = std::cos(start.yaw);
  const double sin_yaw = std::sin(start.yaw);
  return Pose2(start.x() + cos_yaw * forward_m - sin_yaw * left_m,
               start.y() + sin_yaw * forward_m + cos_yaw * left_m, WrapAngle(start.yaw + a));
}

ArcJacobians IntegrateArcJacobians(const Pose2& start, double speed_mps, double yaw_rate_radps,
                                   double dt_s) {
  const double a = yaw_rate_radps * dt_s;
  const ArcFactors f = ComputeArcFactors(a);
  const double cos_yaw = std::cos(start.yaw);
  const double sin_yaw = std::sin(start.yaw);
  const double forward_m = speed_mps * dt_s * f.s;
  const double left_m = speed_mps * dt_s * f.c;
  const double dx_m = cos_yaw * forward_m - sin_yaw * left_m;
  const double dy_m = sin_yaw * forward_m + cos_yaw * left_m;

  ArcJacobians j;
  j.wrt_start << 1.0, 0.0, -dy_m,  //
      0.0, 1.0, dx_m,              //
      0.0, 0.0, 1.0;
  // d(forward, left)/dv = dt (S, C); d(forward, left)/dw = v dt^2 (S', C') since da/dw = dt.
  const double forward_dv = dt_s * f.s;
  const double left_dv = dt_s * f.c;
  const double forward_dw = speed_mps * dt_s * dt_s * f.ds;
  const double left_dw = speed_mps * dt_s * dt_s * f.dc;
  j.wrt_twist << cos_yaw * forward_dv - sin_yaw * left_dv, cos_yaw * forward_dw - sin_yaw * left_dw,
      sin_yaw * forward_dv + cos_yaw * left_dv, sin_yaw * forward_dw + cos_yaw * left_dw,  //
      0.0, dt_s;
  return j;
}

EgoState PropagateEgoState(const EgoState& start, TimeNs t, const OdometryNoise& noise) {
  const double dt_s = ToSeconds(t - start.stamp);
  EgoState out = start;
  out.stamp = t;
  out.pose = IntegrateArc(start.pose, start.speed_mps, start.yaw_rate_radps, dt_s);

  const ArcJacobians j =
      IntegrateArcJacobians(start.pose, start.speed_mps, start.yaw_rate_radps, dt_s);
  const double drift_v = 0.5 * noise.accel_noise_mps2 * dt_s;
  const double drift_w = 0.5 * noise.yaw_accel_noise_radps2 * dt_s;
  Eigen::Matrix2d input_covariance = Eigen::Matrix2d::Zero();
  input_covariance(0, 0) = noise.speed_noise_mps * noise.speed_noise_mps + drift_v * drift_v;
  input_covariance(1, 1) =
      noise.yaw_rate_noise_radps * noise.yaw_rate_noise_radps + drift_w * drift_w;
  const Eigen::Matrix3d p = j.wrt_start * start.covariance * j.wrt_start.transpose() +
                            j.wrt_twist * input_covariance * j.wrt_twist.transpose();
  out.covariance = 0.5 * (p + p.transpose());  // keep it exactly symmetric
  return out;
}

void DeadReckoningOptions::Validate(const std::string& source) const {
  Require(std::isfinite(initial_pose.x()) && std::isfinite(initial_pose.y()) &&
              std::isfinite(initial_pose.yaw),
          source, "initial_pose", "must be finite");
  Require(AllFinite(initial_covariance) &&
              initial_covariance.isApprox(initial_covariance.transpose()) &&
              (initial_covariance.diagonal().array() >= 0.0).all(),
          source, "initial_covariance", "must be finite, symmetric, with a non-negative diagonal");
  Require(FiniteNonNegative(noise.speed_noise_mps), source, "noise.speed_noise_mps",
          "must be finite and >= 0");
  Require(FiniteNonNegative(noise.yaw_rate_noise_radps), source, "noise.yaw_rate_noise_radps",
          "must be finite and >= 0");
  Require(FiniteNonNegative(noise.accel_noise_mps2), source, "noise.accel_noise_mps2",
          "must be finite and >= 0");
  Require(FiniteNonNegative(noise.yaw_accel_noise_radps2), source, "noise.yaw_accel_noise_radps2",
          "must be finite and >= 0");
  Require(FiniteNonNegative(history_s), source, "history_s", "must be finite and >= 0");
  Require(FiniteNonNegative(max_extrapolation_s), source, "max_extrapolation_s",
          "must be finite and >= 0");
}

DeadReckoning::DeadReckoning(const DeadReckoningOptions& options) : options_(options) {
  options_.Validate();
}

bool DeadReckoning::Add(const EgoOdometry& reading) {
  if (!std::isfinite(reading.speed_mps) || !std::isfinite(reading.yaw_rate_radps)) {
    ++rejected_non_finite_;
    return false;
  }
  if (states_.empty()) {
    EgoState first;
    first.stamp = reading.stamp;
    first.pose = options_.initial_pose;
    first.covariance = options_.initial_covariance;
    first.speed_mps = reading.speed_mps;
    first.yaw_rate_radps = reading.yaw_rate_radps;
    states_.push_back(first);
    return true;
  }
  EgoState& newest = states_.back();
  if (reading.stamp < newest.stamp) {
    ++rejected_backwards_;
    return false;
  }
  if (reading.stamp == newest.stamp) {
    newest.speed_mps = reading.speed_mps;
    newest.yaw_rate_radps = reading.yaw_rate_radps;
    return true;
  }
  EgoState next = PropagateEgoState(newest, reading.stamp, options_.noise);
  next.speed_mps = reading.speed_mps;
  next.yaw_rate_radps = reading.yaw_rate_radps;
  states_.push_back(next);
  DropOldStates();
  return true;
}

void DeadReckoning::DropOldStates() {
  // Keep the newest state at or before the horizon: At() answers for times back to it.
  const TimeNs horizon = states_.back().stamp - FromSeconds(options_.history_s);
  while (states_.size() >= 2 && states_[1].stamp <= horizon) states_.pop_front();
}

EgoState DeadReckoning::At(TimeNs t) const {
  assert(HasReading());
  // The newest state with stamp <= t; the oldest when t precedes them all.
  auto after = std::upper_bound(states_.begin(), states_.end(), t,
                                [](TimeNs time, const EgoState& s) { return time < s.stamp; });
  const EgoState& from = after == states_.begin() ? states_.front() : *std::prev(after);
  return PropagateEgoState(from, t, options_.noise);
}

std::optional<EgoState> DeadReckoning::PoseAt(TimeNs t) const {
  if (!HasReading()) return std::nullopt;
  const TimeNs margin = FromSeconds(options_.max_extrapolation_s);
  if (t > NewestStamp() + margin || t < OldestStamp() - margin) return std::nullopt;
  return At(t);
}

}  // namespace lookout
