#include "lookout/stereo/stereo_validation.h"

#include <cmath>
#include <numeric>

namespace lookout::stereo {

std::string_view ToString(DropReason reason) {
  switch (reason) {
    case DropReason::kNonFinite: return "a field is NaN or infinite";
    case DropReason::kNegativeSize: return "negative length or width";
    case DropReason::kCenterCovarianceNotPositiveDefinite:
      return "centre covariance not positive definite";
    case DropReason::kNegativeYawVariance: return "negative yaw variance";
    case DropReason::kSpeedVarianceNotPositive: return "speed variance not positive";
    case DropReason::kBehindCamera: return "centre at or behind the camera (depth <= 0)";
    case DropReason::kLidarOriginInside: return "lidar origin inside the footprint";
  }
  return "unknown reason";
}

std::string Describe(const Drop& drop) {
  return "stereo object " + std::to_string(drop.id) + " dropped: " +
         std::string(ToString(drop.reason));
}

std::int64_t DropCounts::Total() const {
  return std::accumulate(by_reason.begin(), by_reason.end(), std::int64_t{0});
}

DropCounts& DropCounts::operator+=(const DropCounts& other) {
  for (std::size_t i = 0; i < kDropReasonCount; ++i) by_reason[i] += other.by_reason[i];
  return *this;
}

bool IsPositiveDefinite(const Eigen::Matrix2d& m) {
  if (!m.allFinite()) return false;
  const double scale = std::abs(m(0, 0)) + std::abs(m(1, 1)) + std::abs(m(0, 1));
  if (std::abs(m(0, 1) - m(1, 0)) > 1e-9 * scale) return false;
  // A symmetric 2 x 2 matrix is positive definite iff its leading minors are positive.
  return m(0, 0) > 0.0 && m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0) > 0.0;
}

std::optional<DropReason> CheckStereoObject(const StereoObject& o) {
  const bool finite = o.center_m.allFinite() && std::isfinite(o.yaw_rad) &&
                      std::isfinite(o.length_m) && std::isfinite(o.width_m) &&
                      std::isfinite(o.speed_longitudinal_mps) &&
                      std::isfinite(o.speed_lateral_mps) && o.center_covariance.allFinite() &&
                      std::isfinite(o.yaw_variance) && std::isfinite(o.speed_variance);
  if (!finite) return DropReason::kNonFinite;
  if (o.length_m < 0.0 || o.width_m < 0.0) return DropReason::kNegativeSize;
  if (!IsPositiveDefinite(o.center_covariance)) {
    return DropReason::kCenterCovarianceNotPositiveDefinite;
  }
  if (o.yaw_variance < 0.0) return DropReason::kNegativeYawVariance;
  if (!(o.speed_variance > 0.0)) return DropReason::kSpeedVarianceNotPositive;
  if (!(o.center_m.x() > 0.0)) return DropReason::kBehindCamera;
  return std::nullopt;
}

}  // namespace lookout::stereo
