#pragma once

// Risk assessment of seed 004 section VIII, steps B-D, for one instant:
//   B. trajectory prediction to the horizon: vehicles (the ego included) by the kinematic bicycle
//      model (bicycle_model.h); cyclists too (they keep to their path like vehicles, and a
//      bicycle turns through an arc, not on the spot), with their smaller footprint;
//      pedestrians and unknown objects by RiskOptions::pedestrian_model: along their velocity
//      (the default), or as the paper's circle at the detected position whose radius grows with
//      the estimated speed, no direction assumed;
//   C. collision detection: a footprint per object per step (footprint.h, collision.h): an
//      oriented box for vehicles and cyclists (RiskOptions::shape; or the paper's circles), a
//      circle for pedestrians, grown by the position uncertainty (track covariance, and with
//      the distance travelled);
//   D. quantification: the TTC of the earliest potential collision, and the risk indicator;
//      beyond the paper, the collision probability and the post-encroachment time
//      (risk_indicators.h). The probability samples the track's position and velocity
//      covariances, and for pedestrians also the velocities a walker may choose
//      (pedestrian_intent_sigma_mps): where the paper's growing circle says "anywhere within
//      speed x t", the samples say how likely each place is. A pedestrian off the carriageways
//      of the ego's map may wait at the kerb: its probability is weighted by the chance that it
//      steps off (carriageway.h). A car or truck approaching a junction of the ego's map is
//      also predicted under the turns its speed and the corner allow (turn_hypotheses.h),
//      weighted by a prior; its figures are those of the most dangerous plausible manoeuvre.
//
// The risk indicator (the paper's Fig. 7, whose curve the text does not state; Lookout's
// reading): 1 when the TTC is at most the total reaction time (2 s: nothing the driver starts
// then can avoid the collision), falling linearly to 0 at the horizon, 0 without a collision
// inside the horizon.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "lookout/core/object_class.h"
#include "lookout/risk/carriageway.h"
#include "lookout/risk/collision.h"
#include "lookout/risk/risk_options.h"
#include "lookout/risk/turn_hypotheses.h"

namespace lookout::risk {

// The ego as the scenario interpretation (step A) gives it, in a ground-fixed frame.
struct EgoInput {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;
  double speed_mps = 0.0;
  double acceleration_mps2 = 0.0;
  double yaw_rate_radps = 0.0;
  // The intended route (route_prediction.h), in the same frame; empty: none known, the ego is
  // predicted from its state by the bicycle model.
  std::vector<Eigen::Vector2d> route_m;
  // The carriageways of the ego's map (carriageway.h), in the same frame; empty: none known,
  // every walker is left to its state.
  Carriageways carriageways_m;
};

// A tracked object in the same frame.
struct ObjectInput {
  std::uint32_t id = 0;
  ObjectClass object_class = ObjectClass::kUnknown;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();
  double yaw_rate_radps = 0.0;
  // The heading, when known apart from the velocity (a true state); otherwise the velocity's
  // direction at min_heading_speed_mps or more, and none below.
  std::optional<double> yaw_rad;
  Eigen::Matrix2d position_covariance = Eigen::Matrix2d::Zero();  // m^2
  Eigen::Matrix2d velocity_covariance = Eigen::Matrix2d::Zero();  // (m/s)^2
};

// The figures of one object's most dangerous plausible manoeuvre (the largest risk times
// probability, or risk when unsampled, among those of weight >= min_manoeuvre_weight; straight
// on when it ties): its collision probability is given that manoeuvre.
struct ObjectRisk {
  std::uint32_t id = 0;
  std::optional<double> ttc_s;
  double risk = 0.0;
  double collision_probability = 0.0;  // 0 when RiskOptions::collision_samples is 0
  std::optional<double> pet_s;         // post-encroachment time
  Manoeuvre manoeuvre = Manoeuvre::kStraight;
  double manoeuvre_weight = 1.0;       // its prior share among the possible manoeuvres
};

struct RiskAssessment {
  std::vector<ObjectRisk> objects;     // in input order, the dropped ones left out
  std::optional<std::size_t> earliest; // index into objects of the smallest TTC
  double risk = 0.0;                   // of the earliest potential collision
  std::size_t dropped = 0;             // objects with NaN fields or a non-PSD covariance
  bool sampled = false;                // collision probabilities were computed
};

// The risk indicator of a TTC (nullopt: no collision within the horizon). Pure.
double RiskIndicator(std::optional<double> ttc_s, const RiskOptions& options);

// The footprints of each prediction (exposed for tests and the recording). Pure.
FootprintTrack PredictEgo(const EgoInput& ego, const RiskOptions& options);
// With `covariance_margin` false, the footprints leave out the track covariance's margin (for
// sampling, which draws the uncertainty itself).
FootprintTrack PredictObject(const ObjectInput& object, const RiskOptions& options,
                             bool covariance_margin = true);

// Steps B-D. `options` must pass Validate(). Objects with a non-finite field or a covariance
// that is not symmetric positive semi-definite are dropped and counted, never used. Pure.
RiskAssessment AssessRisk(const EgoInput& ego, const std::vector<ObjectInput>& objects,
                          const RiskOptions& options);

}  // namespace lookout::risk
