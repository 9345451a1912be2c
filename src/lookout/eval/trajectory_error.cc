#include "lookout/eval/trajectory_error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "lookout/core/input_error.h"

namespace lookout::eval {

void TrajectoryErrorOptions::Validate() const {
  if (!(max_interpolation_gap_s > 0.0)) {
    throw InputError("options", 0, "max_interpolation_gap_s", "must be positive");
  }
}

std::optional<Pose2> InterpolatePose(const Trajectory2& trajectory, double t_s, double max_gap_s) {
  const auto after = std::upper_bound(trajectory.begin(), trajectory.end(), t_s,
                                      [](double t, const StampedPose2& p) { return t < p.t_s; });
  if (after == trajectory.begin()) return std::nullopt;
  const StampedPose2& before = *(after - 1);
  if (before.t_s == t_s) return before.pose;
  if (after == trajectory.end()) return std::nullopt;
  const double gap = after->t_s - before.t_s;
  if (gap > max_gap_s) return std::nullopt;
  const double alpha = (t_s - before.t_s) / gap;
  const Eigen::Vector2d position =
      before.pose.translation + alpha * (after->pose.translation - before.pose.translation);
  const double yaw = before.pose.yaw + alpha * WrapAngle(after->pose.yaw - before.pose.yaw);
  return Pose2(position, WrapAngle(yaw));
}

Pose2 AlignRigid(const std::vector<Eigen::Vector2d>& source,
                 const std::vector<Eigen::Vector2d>& target) {
  assert(source.size() == target.size() && !source.empty());
  const double n = static_cast<double>(source.size());
  Eigen::Vector2d source_mean = Eigen::Vector2d::Zero();
  Eigen::Vector2d target_mean = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < source.size(); ++i) {
    source_mean += source[i];
    target_mean += target[i];
  }
  source_mean /= n;
  target_mean /= n;
  // The 2D case of the SVD of the cross-covariance: the best rotation turns the centred source
  // by the angle of sum(conj(a) * b) in complex notation.
  double sum_dot = 0.0;
  double sum_cross = 0.0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const Eigen::Vector2d a = source[i] - source_mean;
    const Eigen::Vector2d b = target[i] - target_mean;
    sum_dot += a.dot(b);
    sum_cross += a.x() * b.y() - a.y() * b.x();
  }
  const double yaw = std::atan2(sum_cross, sum_dot);
  Pose2 rotation(0.0, 0.0, yaw);
  return Pose2(target_mean - rotation.Rotation() * source_mean, yaw);
}

AbsoluteTrajectoryError AbsoluteErrorOfPairs(const std::vector<Pose2>& estimate,
                                             const std::vector<Pose2>& reference) {
  assert(estimate.size() == reference.size());
  AbsoluteTrajectoryError result;
  result.matched = estimate.size();
  if (estimate.empty()) return result;
  std::vector<Eigen::Vector2d> source;
  std::vector<Eigen::Vector2d> target;
  source.reserve(estimate.size());
  target.reserve(estimate.size());
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    source.push_back(estimate[i].translation);
    target.push_back(reference[i].translation);
  }
  result.alignment = AlignRigid(source, target);
  double sum_position = 0.0;
  double sum_heading = 0.0;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    const Pose2 aligned = result.alignment * estimate[i];
    sum_position += (aligned.translation - reference[i].translation).squaredNorm();
    const double heading = WrapAngle(aligned.yaw - reference[i].yaw);
    sum_heading += heading * heading;
  }
  const double n = static_cast<double>(estimate.size());
  result.ate_rmse_m = std::sqrt(sum_position / n);
  result.heading_rmse_rad = std::sqrt(sum_heading / n);
  return result;
}

void CheckTrajectoryTimes(const Trajectory2& trajectory, const std::string& name) {
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    if (!std::isfinite(trajectory[i].t_s)) {
      throw InputError(name, 0, fmt::format("[{}].t", i), "time is not finite");
    }
    if (i > 0 && trajectory[i].t_s < trajectory[i - 1].t_s) {
      throw InputError(name, 0, fmt::format("[{}].t", i),
                       fmt::format("time goes backwards ({} s after {} s)", trajectory[i].t_s,
                                   trajectory[i - 1].t_s));
    }
  }
}

AbsoluteTrajectoryError ComputeAbsoluteTrajectoryError(const Trajectory2& estimate,
                                                       const Trajectory2& reference,
                                                       const TrajectoryErrorOptions& options) {
  options.Validate();
  CheckTrajectoryTimes(estimate, "estimate trajectory");
  std::vector<Pose2> paired_estimate;
  std::vector<Pose2> paired_reference;
  std::size_t unmatched = 0;
  for (const StampedPose2& r : reference) {
    const std::optional<Pose2> e =
        std::isfinite(r.t_s) ? InterpolatePose(estimate, r.t_s, options.max_interpolation_gap_s)
                             : std::nullopt;
    if (!e) {
      ++unmatched;
      continue;
    }
    paired_estimate.push_back(*e);
    paired_reference.push_back(r.pose);
  }
  AbsoluteTrajectoryError result = AbsoluteErrorOfPairs(paired_estimate, paired_reference);
  result.unmatched = unmatched;
  return result;
}

}  // namespace lookout::eval
