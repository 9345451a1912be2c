#include "lookout/sim/trajectory.h"

// Motion models of the simulator.
//
// Vehicles (cars, trucks, cyclists, the ego): a kinematic bicycle model whose reference point,
// the midpoint of the rear axle -- the point whose velocity lies along the heading -- is put at
// the centre of the footprint, with the front axle `wheelbase` ahead of it. The state pose is
// therefore the footprint centre with no conversion, and the centre moves with velocity
// speed x heading and turns at yaw rate speed x tan(steer) / wheelbase. Why there and not at
// a real rear axle (about a third of the length behind the centre): the vehicle frame of every
// message has its origin at the footprint centre, and with this choice a unicycle (speed, yaw
// rate) at that origin -- what odometry reports and what a localiser integrates -- reproduces
// the true pose exactly, without a sideslip term that nothing downstream models. The price:
// the body yaws about its centre, not about an axle behind it, so in a turn of radius R a
// real car's heading would differ from the direction its centre moves by about atan(c / R),
// c ~ 0.3 x length the real axle's offset -- about 10 degrees in an 8 m radius junction turn,
// nothing on straights. Everything downstream is scored against this model, so it is the
// truth; it only looks less like a real car in tight turns.
//
// The steering is pure pursuit (Coulter 1992): the goal is the first point of the path, ahead
// of the vehicle's progress, at Euclidean distance lookahead = max(lookahead_min_m,
// lookahead_gain_s x speed) from the reference point; curvature = 2 y_goal / |goal|^2 in the
// vehicle frame, i.e. 2 sin(alpha) / lookahead; the steering angle atan(curvature x
// wheelbase) is clamped to max_steer_rad. The last path segment is extended beyond the end
// for the goal, so the vehicle settles on the final line instead of homing on its end point.
//
// Integration: steering is held constant over each step, so the step is an exact circular arc
// of length equal to the exact integral of the piecewise-linear speed profile over the step.
// Positions are exact for the commanded steering, whatever the speed does within the step.

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>

namespace lookout::sim {
namespace {

using Eigen::Vector2d;

// A polyline with cumulative arc lengths; consecutive duplicate waypoints are dropped so that
// every segment has a direction.
struct Polyline {
  std::vector<Vector2d> points;
  std::vector<double> cumulative_m;  // arc length at each point, cumulative_m[0] = 0

