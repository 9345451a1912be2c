#include "lookout/tracking/motion_models.h"

#include <cmath>

#include "lookout/core/input_error.h"

namespace lookout::tracking {
namespace {

// Below this |omega * dt| the turn terms divide small differences by a small rate; their Taylor
// series (to u^5, error below u^6 / 5040 ~ 1e-21 relative) are used instead.
constexpr double kSeriesLimit = 1e-3;

void Require(bool ok, const std::string& source, const std::string& field, const char* problem) {
  if (!ok) throw InputError(source, 0, field, problem);
}

// sin(w t)/w, (1 - cos(w t))/w and their derivatives in w, with u = w t.
struct TurnTerms {
  double s_over_w;
  double one_minus_c_over_w;
  double d_s_over_w;
  double d_one_minus_c_over_w;
  double s;
  double c;
};

TurnTerms Terms(double w, double dt) {
  const double u = w * dt;
  const double s = std::sin(u);
  const double c = std::cos(u);
  if (std::abs(u) < kSeriesLimit) {
    const double u2 = u * u;
    return {dt * (1.0 - u2 / 6.0 + u2 * u2 / 120.0),
            dt * u * (0.5 - u2 / 24.0 + u2 * u2 / 720.0),
            dt * dt * u * (-1.0 / 3.0 + u2 / 30.0),
            dt * dt * (0.5 - u2 / 8.0 + u2 * u2 / 144.0),
            s,
            c};
  }
  return {s / w, (1.0 - c) / w, (dt * c * w - s) / (w * w), (dt * s * w - (1.0 - c)) / (w * w), s,
          c};
}

}  // namespace

void MotionModel::Validate(const std::string& source, const std::string& prefix) const {
  Require(std::isfinite(noise_psd) && noise_psd > 0.0, source, prefix + ".noise_psd",
          "must be finite and > 0");
  Require(std::isfinite(turn_rate_rad_s), source, prefix + ".turn_rate_rad_s", "must be finite");
  Require(kind != MotionKind::kCoordinatedTurn || turn_rate_rad_s != 0.0, source,
          prefix + ".turn_rate_rad_s", "must be non-zero for a coordinated turn (zero is CV)");
  Require(std::isfinite(turn_rate_noise_psd) && turn_rate_noise_psd > 0.0, source,
          prefix + ".turn_rate_noise_psd", "must be finite and > 0");
}

MotionModel ConstantVelocity(double accel_psd) {
  return {MotionKind::kConstantVelocity, accel_psd, 0.0, 1e-4};
}
MotionModel ConstantAcceleration(double jerk_psd) {
  return {MotionKind::kConstantAcceleration, jerk_psd, 0.0, 1e-4};
}
MotionModel CoordinatedTurn(double turn_rate_rad_s, double accel_psd) {
  return {MotionKind::kCoordinatedTurn, accel_psd, turn_rate_rad_s, 1e-4};
}
MotionModel CoordinatedTurnRate(double accel_psd, double turn_rate_psd) {
  return {MotionKind::kCoordinatedTurnRate, accel_psd, 0.0, turn_rate_psd};
}

const std::vector<int>& StateComponents(MotionKind kind) {
  static const std::vector<int> kCv = {kX, kY, kVx, kVy};
  static const std::vector<int> kCa = {kX, kY, kVx, kVy, kAx, kAy};
  static const std::vector<int> kCtr = {kX, kY, kVx, kVy, kOmega};
  switch (kind) {
    case MotionKind::kConstantAcceleration: return kCa;
    case MotionKind::kCoordinatedTurnRate: return kCtr;
    case MotionKind::kConstantVelocity:
    case MotionKind::kCoordinatedTurn: break;
  }
  return kCv;
}

Eigen::Matrix4d ConstantVelocityMatrix(double dt) {
  Eigen::Matrix4d f = Eigen::Matrix4d::Identity();
  f(0, 2) = dt;
  f(1, 3) = dt;
  return f;
}

// Discretised continuous white-noise acceleration (Bar-Shalom, Li, Kirubarajan, "Estimation with
// Applications to Tracking and Navigation", 2001, section 6.2.2), per axis
// q [dt^3/3 dt^2/2; dt^2/2 dt], in the [x y vx vy] order.
Eigen::Matrix4d WhiteAccelerationNoise(double dt, double psd) {
  const double a = dt * dt * dt / 3.0 * psd;
  const double b = dt * dt / 2.0 * psd;
  const double c = dt * psd;
  Eigen::Matrix4d q = Eigen::Matrix4d::Zero();
  q(0, 0) = q(1, 1) = a;
  q(0, 2) = q(2, 0) = q(1, 3) = q(3, 1) = b;
  q(2, 2) = q(3, 3) = c;
  return q;
}

Eigen::Matrix<double, 6, 6> ConstantAccelerationMatrix(double dt) {
  Eigen::Matrix<double, 6, 6> f = Eigen::Matrix<double, 6, 6>::Identity();
  for (int axis = 0; axis < 2; ++axis) {
    f(axis, 2 + axis) = dt;
    f(axis, 4 + axis) = dt * dt / 2.0;
    f(2 + axis, 4 + axis) = dt;
  }
  return f;
}

// Discretised continuous white-noise jerk (same book, section 6.2.3), per axis
// q [dt^5/20 dt^4/8 dt^3/6; dt^4/8 dt^3/3 dt^2/2; dt^3/6 dt^2/2 dt], in [x y vx vy ax ay] order.
Eigen::Matrix<double, 6, 6> WhiteJerkNoise(double dt, double psd) {
  const double d2 = dt * dt, d3 = d2 * dt, d4 = d3 * dt, d5 = d4 * dt;
  const double per_axis[3][3] = {{d5 / 20.0, d4 / 8.0, d3 / 6.0},
                                 {d4 / 8.0, d3 / 3.0, d2 / 2.0},
                                 {d3 / 6.0, d2 / 2.0, dt}};
  Eigen::Matrix<double, 6, 6> q = Eigen::Matrix<double, 6, 6>::Zero();
  for (int axis = 0; axis < 2; ++axis) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) q(2 * i + axis, 2 * j + axis) = psd * per_axis[i][j];
    }
  }
  return q;
}

