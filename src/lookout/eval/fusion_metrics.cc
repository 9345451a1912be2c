#include "lookout/eval/fusion_metrics.h"

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "lookout/assignment/linear_assignment.h"
#include "lookout/core/chi_square.h"
#include "lookout/fusion/gate.h"

namespace lookout::eval {

using Eigen::Vector2d;

std::vector<TrueObject> TrueObjectsInVehicleFrame(const sim::TruthFrame& frame) {
  const Pose2 vehicle_from_world = frame.ego.state.pose.Inverse();
  std::vector<TrueObject> objects;
  objects.reserve(frame.actors.size());
  for (const sim::ActorTruth& actor : frame.actors) {
    TrueObject o;
    o.actor_index = actor.index;
    o.footprint.center_m = vehicle_from_world * actor.state.pose.translation;
    o.footprint.yaw_rad = WrapAngle(actor.state.pose.yaw - frame.ego.state.pose.yaw);
    const sim::Shape& shape = actor.footprint;
    if (shape.kind == sim::Shape::Kind::kCircle) {
      o.footprint.length_m = 2.0 * shape.radius;
      o.footprint.width_m = 2.0 * shape.radius;
    } else {
      // Shape::Box: rear right, front right, front left, rear left.
      o.footprint.length_m = (shape.vertices[1] - shape.vertices[0]).norm();
      o.footprint.width_m = (shape.vertices[2] - shape.vertices[1]).norm();
    }
    objects.push_back(o);
  }
  return objects;
}

std::vector<Vector2d> TrueFrontPoints(std::span<const TrueObject> truth,
                                      const Vector2d& viewpoint_m) {
  std::vector<Vector2d> points;
  points.reserve(truth.size());
  for (const TrueObject& t : truth) {
    const auto front = stereo::FrontSegmentFacing(t.footprint, viewpoint_m);
    points.push_back(front ? front->midpoint_m
                           : Vector2d::Constant(std::numeric_limits<double>::infinity()));
  }
  return points;
}

std::vector<int> MatchToTruth(std::span<const Vector2d> points,
                              std::span<const Vector2d> true_points, double radius_m) {
  std::vector<int> match(points.size(), -1);
  if (points.empty() || true_points.empty()) return match;
  const double radius_squared = radius_m * radius_m;
  Eigen::MatrixXd cost(static_cast<Eigen::Index>(points.size()),
                       static_cast<Eigen::Index>(true_points.size()));
  for (Eigen::Index i = 0; i < cost.rows(); ++i) {
    for (Eigen::Index j = 0; j < cost.cols(); ++j) {
      const double d2 = (points[static_cast<std::size_t>(i)] -
                         true_points[static_cast<std::size_t>(j)])
                            .squaredNorm();
      cost(i, j) = d2 <= radius_squared ? d2 : assignment::kForbidden;
    }
  }
  const assignment::Assignment a = assignment::SolveLinearAssignment(cost);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (a.column_of_row[i] != assignment::kUnassigned) match[i] = a.column_of_row[i];
  }
  return match;
}

void FusionMetricOptions::Validate() const {
  if (!(match_radius_m > 0.0)) {
    throw std::invalid_argument("FusionMetricOptions.match_radius_m: must be > 0");
  }
  if (!(nees_band_probability > 0.0 && nees_band_probability < 1.0)) {
    throw std::invalid_argument("FusionMetricOptions.nees_band_probability: must be in (0, 1)");
  }
}

FusionMetricsAccumulator::FusionMetricsAccumulator(FusionMetricOptions options)
    : options_(options) {
  options_.Validate();
}

