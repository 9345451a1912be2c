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

using Extent = ClassFootprints::Box;

double RoundRadius(ObjectClass c, const RiskOptions& o) {
  return c == ObjectClass::kPedestrian ? o.footprints.pedestrian_radius_m : o.unknown_radius_m;
}

bool MovesLikeAVehicle(ObjectClass c) {
  return c == ObjectClass::kCar || c == ObjectClass::kTruck || c == ObjectClass::kCyclist;
}

// A pose per step: what a footprint is placed at.
struct PoseAt {
  Eigen::Vector2d position_m;
  double yaw_rad = 0.0;
};

// Footprints along a prediction, their margin growing with the distance travelled. `extent`
// nullopt: circles of `radius_m`; else boxes of the extent (circles of half its diagonal when
// `shape` is kCircles or the heading is unknown).
FootprintTrack FootprintsAlong(const std::vector<PoseAt>& poses, std::optional<Extent> extent,
                               bool heading_known, double radius_m, double margin_m,
                               const RiskOptions& options) {
  FootprintTrack t;
  t.reserve(poses.size());
  const bool boxes = extent && heading_known && options.shape == CollisionShape::kBoxes;
  const double round =
      extent ? 0.5 * std::hypot(extent->length_m, extent->width_m) : radius_m;
  double travelled = 0.0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (k > 0) travelled += (poses[k].position_m - poses[k - 1].position_m).norm();
    const double grown = margin_m + options.growth_per_metre * travelled;
    t.push_back(boxes ? Footprint::Box(poses[k].position_m, poses[k].yaw_rad, extent->length_m,
                                       extent->width_m, grown)
                      : Footprint::Circle(poses[k].position_m, round + grown));
  }
  return t;
}

std::vector<PoseAt> PosesOf(const std::vector<BicycleState>& states) {
  std::vector<PoseAt> out;
  out.reserve(states.size());
  for (const BicycleState& s : states) out.push_back({{s.x_m, s.y_m}, s.yaw_rad});
  return out;
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
      !std::isfinite(object.yaw_rate_radps) ||
      (object.yaw_rad && !std::isfinite(*object.yaw_rad))) {
    return false;
  }
  return SymmetricPsd(object.position_covariance) && SymmetricPsd(object.velocity_covariance);
}

// A turn that the map and the vehicle's speed allow, its footprints with and without the
// covariance margin, and the weights of the turn and of straight on.
struct ManoeuvreTrack {
  Manoeuvre manoeuvre = Manoeuvre::kStraight;
  double weight = 0.0;
  FootprintTrack track, bare;
};

struct Turns {
  double straight_weight = 1.0;
  std::vector<ManoeuvreTrack> plausible;
};

// The turns of a car or truck approaching a junction of `roads` whose weight reaches
// min_manoeuvre_weight; none for other classes, without a heading or a map. Pure.
Turns PredictTurns(const ObjectInput& object, const Carriageways& roads,
                   const RiskOptions& options) {
  const bool turns = object.object_class == ObjectClass::kCar ||
                     object.object_class == ObjectClass::kTruck;
  const double speed = object.velocity_mps.norm();
  if (!options.turn_hypotheses || !turns || roads.empty() ||
      (!object.yaw_rad && speed < options.min_heading_speed_mps)) {
    return {};
  }
  const double yaw = object.yaw_rad ? *object.yaw_rad
                                    : std::atan2(object.velocity_mps.y(), object.velocity_mps.x());
  const Extent box = options.footprints.BoxOf(object.object_class);
  const TurnLimits limits{options.max_turn_lateral_acceleration_mps2,
                          options.turn_heading_tolerance_rad, 0.5 * box.width_m};
  const std::optional<TurnPath> left =
      PlanTurn(roads, object.position_m, yaw, speed, Manoeuvre::kLeftTurn, limits);
  const std::optional<TurnPath> right =
      PlanTurn(roads, object.position_m, yaw, speed, Manoeuvre::kRightTurn, limits);
  const ManoeuvreWeights w = WeighManoeuvres(options.turn_left_prior, options.turn_right_prior,
                                             left.has_value(), right.has_value());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(object.position_covariance);
  const double margin =
      options.covariance_sigmas * std::sqrt(std::max(0.0, eig.eigenvalues().maxCoeff()));
  Turns out;
  out.straight_weight = w.straight;
  const auto add = [&](Manoeuvre m, const std::optional<TurnPath>& path, double weight) {
    if (!path || weight < options.min_manoeuvre_weight) return;
    std::vector<PoseAt> poses;
    for (const PathPose& p : AlongTurn(object.position_m, yaw, speed, *path, options.horizon_s,
                                       options.step_s)) {
      poses.push_back({p.position_m, p.yaw_rad});
    }
    out.plausible.push_back({m, weight, FootprintsAlong(poses, box, true, 0.0, margin, options),
                             FootprintsAlong(poses, box, true, 0.0, 0.0, options)});
  };
  add(Manoeuvre::kLeftTurn, left, w.left);
  add(Manoeuvre::kRightTurn, right, w.right);
  return out;
}

}  // namespace

