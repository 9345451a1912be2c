#include "lookout/risk/turn_hypotheses.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "lookout/core/planar_geometry.h"

namespace lookout::risk {
namespace {

Eigen::Vector2d LeftOf(const Eigen::Vector2d& d) { return {-d.y(), d.x()}; }

Eigen::Vector2d Heading(double yaw_rad) { return {std::cos(yaw_rad), std::sin(yaw_rad)}; }

// The point x with x . n1 = c1 and x . n2 = c2 (n1, n2 not parallel).
Eigen::Vector2d MeetOfLines(const Eigen::Vector2d& n1, double c1, const Eigen::Vector2d& n2,
                            double c2) {
  Eigen::Matrix2d m;
  m.row(0) = n1.transpose();
  m.row(1) = n2.transpose();
  return m.inverse() * Eigen::Vector2d(c1, c2);
}

// The road that the vehicle drives along: it is on it and heads along its axis.
const Footprint* OwnRoad(const Carriageways& roads, const Eigen::Vector2d& p,
                         const Eigen::Vector2d& h, double tolerance_rad) {
  for (const Footprint& road : roads) {
    if (std::abs(Cross(h, road.axis)) <= std::sin(tolerance_rad) &&
        OnCarriageway({road}, p)) {
      return &road;
    }
  }
  return nullptr;
}

}  // namespace

const char* ToString(Manoeuvre manoeuvre) {
  switch (manoeuvre) {
    case Manoeuvre::kStraight: return "straight";
    case Manoeuvre::kLeftTurn: return "left";
    case Manoeuvre::kRightTurn: return "right";
  }
  return "straight";
}

std::optional<TurnPath> PlanTurn(const Carriageways& roads, const Eigen::Vector2d& position_m,
                                 double yaw_rad, double speed_mps, Manoeuvre turn,
                                 const TurnLimits& limits) {
  if (turn == Manoeuvre::kStraight) return std::nullopt;
  const Eigen::Vector2d& p = position_m;
  const Eigen::Vector2d h = Heading(yaw_rad);
  const Footprint* own = OwnRoad(roads, p, h, limits.heading_tolerance_rad);
  if (own == nullptr) return std::nullopt;
  // The nearest road crossing ahead whose crossing lies on it; none when the vehicle is
  // already on it (in the junction: the turn, if any, has begun and its state shows it).
  const Footprint* crossing = nullptr;
  double to_axis_m = std::numeric_limits<double>::infinity();
  for (const Footprint& road : roads) {
    if (&road == own || std::abs(Cross(h, road.axis)) <= std::sin(limits.heading_tolerance_rad)) {
      continue;
    }
    const double d = Cross(road.centre_m - p, road.axis) / Cross(h, road.axis);
    const double along = (p + d * h - road.centre_m).dot(road.axis);
    if (std::abs(along) > road.half_length_m) continue;
    if (OnCarriageway({road}, p)) return std::nullopt;
    if (d > 0.0 && d < to_axis_m) {
      to_axis_m = d;
      crossing = &road;
    }
  }
  if (crossing == nullptr) return std::nullopt;

  const double side = turn == Manoeuvre::kLeftTurn ? 1.0 : -1.0;
  // The exit direction: the crossing road's axis on the turn's side.
  const Eigen::Vector2d e =
      side * Cross(h, crossing->axis) > 0.0 ? crossing->axis : Eigen::Vector2d(-crossing->axis);
  const double angle = std::atan2(Cross(h, e), h.dot(e));
  // The vehicle's lane offset, to the right of its travel, from its road's axis; the exit lane
  // is as far to the right of the exit direction from the crossing road's axis.
  const double lane_offset_m = -Cross(h, p - own->centre_m);
  const Eigen::Vector2d exit_point = crossing->centre_m - lane_offset_m * LeftOf(e);
  // Where the vehicle's line meets the exit lane's, at distance `meet_m` along h.
  const double meet_m = Cross(exit_point - p, e) / Cross(h, e);
  const Eigen::Vector2d meet = p + meet_m * h;
  // Inside normals of the two lines (towards the arc's centre): the centre is R from both,
  // centre = meet + R u with n1 . u = n2 . u = 1.
  const Eigen::Vector2d n1 = side * LeftOf(h);
  const Eigen::Vector2d n2 = side * LeftOf(e);
  const Eigen::Vector2d u = MeetOfLines(n1, 1.0, n2, 1.0);
  // The kerb corner on the turn's inside: the own road's edge on that side meets the crossing
  // road's near edge.
  const Eigen::Vector2d own_normal =
      LeftOf(own->axis).dot(n1) > 0.0 ? LeftOf(own->axis) : Eigen::Vector2d(-LeftOf(own->axis));
  const Eigen::Vector2d near_normal = LeftOf(crossing->axis).dot(p - crossing->centre_m) > 0.0
                                          ? LeftOf(crossing->axis)
                                          : Eigen::Vector2d(-LeftOf(crossing->axis));
  const Eigen::Vector2d corner = MeetOfLines(
      own_normal, own_normal.dot(own->centre_m) + own->half_width_m, near_normal,
      near_normal.dot(crossing->centre_m) + crossing->half_width_m);
  // The vehicle's inner side clears the corner: |meet + R u - corner| <= R - w, a quadratic
  // a R^2 + b R + c <= 0 with a = |u|^2 - 1 > 0 for any turn short of a U-turn.
  const double w = limits.half_width_m;
  const Eigen::Vector2d q = meet - corner;
  const double a = u.squaredNorm() - 1.0;
  const double b = 2.0 * q.dot(u) + 2.0 * w;
  const double c = q.squaredNorm() - w * w;
  const double disc = b * b - 4.0 * a * c;
  if (a <= 1e-12 || disc < 0.0) return std::nullopt;
  const double r_min = std::max((-b - std::sqrt(disc)) / (2.0 * a), w);
  double r_max = (-b + std::sqrt(disc)) / (2.0 * a);
  // The turn-in (meet + R u . h along the line) must still lie ahead.
  const double back_per_radius = -u.dot(h);
  if (back_per_radius > 0.0) r_max = std::min(r_max, meet_m / back_per_radius);
  if (r_max < r_min) return std::nullopt;
  const double v2 = speed_mps * speed_mps;
  const double radius = std::clamp(v2 / limits.max_lateral_acceleration_mps2, r_min, r_max);
  if (v2 / radius > limits.max_lateral_acceleration_mps2 * (1.0 + 1e-9)) return std::nullopt;
  return TurnPath{meet_m - radius * back_per_radius, radius, angle, meet + radius * u};
}

std::vector<PathPose> AlongTurn(const Eigen::Vector2d& position_m, double yaw_rad,
                                double speed_mps, const TurnPath& path, double horizon_s,
                                double dt_s) {
  const Eigen::Vector2d h = Heading(yaw_rad);
  const double side = path.turn_angle_rad >= 0.0 ? 1.0 : -1.0;
  const double arc_m = path.radius_m * std::abs(path.turn_angle_rad);
  const Eigen::Vector2d centre = position_m + path.turn_in_m * h + side * path.radius_m * LeftOf(h);
  const double exit_yaw = yaw_rad + path.turn_angle_rad;
  const Eigen::Vector2d exit_point = centre - side * path.radius_m * LeftOf(Heading(exit_yaw));
  const auto steps = static_cast<std::size_t>(std::floor(horizon_s / dt_s + 1e-9)) + 1;
  std::vector<PathPose> out;
  out.reserve(steps);
  for (std::size_t k = 0; k < steps; ++k) {
    const double s = speed_mps * dt_s * static_cast<double>(k);
    if (s <= path.turn_in_m) {
      out.push_back({position_m + s * h, yaw_rad});
    } else if (s <= path.turn_in_m + arc_m) {
      const double yaw = yaw_rad + side * (s - path.turn_in_m) / path.radius_m;
      out.push_back({centre - side * path.radius_m * LeftOf(Heading(yaw)), yaw});
    } else {
      out.push_back({exit_point + (s - path.turn_in_m - arc_m) * Heading(exit_yaw), exit_yaw});
    }
  }
  return out;
}

ManoeuvreWeights WeighManoeuvres(double left_prior, double right_prior, bool left_possible,
                                 bool right_possible) {
  const double left = left_possible ? left_prior : 0.0;
  const double right = right_possible ? right_prior : 0.0;
  const double straight = 1.0 - left_prior - right_prior;
  const double total = straight + left + right;
  if (total <= 0.0) return {};  // no prior mass on what is possible: straight on
  return {straight / total, left / total, right / total};
}

}  // namespace lookout::risk