  double length_m() const { return cumulative_m.back(); }
  std::size_t segment_count() const { return points.size() - 1; }
  double SegmentLength(std::size_t i) const { return cumulative_m[i + 1] - cumulative_m[i]; }
  Vector2d Direction(std::size_t i) const { return (points[i + 1] - points[i]) / SegmentLength(i); }
  // The segment holding arc length s: [cumulative_m[i], cumulative_m[i + 1]), the last one
  // for s at or past the end. Requires segment_count() > 0.
  std::size_t SegmentAt(double s) const {
    const auto it = std::upper_bound(cumulative_m.begin() + 1, cumulative_m.end() - 1, s);
    return static_cast<std::size_t>(it - cumulative_m.begin()) - 1;
  }
  Vector2d PointAt(double s) const {
    if (segment_count() == 0) return points.front();
    const std::size_t i = SegmentAt(s);
    const double u = std::clamp((s - cumulative_m[i]) / SegmentLength(i), 0.0, 1.0);
    return points[i] + u * (points[i + 1] - points[i]);
  }
  // Heading of the first segment; 0 for a path that never leaves its first point.
  double InitialHeading() const {
    if (segment_count() == 0) return 0.0;
    const Vector2d d = Direction(0);
    return std::atan2(d.y(), d.x());
  }
};

Polyline MakePolyline(const std::vector<Vector2d>& path) {
  assert(!path.empty());
  Polyline line;
  line.points.push_back(path.front());
  line.cumulative_m.push_back(0.0);
  for (const Vector2d& p : path) {
    const double step = (p - line.points.back()).norm();
    if (step <= 1e-9) continue;
    line.points.push_back(p);
    line.cumulative_m.push_back(line.cumulative_m.back() + step);
  }
  return line;
}

// Speeds are never negative: the format has no reversing, so a negative profile value means
// standing still.
double SpeedAt(const SpeedProfile& profile, double t_s) { return std::max(profile.At(t_s), 0.0); }

// d/dt of SpeedAt, taken on the profile segment starting at or before t (right derivative at
// a breakpoint), 0 outside the profile and where the speed is held at 0.
double AccelerationAt(const SpeedProfile& profile, double t_s) {
  const std::vector<Vector2d>& p = profile.points;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    if (t_s >= p[i].x() && t_s < p[i + 1].x()) {
      const double slope = (p[i + 1].y() - p[i].y()) / (p[i + 1].x() - p[i].x());
      const double v = profile.At(t_s);
      return (v > 0.0 || (v == 0.0 && slope > 0.0)) ? slope : 0.0;
    }
  }
  return 0.0;
}

// Integral over [t0, t1] of max(v, 0) for a v linear on the interval: a trapezoid, or the
// triangle on the positive side of its zero crossing.
double PositiveLinearIntegral(double t0, double v0, double t1, double v1) {
  if (v0 >= 0.0 && v1 >= 0.0) return 0.5 * (v0 + v1) * (t1 - t0);
  if (v0 <= 0.0 && v1 <= 0.0) return 0.0;
  const double t_zero = t0 + (t1 - t0) * v0 / (v0 - v1);
  return v0 > 0.0 ? 0.5 * v0 * (t_zero - t0) : 0.5 * v1 * (t1 - t_zero);
}

// Distance travelled over [t0, t1]: the exact integral of SpeedAt, split at the profile's
// breakpoints (the profile is linear between them).
double TravelDistance(const SpeedProfile& profile, double t0, double t1) {
  double total = 0.0;
  double a = t0;
  for (const Vector2d& knot : profile.points) {
    if (knot.x() <= a) continue;
    if (knot.x() >= t1) break;
    total += PositiveLinearIntegral(a, profile.At(a), knot.x(), profile.At(knot.x()));
    a = knot.x();
  }
  return total + PositiveLinearIntegral(a, profile.At(a), t1, profile.At(t1));
}

// sin(x) / x, with its series near 0 where the quotient loses precision.
double Sinc(double x) {
  if (std::abs(x) < 1e-4) return 1.0 - x * x / 6.0;
  return std::sin(x) / x;
}

// Moves `pose` a distance d along the circular arc of signed curvature k (1/m, positive to the
// left) tangent to its heading: exact for any k, including 0. The chord has length
// d sinc(k d / 2) and points along the heading turned by half the arc's angle.
Pose2 AdvanceOnArc(const Pose2& pose, double curvature, double distance_m) {
  const double half_turn = 0.5 * curvature * distance_m;
  const double chord = distance_m * Sinc(half_turn);
  const double chord_dir = pose.yaw + half_turn;
  return Pose2(pose.translation + chord * Vector2d(std::cos(chord_dir), std::sin(chord_dir)),
               WrapAngle(pose.yaw + 2.0 * half_turn));
}

// Follows a vehicle's progress along its path and picks pure pursuit goal points.
class PathTracker {
 public:
  explicit PathTracker(const Polyline& line) : line_(line) {}

  // Arc length of the path point nearest to p. The search starts at the last result's segment
  // and looks at most `window_m` of arc length ahead, and progress never runs backwards: a
  // path that passes near itself is not short-cut, and cutting inside a corner cannot move
  // progress back to the segment before it. The last segment is extended beyond the path's
  // end, so progress can exceed length_m() (the vehicle is then past the end).
  double Project(const Vector2d& p, double window_m) {
    const std::size_t n = line_.segment_count();
    double best_d2 = -1.0;
    double best_s = progress_m_;
    std::size_t best_seg = segment_;
    for (std::size_t i = segment_; i < n && line_.cumulative_m[i] <= progress_m_ + window_m; ++i) {
      const Vector2d a = line_.points[i];
      const Vector2d ab = line_.points[i + 1] - a;
      double u = (p - a).dot(ab) / ab.squaredNorm();
      u = std::max(u, 0.0);
      if (i + 1 < n) u = std::min(u, 1.0);
      const double d2 = (a + u * ab - p).squaredNorm();
      if (best_d2 < 0.0 || d2 < best_d2) {
        best_d2 = d2;
        best_s = line_.cumulative_m[i] + u * line_.SegmentLength(i);
        best_seg = i;
      }
    }
    if (best_s >= progress_m_) {
      progress_m_ = best_s;
      segment_ = best_seg;
    }
    return progress_m_;
  }