double RiskIndicator(std::optional<double> ttc_s, const RiskOptions& options) {
  if (!ttc_s) return 0.0;
  if (*ttc_s <= options.reaction_time_s) return 1.0;
  if (*ttc_s >= options.horizon_s) return 0.0;
  return (options.horizon_s - *ttc_s) / (options.horizon_s - options.reaction_time_s);
}

FootprintTrack PredictEgo(const EgoInput& ego, const RiskOptions& options) {
  const Extent box{options.ego_length_m, options.ego_width_m};
  if (!ego.route_m.empty()) {
    const std::vector<Eigen::Vector2d> path =
        PredictAlongRoute(ego.route_m, ego.position_m, ego.speed_mps, ego.acceleration_mps2,
                          options.horizon_s, options.step_s);
    // The route gives places; the heading is the direction of travel between them (the ego's
    // own while it stands).
    std::vector<PoseAt> poses;
    poses.reserve(path.size());
    double yaw = ego.yaw_rad;
    for (std::size_t k = 0; k < path.size(); ++k) {
      const Eigen::Vector2d ahead = k + 1 < path.size() ? Eigen::Vector2d(path[k + 1] - path[k])
                                                        : Eigen::Vector2d::Zero();
      if (ahead.norm() > 1e-3) yaw = std::atan2(ahead.y(), ahead.x());
      poses.push_back({path[k], yaw});
    }
    return FootprintsAlong(poses, box, true, 0.0, 0.0, options);
  }
  BicycleState s{ego.position_m.x(), ego.position_m.y(), ego.yaw_rad, ego.speed_mps, 0.0};
  BicycleInputs u;
  if (options.hold_yaw_rate) {
    s.steering_rad = SteeringFromYawRate(ego.yaw_rate_radps, ego.speed_mps, options.wheelbase_m);
    u.acceleration_mps2 = ego.acceleration_mps2;
  }
  // The ego's own position is known well: its footprint grows with the distance only.
  return FootprintsAlong(
      PosesOf(PredictBicycle(s, u, options.wheelbase_m, options.horizon_s, options.step_s)), box,
      true, 0.0, 0.0, options);
}

