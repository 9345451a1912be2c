#include "lookout/tracking/kalman.h"

#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace lookout::tracking {

Gaussian PredictState(const MotionModel& model, const Gaussian& prior, double dt_s) {
  const Transition t = Propagate(model, prior.mean, dt_s);
  Gaussian out{t.x, t.F * prior.cov * t.F.transpose() + t.Q};
  // Exact symmetry against rounding; eval() because the operands alias the result.
  out.cov = (0.5 * (out.cov + out.cov.transpose())).eval();
  return out;
}

MeasurementPrediction PredictMeasurement(const Gaussian& predicted, const Eigen::Matrix2d& R) {
  return {predicted.mean.head<2>(), predicted.cov.topLeftCorner<2, 2>() + R};
}

double NormalisedSquare(const Eigen::VectorXd& e, const Eigen::MatrixXd& P) {
  return e.dot(P.ldlt().solve(e));
}

double GaussianLogLikelihood(const Eigen::Vector2d& v, const Eigen::Matrix2d& S) {
  return -0.5 * (NormalisedSquare(v, S) + std::log(S.determinant()) +
                 2.0 * std::log(2.0 * std::numbers::pi));
}

UpdateResult UpdateState(const Gaussian& predicted, const Eigen::Vector2d& z,
                         const Eigen::Matrix2d& R) {
  const Eigen::Index n = predicted.mean.size();
  const MeasurementPrediction m = PredictMeasurement(predicted, R);
  UpdateResult out;
  out.innovation = z - m.z;
  out.S = m.S;
  // K = P H' S^-1, with H = [I2 0]: P H' is the first two columns of P.
  const Eigen::MatrixXd pht = predicted.cov.leftCols<2>();
  const Eigen::MatrixXd K = m.S.ldlt().solve(pht.transpose()).transpose();
  Eigen::MatrixXd i_kh = Eigen::MatrixXd::Identity(n, n);
  i_kh.leftCols<2>() -= K;
  out.posterior.mean = predicted.mean + K * out.innovation;
  out.posterior.cov = i_kh * predicted.cov * i_kh.transpose() + K * R * K.transpose();
  out.posterior.cov = (0.5 * (out.posterior.cov + out.posterior.cov.transpose())).eval();
  out.nis = NormalisedSquare(out.innovation, out.S);
  out.log_likelihood = GaussianLogLikelihood(out.innovation, out.S);
  return out;
}

}  // namespace lookout::tracking
