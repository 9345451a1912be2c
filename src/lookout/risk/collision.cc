#include "lookout/risk/collision.h"

#include <algorithm>

namespace lookout::risk {

std::optional<Collision> FirstCollision(const FootprintTrack& ego, const FootprintTrack& other,
                                        double dt_s) {
  const std::size_t n = std::min(ego.size(), other.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (!Overlap(ego[k], other[k], Eigen::Vector2d::Zero())) continue;
    if (k == 0) return Collision{0.0, 0};
    // Apart at k - 1, touching at k: the zero of the line through both separations lies
    // inside the step.
    const double before = Separation(ego[k - 1], other[k - 1]);
    const double now = Separation(ego[k], other[k]);
    const double fraction = before > now ? before / (before - now) : 1.0;
    return Collision{(static_cast<double>(k - 1) + std::clamp(fraction, 0.0, 1.0)) * dt_s, k};
  }
  return std::nullopt;
}

}  // namespace lookout::risk
