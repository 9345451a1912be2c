#include "lookout/risk/carriageway.h"

namespace lookout::risk {

bool OnCarriageway(const Carriageways& roads, const Eigen::Vector2d& p) {
  const Footprint point = Footprint::Circle(p, 0.0);
  for (const Footprint& road : roads) {
    if (Separation(road, point) <= 0.0) return true;
  }
  return false;
}

}  // namespace lookout::risk
