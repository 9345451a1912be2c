#include "lookout/sim/scenario.h"

#include "lookout/core/class_footprint.h"

namespace lookout::sim {

double SpeedProfile::At(double t_s) const {
  if (points.empty()) return 0.0;
  if (t_s <= points.front().x()) return points.front().y();
  if (t_s >= points.back().x()) return points.back().y();
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (t_s <= points[i].x()) {
      const Eigen::Vector2d& a = points[i - 1];
      const Eigen::Vector2d& b = points[i];
      const double w = (t_s - a.x()) / (b.x() - a.x());
      return a.y() + w * (b.y() - a.y());
    }
  }
  return points.back().y();
}

// The classes' typical footprints (core/class_footprint.h).
double DefaultLength(ObjectClass c) { return ClassFootprints{}.BoxOf(c).length_m; }

double DefaultWidth(ObjectClass c) { return ClassFootprints{}.BoxOf(c).width_m; }

}  // namespace lookout::sim
