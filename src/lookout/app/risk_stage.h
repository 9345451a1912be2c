#pragma once

// Collision risk as a pipeline stage (seed 004 section VIII), after tracking:
//   A. scenario interpretation: the ego state (pose from the fused frame's ego pose, speed and
//      yaw rate from odometry, acceleration as the slope of the odometry speed over the last
//      half second, steering angle from yaw rate, speed and wheelbase) and the confirmed tracks
//      with their classes, all in the odometry frame;
//   B-D. risk::AssessRisk: predictions, collision circles, TTC, risk indicator, collision
//      probability, PET;
//   E. warning levels with hysteresis (risk::WarningState); each change of level is a
//      timestamped event naming the object and its TTC.
//
// How the ego is predicted (EgoPrediction): along its intended route when one is known (the
// default when the run has one: the simulator's ego path stands for a navigation system's
// route), else from its state: constant speed and heading (the paper) or constant yaw rate and
// acceleration.

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/risk/risk_assessment.h"
#include "lookout/risk/risk_options.h"
#include "lookout/risk/warning_levels.h"
#include "lookout/tracking/tracker.h"

namespace lookout::app {

enum class EgoPrediction { kRoute, kHeading, kYawRate };

// "route", "heading", "yaw-rate"; nullopt for another name.
std::optional<EgoPrediction> ParseEgoPrediction(const std::string& name);
const char* ToString(EgoPrediction prediction);

struct RiskStageOptions {
  risk::RiskOptions risk;
  risk::WarningOptions warnings;
  // kRoute falls back to kHeading while no route is known.
  EgoPrediction ego_prediction = EgoPrediction::kRoute;
  // The odometry speeds over this window give the acceleration (least-squares slope) and the
  // speed (the fitted line at the stamp): one reading's noise (0.05 m/s) over 20 ms would be an
  // acceleration noise of 2.5 m/s^2.
  double acceleration_window_s = 0.5;

  void Validate(const std::string& source = "risk stage options") const;
};

// Step A for the ego: its state at `stamp` from the pose and the odometry readings (in time
// order, those up to `stamp` used). Pure.
risk::EgoInput InterpretEgo(TimeNs stamp, const Pose2& ego_pose,
                            const std::deque<EgoOdometry>& odometry, double window_s);

// Step A for the tracks: the confirmed tracks as the risk model's objects. Pure.
std::vector<risk::ObjectInput> InterpretTracks(const std::vector<tracking::Track>& tracks);

class RiskStage {
 public:
  explicit RiskStage(const RiskStageOptions& options = {});

  void OnOdometry(const EgoOdometry& odometry);
  // The ego's intended route in the odometry frame (empty: none). Points must be finite.
  void SetRoute(std::vector<Eigen::Vector2d> route_m);
  // The carriageways of the ego's map in the odometry frame (empty: none).
  void SetCarriageways(risk::Carriageways roads_m);

  // One cycle at `stamp`: the ego's pose (odometry frame) and the confirmed tracks. A stamp not
  // after the previous one's is ignored (nothing changes; counted).
  void Step(TimeNs stamp, const Pose2& ego_pose, const std::vector<tracking::Track>& tracks);

  // As validated, with risk.hold_yaw_rate set from ego_prediction.
  const RiskStageOptions& options() const { return options_; }
  const risk::EgoInput& last_ego() const { return ego_; }
  const risk::RiskAssessment& last_assessment() const { return assessment_; }
  std::optional<TimeNs> last_stamp() const { return last_stamp_; }
  risk::WarningLevel level() const { return warnings_.level(); }
  const std::vector<risk::WarningEvent>& events() const { return warnings_.events(); }
  // Tracks the assessment dropped (non-finite, covariance not PSD), over the run.
  std::int64_t dropped_tracks() const { return dropped_; }
  std::int64_t refused_steps() const { return refused_; }
  const std::vector<double>& step_ms() const { return step_ms_; }

 private:
  RiskStageOptions options_;
  std::deque<EgoOdometry> odometry_;
  std::vector<Eigen::Vector2d> route_;
  risk::Carriageways carriageways_;
  risk::WarningState warnings_;
  risk::EgoInput ego_;
  risk::RiskAssessment assessment_;
  std::optional<TimeNs> last_stamp_;
  std::int64_t dropped_ = 0;
  std::int64_t refused_ = 0;
  std::vector<double> step_ms_;
};

}  // namespace lookout::app
