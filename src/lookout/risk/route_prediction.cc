#include "lookout/risk/route_prediction.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lookout::risk {
namespace {

constexpr double kOffsetFade_s = 1.0;

}  // namespace

double ProjectOntoRoute(const std::vector<Eigen::Vector2d>& route, const Eigen::Vector2d& p) {
  double best_distance = (p - route.front()).squaredNorm();
  double best_s = 0.0;
  double s = 0.0;
  for (std::size_t i = 1; i < route.size(); ++i) {
    const Eigen::Vector2d a = route[i - 1];
    const Eigen::Vector2d ab = route[i] - a;
    const double length = ab.norm();
    if (length <= 0.0) continue;
    const double u = std::clamp((p - a).dot(ab) / (length * length), 0.0, 1.0);
    const double d = (p - (a + u * ab)).squaredNorm();
    if (d < best_distance) {
      best_distance = d;
      best_s = s + u * length;
    }
    s += length;
  }
  return best_s;
}

Eigen::Vector2d RoutePointAt(const std::vector<Eigen::Vector2d>& route, double s_m) {
  double s = 0.0;
  for (std::size_t i = 1; i < route.size(); ++i) {
    const Eigen::Vector2d ab = route[i] - route[i - 1];
    const double length = ab.norm();
    if (s_m <= s + length && length > 0.0) {
      return route[i - 1] + std::max(0.0, s_m - s) / length * ab;
    }
    s += length;
  }
  return route.back();
}

std::vector<Eigen::Vector2d> PredictAlongRoute(const std::vector<Eigen::Vector2d>& route,
                                               const Eigen::Vector2d& position_m,
                                               double speed_mps, double acceleration_mps2,
                                               double horizon_s, double dt_s) {
  const auto steps = static_cast<std::size_t>(std::floor(horizon_s / dt_s + 1e-9));
  const double s0 = ProjectOntoRoute(route, position_m);
  const double v0 = std::max(0.0, speed_mps);
  // Braking stops the ego at t_stop; it does not reverse.
  const double t_stop = acceleration_mps2 < 0.0 ? v0 / -acceleration_mps2
                                                : std::numeric_limits<double>::infinity();
  // The ego is seldom exactly on the polyline (a driver cuts corners): its offset from the route
  // fades out over about a second, as a steering controller brings it back.
  const Eigen::Vector2d offset = position_m - RoutePointAt(route, s0);
  std::vector<Eigen::Vector2d> out;
  out.reserve(steps + 1);
  for (std::size_t k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) * dt_s;
    const double tm = std::min(t, t_stop);
    out.push_back(RoutePointAt(route, s0 + v0 * tm + 0.5 * acceleration_mps2 * tm * tm) +
                  std::exp(-t / kOffsetFade_s) * offset);
  }
  return out;
}

}  // namespace lookout::risk