  // The pure pursuit goal: walking along the path from the current progress, the first point
  // at distance >= lookahead_m from p (the last segment extended without end). When the
  // progress point itself is that far away -- the vehicle is off its path by more than the
  // lookahead -- it is the goal, which steers the vehicle back towards the path.
  Vector2d Goal(const Vector2d& p, double lookahead_m) const {
    const std::size_t n = line_.segment_count();
    const double r2 = lookahead_m * lookahead_m;
    Vector2d a = line_.PointAt(std::min(progress_m_, line_.length_m()));
    if (progress_m_ > line_.length_m()) {
      a = line_.points.back() + (progress_m_ - line_.length_m()) * line_.Direction(n - 1);
    }
    for (std::size_t i = segment_; i < n; ++i) {
      const Vector2d f = a - p;
      const double c = f.squaredNorm() - r2;
      if (c >= 0.0) return a;
      // a is inside the lookahead circle: the segment's line leaves it at the larger root of
      // |a + u d - p|^2 = r^2, which is positive since c < 0.
      // On the last segment d is its unit direction and u unbounded (the extension).
      const bool last = i + 1 == n;
      const Vector2d d = last ? line_.Direction(i) : Vector2d(line_.points[i + 1] - a);
      const double qa = d.squaredNorm();
      if (qa > 0.0) {
        const double qb = 2.0 * f.dot(d);
        const double u = (-qb + std::sqrt(qb * qb - 4.0 * qa * c)) / (2.0 * qa);
        if (u <= 1.0 || last) return a + u * d;
      }
      a = line_.points[i + 1];
    }
    return a;
  }

 private:
  const Polyline& line_;
  std::size_t segment_ = 0;
  double progress_m_ = 0.0;
};

// Pure pursuit curvature towards `goal` (1/m, positive left), after the steering clamp.
double PurePursuitCurvature(const Pose2& pose, const Vector2d& goal, double wheelbase_m,
                            double max_steer_rad) {
  const Vector2d g = pose.Rotation().transpose() * (goal - pose.translation);
  const double dist2 = g.squaredNorm();
  if (dist2 <= 1e-12) return 0.0;
  const double curvature = 2.0 * g.y() / dist2;
  const double steer =
      std::clamp(std::atan(curvature * wheelbase_m), -max_steer_rad, max_steer_rad);
  return std::tan(steer) / wheelbase_m;
}

// Number of steps from start to the first sample at or after stop. The small tolerance keeps
// a span that is a whole number of steps from gaining a spurious extra one to rounding.
std::size_t StepCount(double start_s, double stop_s, double step_s) {
  assert(step_s > 0.0);
  if (!(stop_s > start_s)) return 0;
  return static_cast<std::size_t>(std::ceil((stop_s - start_s) / step_s - 1e-9));
}

}  // namespace

Eigen::Vector2d KinematicState::Velocity() const {
  return speed_mps * Eigen::Vector2d(std::cos(pose.yaw), std::sin(pose.yaw));
}

