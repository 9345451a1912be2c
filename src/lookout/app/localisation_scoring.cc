#include "lookout/app/localisation_scoring.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace lookout::app {

LocalisationScorer::LocalisationScorer(const Pose2& world_from_odom, std::string prefix)
    : odom_from_world_(world_from_odom.Inverse()), prefix_(std::move(prefix)) {}

void LocalisationScorer::Observe(const std::optional<EgoState>& estimate,
                                 const Pose2& truth_world) {
  if (!estimate) {
    ++missing_;
    last_estimate_.reset();
    return;
  }
  const Pose2 truth = odom_from_world_ * truth_world;
  if (last_estimate_) {
    const Pose2 moved = last_estimate_->Inverse() * estimate->pose;
    const Pose2 truly_moved = last_truth_.Inverse() * truth;
    sum_step_sq_ += (moved.translation - truly_moved.translation).squaredNorm();
    ++steps_;
  }
  last_estimate_ = estimate->pose;
  last_truth_ = truth;
  const double position = (estimate->pose.translation - truth.translation).norm();
  const double heading = WrapAngle(estimate->pose.yaw - truth.yaw);
  sum_position_sq_ += position * position;
  sum_heading_sq_ += heading * heading;
  max_error_m_ = std::max(max_error_m_, position);
  ++frames_;
}

void LocalisationScorer::Report(std::map<std::string, double>& metrics) const {
  metrics[prefix_ + "missing_frames"] = static_cast<double>(missing_);
  if (frames_ == 0) return;
  const double n = static_cast<double>(frames_);
  metrics[prefix_ + "ate_rmse_m"] = std::sqrt(sum_position_sq_ / n);
  metrics[prefix_ + "heading_rmse_deg"] = std::sqrt(sum_heading_sq_ / n) * 180.0 / kPi;
  metrics[prefix_ + "max_error_m"] = max_error_m_;
  if (steps_ > 0) {
    metrics[prefix_ + "step_rmse_m"] = std::sqrt(sum_step_sq_ / static_cast<double>(steps_));
  }
}

}  // namespace lookout::app
