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

bool ClassesCompatible(ObjectClass track, ObjectClass detection) {
  if (track == ObjectClass::kUnknown || detection == ObjectClass::kUnknown) return true;
  const auto vehicle = [](ObjectClass c) {
    return c == ObjectClass::kCar || c == ObjectClass::kTruck;
  };
  if (vehicle(track) && vehicle(detection)) return true;  // car and truck are easily confused
  return track == detection;
}

}  // namespace lookout::tracking
