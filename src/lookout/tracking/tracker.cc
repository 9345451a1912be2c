#include "lookout/tracking/tracker.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace lookout::tracking {

bool DetectionUsable(const Detection& d) {
  if (!d.position_m.allFinite() || !d.covariance.allFinite()) return false;
  const Eigen::Matrix2d& c = d.covariance;
  if (std::abs(c(0, 1) - c(1, 0)) > 1e-9 * (1.0 + c.cwiseAbs().maxCoeff())) return false;
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(c).eigenvalues().minCoeff() > 0.0;
}

Gaussian BirthState(const Detection& d, double speed_sigma_mps) {
  Gaussian g{Eigen::Vector4d(d.position_m.x(), d.position_m.y(), 0.0, 0.0),
             Eigen::Matrix4d::Zero()};
  g.cov.topLeftCorner<2, 2>() = d.covariance;
  Eigen::Matrix2d velocity_cov = Eigen::Matrix2d::Identity() * speed_sigma_mps * speed_sigma_mps;
  if (d.velocity_mps && d.velocity_mps->allFinite()) {
    const Eigen::Matrix2d& c = d.velocity_covariance;
    const bool usable =
        c.allFinite() && std::abs(c(0, 1) - c(1, 0)) <= 1e-9 * (1.0 + c.cwiseAbs().maxCoeff()) &&
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(c).eigenvalues().minCoeff() > 0.0;
    if (usable && c.trace() < velocity_cov.trace()) {
      g.mean.segment<2>(2) = *d.velocity_mps;
      velocity_cov = c;
    }
  }
  g.cov.bottomRightCorner<2, 2>() = velocity_cov;
  return g;
}

bool ClassesCompatible(ObjectClass track, ObjectClass detection) {
  if (track == ObjectClass::kUnknown || detection == ObjectClass::kUnknown) return true;
  const auto vehicle = [](ObjectClass c) {
    return c == ObjectClass::kCar || c == ObjectClass::kTruck;
  };
  if (vehicle(track) && vehicle(detection)) return true;  // car and truck are easily confused
  return track == detection;
}

}  // namespace lookout::tracking
