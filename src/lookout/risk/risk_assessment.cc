#include "lookout/risk/risk_assessment.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "lookout/core/random.h"
#include "lookout/risk/bicycle_model.h"
#include "lookout/risk/risk_indicators.h"
#include "lookout/risk/route_prediction.h"

namespace lookout::risk {
namespace {

double TypeRadius(ObjectClass c, const RiskOptions& o) {
  switch (c) {
    case ObjectClass::kCar: return o.car_radius_m;
    case ObjectClass::kTruck: return o.truck_radius_m;
    case ObjectClass::kCyclist: return o.cyclist_radius_m;
    case ObjectClass::kPedestrian: return o.pedestrian_radius_m;
    case ObjectClass::kPole:
    case ObjectClass::kUnknown: return o.unknown_radius_m;
  }
  return o.unknown_radius_m;
}

bool MovesLikeAVehicle(ObjectClass c) {
  return c == ObjectClass::kCar || c == ObjectClass::kTruck || c == ObjectClass::kCyclist;
}

// Circles along a bicycle-model prediction, growing with the distance travelled.
CircleTrack CirclesAlong(const std::vector<BicycleState>& states, double radius_m,
                         double growth_per_metre) {
  CircleTrack t;
  t.centre_m.reserve(states.size());
  t.radius_m.reserve(states.size());
  double travelled = 0.0;
  for (std::size_t k = 0; k < states.size(); ++k) {
    const Eigen::Vector2d p(states[k].x_m, states[k].y_m);
    if (k > 0) travelled += (p - t.centre_m.back()).norm();
    t.centre_m.push_back(p);
    t.radius_m.push_back(radius_m + growth_per_metre * travelled);
  }
  return t;
}

std::size_t StepCount(const RiskOptions& o) {
  return static_cast<std::size_t>(std::floor(o.horizon_s / o.step_s + 1e-9)) + 1;
}

bool SymmetricPsd(const Eigen::Matrix2d& p) {
  if (!p.allFinite()) return false;
  if (std::abs(p(0, 1) - p(1, 0)) > 1e-9 * (1.0 + p.cwiseAbs().maxCoeff())) return false;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(p);
  return eig.eigenvalues().minCoeff() >= -1e-12;
}

bool Valid(const ObjectInput& object) {
  if (!object.position_m.allFinite() || !object.velocity_mps.allFinite() ||
      !std::isfinite(object.yaw_rate_radps)) {
    return false;
  }
  return SymmetricPsd(object.position_covariance) && SymmetricPsd(object.velocity_covariance);
}

}  // namespace

double RiskIndicator(std::optional<double> ttc_s, const RiskOptions& options) {
  if (!ttc_s) return 0.0;
  if (*ttc_s <= options.reaction_time_s) return 1.0;
  if (*ttc_s >= options.horizon_s) return 0.0;
  return (options.horizon_s - *ttc_s) / (options.horizon_s - options.reaction_time_s);
}

CircleTrack PredictEgo(const EgoInput& ego, const RiskOptions& options) {
  if (!ego.route_m.empty()) {
    const std::vector<Eigen::Vector2d> path =
        PredictAlongRoute(ego.route_m, ego.position_m, ego.speed_mps, ego.acceleration_mps2,
                          options.horizon_s, options.step_s);
    std::vector<BicycleState> states;
    states.reserve(path.size());
    for (const Eigen::Vector2d& p : path) states.push_back({p.x(), p.y(), 0.0, 0.0, 0.0});
    return CirclesAlong(states, options.ego_radius_m, options.growth_per_metre);
  }
  BicycleState s{ego.position_m.x(), ego.position_m.y(), ego.yaw_rad, ego.speed_mps, 0.0};
  BicycleInputs u;
  if (options.hold_yaw_rate) {
    s.steering_rad = SteeringFromYawRate(ego.yaw_rate_radps, ego.speed_mps, options.wheelbase_m);
    u.acceleration_mps2 = ego.acceleration_mps2;
  }
  // The ego's own position is known well: its circle grows with the distance only.
  return CirclesAlong(PredictBicycle(s, u, options.wheelbase_m, options.horizon_s, options.step_s),
                      options.ego_radius_m, options.growth_per_metre);
}

CircleTrack PredictObject(const ObjectInput& object, const RiskOptions& options,
                          bool covariance_margin) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(object.position_covariance);
  const double sigma = std::sqrt(std::max(0.0, eig.eigenvalues().maxCoeff()));
  const double radius = TypeRadius(object.object_class, options) +
                        (covariance_margin ? options.covariance_sigmas * sigma : 0.0);
  const double speed = object.velocity_mps.norm();
  if (MovesLikeAVehicle(object.object_class)) {
    const double yaw = speed > 1e-9 ? std::atan2(object.velocity_mps.y(), object.velocity_mps.x())
                                    : 0.0;
    BicycleState s{object.position_m.x(), object.position_m.y(), yaw, speed, 0.0};
    if (options.hold_yaw_rate) {
      s.steering_rad = SteeringFromYawRate(object.yaw_rate_radps, speed, options.wheelbase_m);
    }
    return CirclesAlong(PredictBicycle(s, {}, options.wheelbase_m, options.horizon_s, options.step_s),
                        radius, options.growth_per_metre);
  }
  // Pedestrians and unknown objects: no direction assumed.
  CircleTrack t;
  const std::size_t n = StepCount(options);
  for (std::size_t k = 0; k < n; ++k) {
    const double time = static_cast<double>(k) * options.step_s;
    t.centre_m.push_back(object.position_m);
    t.radius_m.push_back(radius + options.pedestrian_growth_factor * speed * time);
  }
  return t;
}

RiskAssessment AssessRisk(const EgoInput& ego, const std::vector<ObjectInput>& objects,
                          const RiskOptions& options) {
  RiskAssessment out;
  const CircleTrack ego_track = PredictEgo(ego, options);
  const std::vector<Eigen::Vector4d> normals =
      DrawStandardNormals(options.collision_samples, DeriveSeed(options.seed, "risk", 0));
  for (const ObjectInput& object : objects) {
    if (!Valid(object)) {
      ++out.dropped;
      continue;
    }
    ObjectRisk r;
    r.id = object.id;
    const CircleTrack track = PredictObject(object, options);
    if (const auto c = FirstCollision(ego_track, track, options.step_s)) r.ttc_s = c->ttc_s;
    r.risk = RiskIndicator(r.ttc_s, options);
    r.pet_s = PostEncroachmentTime(ego_track, track, options.step_s);
    if (options.collision_samples > 0) {
      const SamplingInput sampling{object.position_covariance, object.velocity_covariance};
      r.collision_probability = CollisionProbability(
          ego_track, PredictObject(object, options, /*covariance_margin=*/false), options.step_s,
          sampling, normals);
    }
    out.objects.push_back(r);
    const std::size_t i = out.objects.size() - 1;
    if (r.ttc_s && (!out.earliest || *r.ttc_s < *out.objects[*out.earliest].ttc_s)) {
      out.earliest = i;
    }
  }
  if (out.earliest) out.risk = out.objects[*out.earliest].risk;
  return out;
}

}  // namespace lookout::risk