// The exact transition of a coordinated turn at rate w (same book, section 11.7), in
// [x y vx vy] order.
Eigen::Matrix4d CoordinatedTurnMatrix(double w, double dt) {
  const TurnTerms t = Terms(w, dt);
  Eigen::Matrix4d f;
  f << 1, 0, t.s_over_w, -t.one_minus_c_over_w,  //
      0, 1, t.one_minus_c_over_w, t.s_over_w,    //
      0, 0, t.c, -t.s,                            //
      0, 0, t.s, t.c;
  return f;
}

Transition Propagate(const MotionModel& model, const Eigen::VectorXd& x, double dt) {
  Transition out;
  switch (model.kind) {
    case MotionKind::kConstantVelocity:
      out.F = ConstantVelocityMatrix(dt);
      out.Q = WhiteAccelerationNoise(dt, model.noise_psd);
      break;
    case MotionKind::kConstantAcceleration:
      out.F = ConstantAccelerationMatrix(dt);
      out.Q = WhiteJerkNoise(dt, model.noise_psd);
      break;
    case MotionKind::kCoordinatedTurn:
      out.F = CoordinatedTurnMatrix(model.turn_rate_rad_s, dt);
      // The turn is exact; what it leaves out (rate errors, speed changes) is taken as white
      // acceleration, as for CV.
      out.Q = WhiteAccelerationNoise(dt, model.noise_psd);
      break;
    case MotionKind::kCoordinatedTurnRate: {
      const double w = x(4);
      const double vx = x(2), vy = x(3);
      out.F = Eigen::MatrixXd::Identity(5, 5);
      out.F.topLeftCorner<4, 4>() = CoordinatedTurnMatrix(w, dt);
      out.x = x;
      out.x.head<4>() = CoordinatedTurnMatrix(w, dt) * x.head<4>();
      // d/dw of the four rows.
      const TurnTerms t = Terms(w, dt);
      const double ds_over_w = t.d_s_over_w;
      const double d_one_minus_c_over_w = t.d_one_minus_c_over_w;
      out.F(0, 4) = vx * ds_over_w - vy * d_one_minus_c_over_w;
      out.F(1, 4) = vx * d_one_minus_c_over_w + vy * ds_over_w;
      out.F(2, 4) = -dt * t.s * vx - dt * t.c * vy;
      out.F(3, 4) = dt * t.c * vx - dt * t.s * vy;
      out.Q = Eigen::MatrixXd::Zero(5, 5);
      out.Q.topLeftCorner<4, 4>() = WhiteAccelerationNoise(dt, model.noise_psd);
      out.Q(4, 4) = model.turn_rate_noise_psd * dt;
      return out;
    }
  }
  out.x = out.F * x;
  return out;
}

}  // namespace lookout::tracking
