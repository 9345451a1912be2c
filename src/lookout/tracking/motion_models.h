#pragma once

// Motion models of seed 004 section VII.C (constant velocity, constant acceleration, left turn,
// right turn) as pure functions: the state transition over dt, its Jacobian, and the discrete
// process noise. Units SI; x east, y north; turn rates counter-clockwise positive (a left turn).
//
// Every model's state is a subset of one canonical state
//     [x, y, vx, vy, ax, ay, omega]          (FullState indices below)
// so models of different sizes can be mixed by the IMM (imm.h):
//   CV   [x y vx vy]          white-noise acceleration (continuous PSD q)
//   CA   [x y vx vy ax ay]    white-noise jerk (continuous PSD q)
//   CT   [x y vx vy]          coordinated turn at a FIXED rate omega (left: omega > 0)
//   CTR  [x y vx vy omega]    coordinated turn with the rate as a state (EKF)
//
// Fixed-rate turns or a turn-rate state? Both are here; the paper's set (CV, CA, left, right) uses
// fixed rates, and that is what the IMM of docs/imm.md runs: each fixed-rate model is linear, so
// its Kalman filter is exact and its likelihood is a true Gaussian, and the IMM itself estimates
// which way (and, through the mode probabilities, roughly how hard) the target turns. A
// turn-rate state adapts to any rate but needs an EKF and a rate that is observable only through
// several position measurements; docs/imm.md compares the two on the real radar data.

#include <string>
#include <vector>

#include <Eigen/Core>

namespace lookout::tracking {

enum FullState : int { kX = 0, kY = 1, kVx = 2, kVy = 3, kAx = 4, kAy = 5, kOmega = 6 };
inline constexpr int kFullStateSize = 7;

enum class MotionKind {
  kConstantVelocity,
  kConstantAcceleration,
  kCoordinatedTurn,      // fixed rate turn_rate_rad_s
  kCoordinatedTurnRate,  // rate in the state
};

struct MotionModel {
  MotionKind kind = MotionKind::kConstantVelocity;
  // Continuous-time PSD of the white noise driving the highest derivative: acceleration for CV,
  // CT and CTR (m^2/s^3), jerk for CA (m^2/s^5).
  double noise_psd = 1.0;
  double turn_rate_rad_s = 0.0;        // CT only: > 0 left, < 0 right
  double turn_rate_noise_psd = 1e-4;   // CTR only: PSD of the turn-rate random walk (rad^2/s^3)

  // Validates the fields; `prefix` names the model in errors (InputError).
  void Validate(const std::string& source, const std::string& prefix) const;
};

MotionModel ConstantVelocity(double accel_psd);
MotionModel ConstantAcceleration(double jerk_psd);
MotionModel CoordinatedTurn(double turn_rate_rad_s, double accel_psd);
MotionModel CoordinatedTurnRate(double accel_psd, double turn_rate_psd);

// The canonical components (FullState) a model's state holds, in its order.
const std::vector<int>& StateComponents(MotionKind kind);
inline int StateSize(MotionKind kind) { return static_cast<int>(StateComponents(kind).size()); }

// x_k+1 = f(x_k) and its Jacobian F = df/dx at x_k, with the discrete process noise Q, over dt.
struct Transition {
  Eigen::VectorXd x;
  Eigen::MatrixXd F;
  Eigen::MatrixXd Q;
};

// Linear models (CV, CA, CT) ignore nothing: F is exact and x = F x_k. CTR is nonlinear.
Transition Propagate(const MotionModel& model, const Eigen::VectorXd& x, double dt_s);

// The pieces, for tests and for whoever needs one model alone.
Eigen::Matrix4d ConstantVelocityMatrix(double dt_s);
Eigen::Matrix4d WhiteAccelerationNoise(double dt_s, double psd);
Eigen::Matrix<double, 6, 6> ConstantAccelerationMatrix(double dt_s);
Eigen::Matrix<double, 6, 6> WhiteJerkNoise(double dt_s, double psd);
Eigen::Matrix4d CoordinatedTurnMatrix(double turn_rate_rad_s, double dt_s);

}  // namespace lookout::tracking
