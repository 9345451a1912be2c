#pragma once

// What makes a stereo object unusable, checked before anything is computed from it. A bad
// object is dropped with its reason, counted and listed for the log; it never throws, since
// one broken object in a camera's list must not stop the pipeline.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "lookout/core/messages.h"

namespace lookout::stereo {

enum class DropReason {
  kNonFinite = 0,                        // a NaN or infinite field
  kNegativeSize,                         // length or width < 0
  kCenterCovarianceNotPositiveDefinite,  // asymmetric, or an eigenvalue <= 0
  kNegativeYawVariance,
  kSpeedVarianceNotPositive,  // the velocity covariance speed_variance I must be invertible
  kBehindCamera,              // centre depth <= 0: the depth model has no meaning there
  kLidarOriginInside,         // the lidar origin inside the footprint: no side faces it
};
inline constexpr std::size_t kDropReasonCount = 7;

std::string_view ToString(DropReason reason);

// One dropped object: the camera's id and why.
struct Drop {
  std::uint32_t id = 0;
  DropReason reason = DropReason::kNonFinite;
};
// One line for a log: "stereo object 12 dropped: centre covariance not positive definite".
std::string Describe(const Drop& drop);

struct DropCounts {
  std::array<std::int64_t, kDropReasonCount> by_reason{};

  void Add(DropReason reason) { ++by_reason[static_cast<std::size_t>(reason)]; }
  std::int64_t Count(DropReason reason) const {
    return by_reason[static_cast<std::size_t>(reason)];
  }
  std::int64_t Total() const;
  DropCounts& operator+=(const DropCounts& other);
};

// The first reason (in DropReason order) `object` cannot be used, or nullopt. The footprint
// check against the lidar origin needs the mount, so ProjectStereoObject makes it.
std::optional<DropReason> CheckStereoObject(const StereoObject& object);

// True when `m` is symmetric (to a relative 1e-9) and both its eigenvalues are > 0.
bool IsPositiveDefinite(const Eigen::Matrix2d& m);

}  // namespace lookout::stereo