FootprintTrack PredictObject(const ObjectInput& object, const RiskOptions& options,
                             bool covariance_margin) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(object.position_covariance);
  const double sigma = std::sqrt(std::max(0.0, eig.eigenvalues().maxCoeff()));
  const double margin = covariance_margin ? options.covariance_sigmas * sigma : 0.0;
  const double speed = object.velocity_mps.norm();
  if (MovesLikeAVehicle(object.object_class)) {
    const bool heading_known = object.yaw_rad || speed >= options.min_heading_speed_mps;
    const double yaw = object.yaw_rad ? *object.yaw_rad
                       : speed > 1e-9 ? std::atan2(object.velocity_mps.y(), object.velocity_mps.x())
                                      : 0.0;
    BicycleState s{object.position_m.x(), object.position_m.y(), yaw, speed, 0.0};
    if (options.hold_yaw_rate) {
      s.steering_rad = SteeringFromYawRate(object.yaw_rate_radps, speed, options.wheelbase_m);
    }
    return FootprintsAlong(
        PosesOf(PredictBicycle(s, {}, options.wheelbase_m, options.horizon_s, options.step_s)),
        options.footprints.BoxOf(object.object_class), heading_known, 0.0, margin, options);
  }
  const double radius = RoundRadius(object.object_class, options) + margin;
  const std::size_t n = StepCount(options);
  FootprintTrack t;
  t.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double time = static_cast<double>(k) * options.step_s;
    if (options.pedestrian_model == PedestrianModel::kGrowingCircle) {
      // The paper: no direction assumed.
      t.push_back(Footprint::Circle(object.position_m,
                                    radius + options.pedestrian_growth_factor * speed * time));
    } else {
      t.push_back(Footprint::Circle(object.position_m + time * object.velocity_mps, radius));
    }
  }
  return t;
}

RiskAssessment AssessRisk(const EgoInput& ego, const std::vector<ObjectInput>& objects,
                          const RiskOptions& options) {
  RiskAssessment out;
  out.sampled = options.collision_samples > 0;
  const FootprintTrack ego_track = PredictEgo(ego, options);
  const std::vector<Eigen::Vector4d> normals =
      DrawStandardNormals(options.collision_samples, DeriveSeed(options.seed, "risk", 0));
  for (ObjectInput object : objects) {
    if (!Valid(object)) {
      ++out.dropped;
      continue;
    }
    if (object.object_class == ObjectClass::kUnknown &&
        object.velocity_mps.norm() >= options.unknown_as_car_speed_mps) {
      object.object_class = ObjectClass::kCar;
    }
    SamplingInput sampling{object.position_covariance, object.velocity_covariance};
    const bool walks = !MovesLikeAVehicle(object.object_class) &&
                       options.pedestrian_model == PedestrianModel::kConstantVelocity;
    if (walks) {
      const double s = options.pedestrian_intent_sigma_mps;
      sampling.velocity_covariance += s * s * Eigen::Matrix2d::Identity();
    }
    const bool at_kerb = object.object_class == ObjectClass::kPedestrian &&
                         !ego.carriageways_m.empty() &&
                         !OnCarriageway(ego.carriageways_m, object.position_m);
    // One manoeuvre's figures, from its footprints with and without the covariance margin.
    const auto assess = [&](const FootprintTrack& track, const FootprintTrack& bare) {
      ObjectRisk r;
      r.id = object.id;
      if (const auto c = FirstCollision(ego_track, track, options.step_s)) r.ttc_s = c->ttc_s;
      r.risk = RiskIndicator(r.ttc_s, options);
      r.pet_s = PostEncroachmentTime(ego_track, track, options.step_s);
      if (out.sampled) {
        r.collision_probability =
            CollisionProbability(ego_track, bare, options.step_s, sampling, normals);
        if (at_kerb) r.collision_probability *= options.kerb_step_off_probability;
      }
      return r;
    };
    ObjectRisk r = assess(PredictObject(object, options),
                          PredictObject(object, options, /*covariance_margin=*/false));
    const Turns turns = PredictTurns(object, ego.carriageways_m, options);
    r.manoeuvre_weight = turns.straight_weight;
    const auto danger = [&](const ObjectRisk& x) {
      return out.sampled ? x.risk * x.collision_probability : x.risk;
    };
    for (const ManoeuvreTrack& m : turns.plausible) {
      ObjectRisk turned = assess(m.track, m.bare);
      turned.manoeuvre = m.manoeuvre;
      turned.manoeuvre_weight = m.weight;
      if (danger(turned) > danger(r)) r = turned;
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
