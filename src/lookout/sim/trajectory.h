#pragma once

// The motion of the ego and of each actor over the whole scenario, computed once when the
// simulator is built and interpolated afterwards: the state at any time is then a pure,
// thread-safe function of time, which is what lets sensor frames be simulated in parallel and
// lets ground truth look into the future (contact times).

#include <Eigen/Core>
#include <vector>

#include "lookout/core/pose2.h"
#include "lookout/sim/scenario.h"

namespace lookout::sim {

struct KinematicState {
  // Footprint centre and heading, world frame. For vehicles the centre is also the bicycle
  // model's no-slip point, so the velocity lies along the heading (trajectory.cc says why).
  Pose2 pose;
  double speed_mps = 0.0;        // signed along the heading
  double yaw_rate_radps = 0.0;
  double acceleration_mps2 = 0.0;
  Eigen::Vector2d Velocity() const;  // world frame
};

struct TrajectoryOptions {
  double step_s = 0.01;             // integration step
  double wheelbase_fraction = 0.6;  // wheelbase = fraction x length for vehicles
  double lookahead_min_m = 3.0;     // pure pursuit lookahead: max(min, gain x speed)
  double lookahead_gain_s = 0.6;
  double max_steer_rad = 0.6;
};

class Trajectory {
 public:
  // Cars, trucks, cyclists and the ego: kinematic bicycle model steered by pure pursuit along
  // `path`, speed from `speed`; stops at the path's end. Pedestrians: along the polyline,
  // turning on the spot at waypoints. Both start at the first waypoint heading along the first
  // segment; the profile is read at scenario time, and a negative speed means standing (no
  // reversing). trajectory.cc documents the model's reference point and integration.
  static Trajectory Vehicle(const std::vector<Eigen::Vector2d>& path, const SpeedProfile& speed,
                            double length_m, double start_s, double stop_s,
                            const TrajectoryOptions& options = {});
  static Trajectory Walker(const std::vector<Eigen::Vector2d>& path, const SpeedProfile& speed,
                           double start_s, double stop_s, const TrajectoryOptions& options = {});

  bool Present(double t_s) const { return t_s >= start_s_ && t_s <= stop_s_; }
  double start_s() const { return start_s_; }
  double stop_s() const { return stop_s_; }
  // Interpolated state; t clamped to [start, stop]. The samples are exact (trajectory.cc);
  // between two, position and speed are linear and yaw turns the short way. The position is
  // then off by at most |a| step^2 / 8 for an acceleration a along or across the track:
  // 0.125 mm at 10 m/s^2 and the default step.
  KinematicState At(double t_s) const;

 private:
  double start_s_ = 0.0;
  double stop_s_ = 0.0;
  double step_s_ = 0.01;
  std::vector<KinematicState> samples_;  // at start_s_ + k * step_s_
};

}  // namespace lookout::sim
