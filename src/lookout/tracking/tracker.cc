#include "lookout/tracking/tracker.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <iterator>

#include "lookout/core/chi_square.h"

namespace lookout::tracking {

namespace {

// Finite, symmetric (to rounding) and positive definite. A symmetric 2 x 2 matrix is positive
// definite when its first pivot and its determinant are (Sylvester), read from the lower
// triangle as an eigen-solver would: no eigen-decomposition, since MeasurementFor asks this of
// a class centre for every track and detection the trackers gate.
bool UsableCovariance(const Eigen::Matrix2d& c) {
  if (!c.allFinite()) return false;
  if (std::abs(c(0, 1) - c(1, 0)) > 1e-9 * (1.0 + c.cwiseAbs().maxCoeff())) return false;
  return c(0, 0) > 0.0 && c(0, 0) * c(1, 1) - c(1, 0) * c(1, 0) > 0.0;
}

}  // namespace

std::vector<Detection> UsableDetections(const std::vector<Detection>& detections) {
  std::vector<Detection> usable;
  usable.reserve(detections.size());
  std::copy_if(detections.begin(), detections.end(), std::back_inserter(usable),
               [](const Detection& d) {
                 return d.position_m.allFinite() && UsableCovariance(d.covariance);
               });
  return usable;
}

ClassCentre MeasurementFor(const Detection& d, ObjectClass track_class) {
  if (d.object_class == ObjectClass::kUnknown) {
    const std::optional<ClassCentre>& c = d.class_centres[static_cast<std::size_t>(track_class)];
    if (c && c->position_m.allFinite() && UsableCovariance(c->covariance)) return *c;
  }
  return {d.position_m, d.covariance};
}

Gaussian BirthState(const Detection& d, double speed_sigma_mps) {
  Gaussian g{Eigen::Vector4d(d.position_m.x(), d.position_m.y(), 0.0, 0.0),
             Eigen::Matrix4d::Zero()};
  g.cov.topLeftCorner<2, 2>() = d.covariance;
  Eigen::Matrix2d velocity_cov = Eigen::Matrix2d::Identity() * speed_sigma_mps * speed_sigma_mps;
  if (d.velocity_mps && d.velocity_mps->allFinite() && UsableCovariance(d.velocity_covariance) &&
      d.velocity_covariance.trace() < velocity_cov.trace()) {
    g.mean.segment<2>(2) = *d.velocity_mps;
    velocity_cov = d.velocity_covariance;
  }
  g.cov.bottomRightCorner<2, 2>() = velocity_cov;
  return g;
}

std::optional<Gaussian> ThreePointVelocity(std::span<const SeenPoint> p,
                                           double agreement_probability) {
  if (p.size() < 3) return std::nullopt;
  const double dt1 = ToSeconds(p[1].stamp - p[0].stamp);
  const double dt2 = ToSeconds(p[2].stamp - p[1].stamp);
  if (!(dt1 > 0.0) || !(dt2 > 0.0)) return std::nullopt;
  const Eigen::Vector2d v12 = (p[1].point_m - p[0].point_m) / dt1;
  const Eigen::Vector2d v23 = (p[2].point_m - p[1].point_m) / dt2;
  // v12 - v23 = -s1 / dt1 + s2 (1 / dt1 + 1 / dt2) - s3 / dt2.
  const double middle = 1.0 / dt1 + 1.0 / dt2;
  const Eigen::Matrix2d s = p[0].covariance / (dt1 * dt1) + p[1].covariance * middle * middle +
                            p[2].covariance / (dt2 * dt2);
  const Eigen::Vector2d d = v12 - v23;
  if (!d.allFinite() || !s.allFinite() || !(s.determinant() > 0.0)) return std::nullopt;
  if (d.dot(s.inverse() * d) > ChiSquareQuantile(agreement_probability, 2.0)) return std::nullopt;
  const double t = dt1 + dt2;
  return Gaussian{(p[2].point_m - p[0].point_m) / t, (p[0].covariance + p[2].covariance) / (t * t)};
}

Gaussian WithSurerVelocity(const Gaussian& state, const Gaussian& velocity) {
  if (!(velocity.cov.trace() < state.cov.block<2, 2>(2, 2).trace())) return state;
  Gaussian out = state;
  out.mean.segment<2>(2) = velocity.mean;
  out.cov.block<2, 2>(2, 2) = velocity.cov;
  out.cov.block<2, 2>(0, 2).setZero();
  out.cov.block<2, 2>(2, 0).setZero();
  return out;
}

Gaussian WithSeenVelocity(const Gaussian& state, const EarlySeenPoints& early_seen_points,
                          double agreement_probability) {
  if (!(agreement_probability > 0.0) || early_seen_points.size() != 3) return state;
  const std::optional<Gaussian> v = ThreePointVelocity(
      {early_seen_points.data(), early_seen_points.size()}, agreement_probability);
  return v ? WithSurerVelocity(state, *v) : state;
}

bool ClassesCompatible(ObjectClass track, ObjectClass detection) {
  if (track == ObjectClass::kUnknown || detection == ObjectClass::kUnknown) return true;
  const auto vehicle = [](ObjectClass c) {
    return c == ObjectClass::kCar || c == ObjectClass::kTruck;
  };
  if (vehicle(track) && vehicle(detection)) return true;  // car and truck are easily confused
  return track == detection;
}

}  // namespace lookout::tracking
