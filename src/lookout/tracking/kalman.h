#pragma once

// Kalman and extended Kalman filter steps for one motion model (motion_models.h) with a 2-D
// position measurement, as pure functions, plus the consistency statistics NIS and NEES.
//
// The update uses the Joseph form P = (I - K H) P (I - K H)' + K R K', which stays symmetric and
// positive semi-definite under rounding for any gain (Bar-Shalom et al. 2001, section 5.2.3).

#include <Eigen/Core>

#include "lookout/tracking/motion_models.h"

namespace lookout::tracking {

struct Gaussian {
  Eigen::VectorXd mean;
  Eigen::MatrixXd cov;
};

// x = f(x), P = F P F' + Q: the exact Kalman prediction for CV, CA and CT, the EKF one for CTR.
Gaussian PredictState(const MotionModel& model, const Gaussian& prior, double dt_s);

// Every model measures the position: z = H x + w, H = [I2 0], w ~ N(0, R).
struct MeasurementPrediction {
  Eigen::Vector2d z;
  Eigen::Matrix2d S;  // innovation covariance H P H' + R
};
MeasurementPrediction PredictMeasurement(const Gaussian& predicted, const Eigen::Matrix2d& R);

struct UpdateResult {
  Gaussian posterior;
  Eigen::Vector2d innovation;
  Eigen::Matrix2d S;
  double nis = 0.0;             // innovation' S^-1 innovation
  double log_likelihood = 0.0;  // log N(innovation; 0, S)
};
UpdateResult UpdateState(const Gaussian& predicted, const Eigen::Vector2d& z,
                         const Eigen::Matrix2d& R);

// log N(v; 0, S) for a 2-D v.
double GaussianLogLikelihood(const Eigen::Vector2d& v, const Eigen::Matrix2d& S);
// e' P^-1 e: normalised innovation (NIS, with S) or estimation error (NEES, with P) squared.
double NormalisedSquare(const Eigen::VectorXd& e, const Eigen::MatrixXd& P);

}  // namespace lookout::tracking
