#pragma once

// Scores the risk stage against the simulator's ground truth: the risk.* keys of
// docs/cli-contract.md and a few beside them.
//
// - risk.warned (1 or 0), risk.first_warning_s (scenario time of the first warning event),
//   risk.lead_time_s (the earliest true contact, from the simulator's contact times, minus the
//   first warning; absent without a contact or a warning), risk.first_information_s,
//   risk.max_level (0 none, 1 information, 2 warning).
// - risk.ttc_mae_s: the true TTC is the TTC "in the same sense" as the estimate: the same
//   prediction (the same model of each class, the same footprints, the ego along the same route
//   or from its state as the stage) run on the true states of the ego and the actors (their
//   true headings; no covariance, so no covariance margin). Wherever an actor's true TTC is below
//   4 s, its track (the confirmed track nearest to it within 2 m) is compared: the mean absolute
//   difference over those frames, risk.ttc_pairs of them; risk.ttc_missing counts the frames where
//   the actor had no track or its track no TTC. This measures what perception and tracking cost the
//   TTC; how far the prediction model itself is from the real future shows in the lead time.
// - risk.ideal_first_warning_s, risk.ideal_max_level: the warning levels (same rule, thresholds
//   and hysteresis) on the true states' assessment: what perfect perception would give, so that
//   the gap to the stage's own figures is what the perception chain loses.
// - risk.expectation_met: 1 when the scenario's `expect` holds (a warning by warn_before and at
//   least 2.0 s before the true contact; or, for expect.warning false, nothing above
//   information), 0 otherwise; absent when the scenario states no expectation.

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lookout/app/risk_stage.h"
#include "lookout/core/pose2.h"
#include "lookout/risk/warning_levels.h"
#include "lookout/sim/scenario.h"
#include "lookout/sim/truth.h"
#include "lookout/tracking/tracker.h"

namespace lookout::app {

struct RiskScoringOptions {
  double true_ttc_below_s = 4.0;
  double match_distance_m = 2.0;
  double min_lead_time_s = 2.0;  // the driver's and the vehicle's reaction time
};

// The risk of each actor of `truth` (objects indexed as truth.actors) under `options`'
// prediction, from the true states (poses, velocities, no covariance), the ego along
// `route_world` when the options predict along a route, with the map's `carriageways_world`.
// Pure.
risk::RiskAssessment TrueAssessment(const sim::TruthFrame& truth, const RiskStageOptions& options,
                                    const std::vector<Eigen::Vector2d>& route_world,
                                    const risk::Carriageways& carriageways_world = {});

class RiskScorer {
 public:
  // `contacts`: the simulator's true contacts (actor id, scenario time).
  RiskScorer(const Pose2& world_from_odom, const RiskStageOptions& options,
             std::vector<Eigen::Vector2d> route_world, risk::Carriageways carriageways_world,
             sim::Expectation expectation, std::vector<std::pair<std::string, double>> contacts,
             const RiskScoringOptions& scoring = {});

  // After a cycle in which the risk stage ran: the truth at its stamp, the tracks it assessed
  // (odometry frame) and its assessment.
  void Observe(const sim::TruthFrame& truth, const std::vector<tracking::Track>& tracks,
               const risk::RiskAssessment& assessment);

  // `events`: the stage's warning events over the run.
  void Report(const std::vector<risk::WarningEvent>& events,
              std::map<std::string, double>& metrics) const;

 private:
  Pose2 world_from_odom_;
  RiskStageOptions options_;
  std::vector<Eigen::Vector2d> route_world_;
  risk::Carriageways carriageways_world_;
  sim::Expectation expectation_;
  std::vector<std::pair<std::string, double>> contacts_;
  RiskScoringOptions scoring_;
  risk::WarningState ideal_;
  double abs_error_sum_ = 0.0;
  std::int64_t pairs_ = 0;
  std::int64_t missing_ = 0;
};

}  // namespace lookout::app
