#include "lookout/sim/scenario.h"

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

// Typical footprints: a mid-size car, a rigid two-axle truck, a bicycle with its rider.
double DefaultLength(ObjectClass c) {
  switch (c) {
    case ObjectClass::kTruck: return 8.0;
    case ObjectClass::kCyclist: return 1.8;
    case ObjectClass::kPedestrian: return 0.6;
    default: return 4.5;
  }
}

double DefaultWidth(ObjectClass c) {
  switch (c) {
    case ObjectClass::kTruck: return 2.5;
    case ObjectClass::kCyclist: return 0.6;
    case ObjectClass::kPedestrian: return 0.6;
    default: return 1.8;
  }
}

}  // namespace lookout::sim