Trajectory Trajectory::Vehicle(const std::vector<Eigen::Vector2d>& path, const SpeedProfile& speed,
                               double length_m, double start_s, double stop_s,
                               const TrajectoryOptions& options) {
  assert(length_m > 0.0 && options.wheelbase_fraction > 0.0);
  Trajectory traj;
  traj.start_s_ = start_s;
  traj.stop_s_ = stop_s;
  traj.step_s_ = options.step_s;

  const Polyline line = MakePolyline(path);
  const double wheelbase_m = options.wheelbase_fraction * length_m;
  const std::size_t steps = StepCount(start_s, stop_s, options.step_s);
  traj.samples_.reserve(steps + 1);

  PathTracker tracker(line);
  Pose2 pose(line.points.front(), line.InitialHeading());
  bool arrived = line.segment_count() == 0;
  double curvature = 0.0;  // held over the step that starts at the current sample
  for (std::size_t k = 0;; ++k) {
    const double t = start_s + static_cast<double>(k) * options.step_s;
    const double v = arrived ? 0.0 : SpeedAt(speed, t);
    double progress_m = line.length_m();
    if (!arrived) {
      const double lookahead_m = std::max(options.lookahead_min_m, options.lookahead_gain_s * v);
      progress_m = tracker.Project(pose.translation, 2.0 * lookahead_m + 1.0);
      curvature = PurePursuitCurvature(pose, tracker.Goal(pose.translation, lookahead_m),
                                       wheelbase_m, options.max_steer_rad);
    }

    KinematicState state;
    state.pose = pose;
    state.speed_mps = v;
    state.yaw_rate_radps = arrived ? 0.0 : v * curvature;
    state.acceleration_mps2 = arrived ? 0.0 : AccelerationAt(speed, t);
    traj.samples_.push_back(state);
    if (k == steps) break;
    if (arrived) continue;

    // The path's end stops the vehicle where it is reached, within the step: it travels only
    // the remaining arc length and stands from the next sample on. The nanometre tolerance
    // keeps rounding from leaving a zero-length last step to take.
    double distance_m = TravelDistance(speed, t, t + options.step_s);
    const double remaining_m = line.length_m() - progress_m;
    if (distance_m >= remaining_m - 1e-9) {
      distance_m = std::max(remaining_m, 0.0);
      arrived = true;
    }
    pose = AdvanceOnArc(pose, curvature, distance_m);
  }
  return traj;
}

// Pedestrians turn on the spot at a waypoint: the heading is the direction of the segment
// they are on (the next one at a waypoint, the last one at the end) and the yaw rate is 0.
// The linear interpolation in At() spreads each turn over one step.
Trajectory Trajectory::Walker(const std::vector<Eigen::Vector2d>& path, const SpeedProfile& speed,
                              double start_s, double stop_s, const TrajectoryOptions& options) {
  Trajectory traj;
  traj.start_s_ = start_s;
  traj.stop_s_ = stop_s;
  traj.step_s_ = options.step_s;

  const Polyline line = MakePolyline(path);
  const std::size_t steps = StepCount(start_s, stop_s, options.step_s);
  traj.samples_.reserve(steps + 1);

  double s_m = 0.0;  // arc length walked
  bool arrived = line.segment_count() == 0;
  for (std::size_t k = 0;; ++k) {
    const double t = start_s + static_cast<double>(k) * options.step_s;
    KinematicState state;
    double heading = line.InitialHeading();
    if (line.segment_count() > 0) {
      const Vector2d d = line.Direction(line.SegmentAt(s_m));
      heading = std::atan2(d.y(), d.x());
    }
    state.pose = Pose2(line.PointAt(s_m), heading);
    state.speed_mps = arrived ? 0.0 : SpeedAt(speed, t);
    state.acceleration_mps2 = arrived ? 0.0 : AccelerationAt(speed, t);
    traj.samples_.push_back(state);
    if (k == steps) break;
    if (arrived) continue;

    s_m += TravelDistance(speed, t, t + options.step_s);
    if (s_m >= line.length_m() - 1e-9) {
      s_m = line.length_m();
      arrived = true;
    }
  }
  return traj;
}

KinematicState Trajectory::At(double t_s) const {
  if (samples_.empty()) return {};
  if (samples_.size() == 1) return samples_.front();
  const double t = std::clamp(t_s, start_s_, stop_s_);
  const double u = (t - start_s_) / step_s_;
  const std::size_t k =
      std::min(static_cast<std::size_t>(std::max(std::floor(u), 0.0)), samples_.size() - 2);
  const double f = std::clamp(u - static_cast<double>(k), 0.0, 1.0);
  const KinematicState& a = samples_[k];
  const KinematicState& b = samples_[k + 1];
  const auto lerp = [f](double x, double y) { return x + f * (y - x); };

  KinematicState s;
  s.pose = Pose2(a.pose.translation + f * (b.pose.translation - a.pose.translation),
                 WrapAngle(a.pose.yaw + f * WrapAngle(b.pose.yaw - a.pose.yaw)));
  s.speed_mps = lerp(a.speed_mps, b.speed_mps);
  s.yaw_rate_radps = lerp(a.yaw_rate_radps, b.yaw_rate_radps);
  s.acceleration_mps2 = lerp(a.acceleration_mps2, b.acceleration_mps2);
  return s;
}

}  // namespace lookout::sim
