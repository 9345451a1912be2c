#include "lookout/app/risk_scoring.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lookout::app {
namespace {

std::optional<TimeNs> FirstEventAtLeast(const std::vector<risk::WarningEvent>& events,
                                        risk::WarningLevel level) {
  for (const risk::WarningEvent& e : events) {
    if (e.level >= level) return e.stamp;
  }
  return std::nullopt;
}

int MaxLevel(const std::vector<risk::WarningEvent>& events) {
  int level = 0;
  for (const risk::WarningEvent& e : events) level = std::max(level, static_cast<int>(e.level));
  return level;
}

}  // namespace

risk::RiskAssessment TrueAssessment(const sim::TruthFrame& truth, const RiskStageOptions& options,
                                    const std::vector<Eigen::Vector2d>& route_world,
                                    const risk::Carriageways& carriageways_world) {
  risk::EgoInput ego;
  const sim::KinematicState& e = truth.ego.state;
  ego.position_m = e.pose.translation;
  ego.yaw_rad = e.pose.yaw;
  ego.speed_mps = e.speed_mps;
  ego.acceleration_mps2 = e.acceleration_mps2;
  ego.yaw_rate_radps = e.yaw_rate_radps;
  if (options.ego_prediction == EgoPrediction::kRoute) ego.route_m = route_world;
  ego.carriageways_m = carriageways_world;
  std::vector<risk::ObjectInput> objects;
  objects.reserve(truth.actors.size());
  for (const sim::ActorTruth& a : truth.actors) {
    risk::ObjectInput in;
    in.id = static_cast<std::uint32_t>(a.index);
    in.object_class = a.object_class;
    in.position_m = a.state.pose.translation;
    in.velocity_mps = a.state.Velocity();
    in.yaw_rate_radps = a.state.yaw_rate_radps;
    in.yaw_rad = a.state.pose.yaw;
    objects.push_back(in);
  }
  return risk::AssessRisk(ego, objects, options.risk);
}

RiskScorer::RiskScorer(const Pose2& world_from_odom, const RiskStageOptions& options,
                       std::vector<Eigen::Vector2d> route_world,
                       risk::Carriageways carriageways_world, sim::Expectation expectation,
                       std::vector<std::pair<std::string, double>> contacts,
                       const RiskScoringOptions& scoring)
    : world_from_odom_(world_from_odom),
      options_(options),
      route_world_(std::move(route_world)),
      carriageways_world_(std::move(carriageways_world)),
      expectation_(expectation),
      contacts_(std::move(contacts)),
      scoring_(scoring),
      ideal_(options.warnings) {}

void RiskScorer::Observe(const sim::TruthFrame& truth, const std::vector<tracking::Track>& tracks,
                         const risk::RiskAssessment& assessment) {
  const risk::RiskAssessment ideal =
      TrueAssessment(truth, options_, route_world_, carriageways_world_);
  ideal_.Update(truth.stamp, ideal);

  for (std::size_t i = 0; i < truth.actors.size(); ++i) {
    const std::optional<double> true_ttc = ideal.objects[i].ttc_s;
    if (!true_ttc || *true_ttc >= scoring_.true_ttc_below_s) continue;
    const Eigen::Vector2d actor = truth.actors[i].state.pose.translation;
    // The actor's track: the nearest confirmed track within the match distance.
    const tracking::Track* best = nullptr;
    double best_distance = scoring_.match_distance_m;
    for (const tracking::Track& t : tracks) {
      const double d = (world_from_odom_ * t.Position() - actor).norm();
      if (d <= best_distance) {
        best_distance = d;
        best = &t;
      }
    }
    std::optional<double> estimate;
    if (best) {
      for (const risk::ObjectRisk& o : assessment.objects) {
        if (o.id == best->id) estimate = o.ttc_s;
      }
    }
    if (estimate) {
      abs_error_sum_ += std::abs(*estimate - *true_ttc);
      ++pairs_;
    } else {
      ++missing_;
    }
  }
}

void RiskScorer::Report(const std::vector<risk::WarningEvent>& events,
                        std::map<std::string, double>& metrics) const {
  const std::optional<TimeNs> warning = FirstEventAtLeast(events, risk::WarningLevel::kWarning);
  const std::optional<TimeNs> information =
      FirstEventAtLeast(events, risk::WarningLevel::kInformation);
  metrics["risk.warned"] = warning ? 1.0 : 0.0;
  metrics["risk.max_level"] = MaxLevel(events);
  if (warning) metrics["risk.first_warning_s"] = ToSeconds(*warning);
  if (information) metrics["risk.first_information_s"] = ToSeconds(*information);
  std::optional<double> contact;
  for (const auto& [id, t] : contacts_) {
    if (!contact || t < *contact) contact = t;
  }
  if (warning && contact) metrics["risk.lead_time_s"] = *contact - ToSeconds(*warning);
  if (pairs_ > 0) metrics["risk.ttc_mae_s"] = abs_error_sum_ / static_cast<double>(pairs_);
  metrics["risk.ttc_pairs"] = static_cast<double>(pairs_);
  metrics["risk.ttc_missing"] = static_cast<double>(missing_);
  const std::optional<TimeNs> ideal =
      FirstEventAtLeast(ideal_.events(), risk::WarningLevel::kWarning);
  if (ideal) metrics["risk.ideal_first_warning_s"] = ToSeconds(*ideal);
  metrics["risk.ideal_max_level"] = MaxLevel(ideal_.events());
  if (expectation_.warning) {
    bool met = false;
    if (*expectation_.warning) {
      const double deadline = expectation_.warn_before_s.value_or(
          contact ? *contact - scoring_.min_lead_time_s : std::numeric_limits<double>::infinity());
      met = warning && ToSeconds(*warning) <= deadline &&
            (!contact || *contact - ToSeconds(*warning) >= scoring_.min_lead_time_s);
    } else {
      met = MaxLevel(events) <= static_cast<int>(risk::WarningLevel::kInformation);
    }
    metrics["risk.expectation_met"] = met ? 1.0 : 0.0;
  }
}

}  // namespace lookout::app
