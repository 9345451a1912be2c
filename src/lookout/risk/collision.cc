#include "lookout/risk/collision.h"

#include <algorithm>

namespace lookout::risk {

std::optional<Collision> FirstCollision(const CircleTrack& ego, const CircleTrack& other,
                                        double dt_s) {
  const std::size_t n = std::min({ego.centre_m.size(), ego.radius_m.size(),
                                  other.centre_m.size(), other.radius_m.size()});
  auto separation = [&](std::size_t k) {
    return (ego.centre_m[k] - other.centre_m[k]).norm() - (ego.radius_m[k] + other.radius_m[k]);
  };
  double previous = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double s = separation(k);
    if (s <= 0.0) {
      if (k == 0) return Collision{0.0, 0};
      // previous > 0 >= s: the zero of the line through both lies inside the step.
      const double fraction = previous / (previous - s);
      return Collision{(static_cast<double>(k - 1) + fraction) * dt_s, k};
    }
    previous = s;
  }
  return std::nullopt;
}

}  // namespace lookout::risk