void FusionMetricsAccumulator::AddFrame(const fusion::FusedObjectFrame& fused,
                                        const LidarObjectFrame& lidar,
                                        std::span<const stereo::StereoPoint> stereo,
                                        std::span<const TrueObject> truth) {
  struct Candidate {
    const fusion::FusedObject* fused;
    const LidarObject* lidar;
    const stereo::StereoPoint* stereo;
  };
  std::vector<Candidate> candidates;
  for (const fusion::FusedObject& f : fused.objects) {
    if (f.sensor_count != 2 || !f.lidar_id || !f.stereo_id || f.footprint_pair) continue;
    const LidarObject* l = nullptr;
    for (const LidarObject& o : lidar.objects) {
      if (o.id == *f.lidar_id) l = &o;
    }
    const stereo::StereoPoint* s = nullptr;
    for (const stereo::StereoPoint& o : stereo) {
      if (o.id == *f.stereo_id) s = &o;
    }
    if (l == nullptr || s == nullptr) continue;  // not the sources given: not scored
    candidates.push_back({&f, l, s});
  }
  if (candidates.empty() || truth.empty()) return;
  const std::vector<Vector2d> true_points = TrueFrontPoints(truth, fused.mount.translation);
  std::vector<Vector2d> fused_points;
  for (const Candidate& c : candidates) fused_points.push_back(c.fused->point_m);
  const std::vector<int> match = MatchToTruth(fused_points, true_points, options_.match_radius_m);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const int j = match[i];
    if (j < 0) continue;
    const Vector2d& truth_point = true_points[static_cast<std::size_t>(j)];
    const Candidate& c = candidates[i];
    const Vector2d error = c.fused->point_m - truth_point;
    fused_squared_ += error.squaredNorm();
    const Vector2d lidar_error = c.lidar->point_m - truth_point;
    const Vector2d stereo_error = c.stereo->point.point_m - truth_point;
    lidar_squared_ += lidar_error.squaredNorm();
    stereo_squared_ += stereo_error.squaredNorm();
    nees_sum_ += error.dot(c.fused->point_covariance.inverse() * error);
    lidar_nees_sum_ += lidar_error.dot(c.lidar->point_covariance.inverse() * lidar_error);
    stereo_nees_sum_ +=
        stereo_error.dot(c.stereo->point.covariance.inverse() * stereo_error);
    ++count_;
  }
}

namespace {
std::optional<double> Rms(double sum_squared, std::int64_t count) {
  if (count == 0) return std::nullopt;
  return std::sqrt(sum_squared / static_cast<double>(count));
}
}  // namespace

std::optional<double> FusionMetricsAccumulator::PositionRmse() const {
  return Rms(fused_squared_, count_);
}
std::optional<double> FusionMetricsAccumulator::LidarOnlyRmse() const {
  return Rms(lidar_squared_, count_);
}
std::optional<double> FusionMetricsAccumulator::StereoOnlyRmse() const {
  return Rms(stereo_squared_, count_);
}

std::optional<double> FusionMetricsAccumulator::MeanNees() const {
  if (count_ == 0) return std::nullopt;
  return nees_sum_ / static_cast<double>(count_);
}

std::optional<NeesBand> FusionMetricsAccumulator::MeanNeesBand() const {
  if (count_ == 0) return std::nullopt;
  const double n = static_cast<double>(count_);
  const double tail = 0.5 * (1.0 - options_.nees_band_probability);
  return NeesBand{ChiSquareQuantile(tail, 2.0 * n) / n,
                  ChiSquareQuantile(1.0 - tail, 2.0 * n) / n};
}

std::map<std::string, double> FusionMetricsAccumulator::Values() const {
  std::map<std::string, double> values;
  values["fusion.matched_objects"] = static_cast<double>(count_);
  if (count_ == 0) return values;
  values["fusion.position_rmse_m"] = *PositionRmse();
  values["fusion.lidar_only_rmse_m"] = *LidarOnlyRmse();
  values["fusion.stereo_only_rmse_m"] = *StereoOnlyRmse();
  values["fusion.nees_mean"] = *MeanNees();
  values["fusion.lidar_nees_mean"] = lidar_nees_sum_ / static_cast<double>(count_);
  values["fusion.stereo_nees_mean"] = stereo_nees_sum_ / static_cast<double>(count_);
  const NeesBand band = *MeanNeesBand();
  values["fusion.nees_band_low"] = band.low;
  values["fusion.nees_band_high"] = band.high;
  return values;
}

}  // namespace lookout::eval
