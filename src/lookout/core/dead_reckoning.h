#pragma once

// Dead reckoning: the ego pose in the odometry frame from wheel speed and yaw rate alone
// (EgoOdometry), until the lidar-chain localisation supplies a better one through the same
// EgoPoseSource interface.
//
// Motion model. Between two readings the vehicle moves with the speed and yaw rate of the
// earlier reading (zero-order hold: causal, and the same rule serves extrapolation past the
// last reading). At constant speed v and yaw rate w the path is an exact circular arc:
//   yaw' = yaw + w dt
//   x'   = x + v/w (sin(yaw + w dt) - sin yaw)
//   y'   = y - v/w (cos(yaw + w dt) - cos yaw)
// evaluated in the equivalent form "forward v dt sin(a)/a, left v dt (1 - cos a)/a in the start
// heading, a = w dt", whose w -> 0 limit is taken with a Taylor series (no division by w).
//
// Noise model (documented for EgoState::covariance). Each reading's speed and yaw rate carry
// independent zero-mean Gaussian errors (speed_noise_mps, yaw_rate_noise_radps, one draw per
// reading, as the simulated sensor makes them). That error is held over the whole interval the
// reading covers, so it is fully correlated within an interval and independent between them.
// On top, the true motion drifts away from the held reading while it is held: an unknown
// constant acceleration a (1-sigma accel_noise_mps2; yaw_accel_noise_radps2 for yaw) moves the
// vehicle by a dt^2 / 2, the same as a speed error of a dt / 2. So one interval of length dt
// adds the effective input variances
//   var_v(dt) = speed_noise_mps^2 + (accel_noise_mps2 dt / 2)^2
//   var_w(dt) = yaw_rate_noise_radps^2 + (yaw_accel_noise_radps2 dt / 2)^2
// propagated to first order through the arc (an extended Kalman filter's prediction):
//   P' = F P F^T + G diag(var_v, var_w) G^T,  F = d(x', y', yaw')/d(x, y, yaw),
//                                             G = d(x', y', yaw')/d(v, w).
// Consequences: the covariance grows without bound (dead reckoning has no absolute reference),
// and extrapolation far past the last reading grows it as dt^2 (from the held reading's error)
// and dt^4 (from the drift): which is why PoseAt() refuses beyond max_extrapolation_s.

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include "lookout/core/ego_state.h"
#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/core/time.h"

namespace lookout {

struct OdometryNoise {
  double speed_noise_mps = 0.05;        // 1-sigma of one reading's speed
  double yaw_rate_noise_radps = 0.005;  // 1-sigma of one reading's yaw rate
  double accel_noise_mps2 = 1.0;        // 1-sigma of the unmodelled acceleration while held
  double yaw_accel_noise_radps2 = 0.5;  // 1-sigma of the unmodelled yaw acceleration
};

// The pose reached from `start` after dt_s (may be negative: backwards in time) at constant
// speed and yaw rate: an exact arc, a straight line when the yaw rate is 0. Pure.
Pose2 IntegrateArc(const Pose2& start, double speed_mps, double yaw_rate_radps, double dt_s);

// Jacobians of IntegrateArc: F with respect to the start (x, y, yaw), G with respect to
// (speed, yaw rate). Named struct rather than a tuple so the call site reads.
struct ArcJacobians {
  Eigen::Matrix3d wrt_start;              // F
  Eigen::Matrix<double, 3, 2> wrt_twist;  // G
};
ArcJacobians IntegrateArcJacobians(const Pose2& start, double speed_mps, double yaw_rate_radps,
                                   double dt_s);

// The state at `t`: `start` moved along the arc of its own speed and yaw rate (held), its
// covariance propagated with the noise model above. Speed and yaw rate are carried over. Pure.
EgoState PropagateEgoState(const EgoState& start, TimeNs t, const OdometryNoise& noise);

struct DeadReckoningOptions {
  Pose2 initial_pose;  // the vehicle's pose at the first reading, in the odometry frame
  Eigen::Matrix3d initial_covariance = Eigen::Matrix3d::Zero();
  OdometryNoise noise;
  // How far back from the newest reading At() answers from the reading that was held at the
  // time asked (older states are dropped; earlier times are extrapolated backwards from the
  // oldest kept reading). One second covers a lidar scan arriving late by several periods.
  double history_s = 1.0;
  // PoseAt() answers nullopt for times further than this outside the kept readings: a pose
  // extrapolated for longer (odometry stopped arriving) is not one to build a map with.
  double max_extrapolation_s = 0.5;

  // Throws lookout::InputError naming the first field out of range (field path
  // "dead_reckoning.<name>", `source` as the file).
  void Validate(const std::string& source = "dead reckoning options") const;
};

// Integrates EgoOdometry readings, in time order, into EgoStates. Deterministic.
//
// Readings whose stamp is earlier than the newest accepted one are refused and counted (a
// library does not print: the runner reports the counters); so are readings with a non-finite
// speed or yaw rate. A reading with the same stamp as the newest replaces its speed and yaw
// rate (no time has passed, the pose is unchanged).
class DeadReckoning final : public EgoPoseSource {
 public:
  // Validates the options (lookout::InputError).
  explicit DeadReckoning(const DeadReckoningOptions& options = {});

  // Returns whether the reading was accepted.
  bool Add(const EgoOdometry& reading);

  bool HasReading() const { return !states_.empty(); }
  // Stamps of the oldest kept and the newest reading; only with HasReading().
  TimeNs OldestStamp() const { return states_.front().stamp; }
  TimeNs NewestStamp() const { return states_.back().stamp; }

  // The state at t, integrated from the newest kept reading at or before t (extrapolation past
  // the newest; backwards from the oldest for earlier t). Precondition: HasReading().
  EgoState At(TimeNs t) const;

  // At(t), or nullopt without a reading or when t is more than max_extrapolation_s outside
  // [OldestStamp(), NewestStamp()].
  std::optional<EgoState> PoseAt(TimeNs t) const override;

  std::int64_t rejected_backwards_count() const { return rejected_backwards_; }
  std::int64_t rejected_non_finite_count() const { return rejected_non_finite_; }

 private:
  void DropOldStates();

  DeadReckoningOptions options_;
  // One per accepted reading: the pose and covariance at its stamp, its speed and yaw rate.
  // Stamps strictly increasing.
  std::deque<EgoState> states_;
  std::int64_t rejected_backwards_ = 0;
  std::int64_t rejected_non_finite_ = 0;
};

}  // namespace lookout
