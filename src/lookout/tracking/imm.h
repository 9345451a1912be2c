#pragma once

// Interacting Multiple Model filter (Blom and Bar-Shalom 1988; the cycle of Bar-Shalom, Li and
// Kirubarajan 2001, section 11.6.6) over models of different state sizes, as pure functions of an
// ImmState that a track holds:
//
//   Predict     1. mixing probabilities mu_i|j = pi_ij mu_i / c_j,  c_j = sum_i pi_ij mu_i
//               2. mixed initial condition of each model j (moment matching, MixInto)
//               3. mode-matched prediction of each model over dt; probabilities become c_j
//   Update      4. mode-matched Kalman updates, likelihoods L_j = N(nu_j; 0, S_j)
//               5. mu_j = L_j c_j / sum_l L_l c_l
//   Combine     6. moment-matched combined estimate
//
// Different state sizes (CV 4, CA 6, CTR 5; motion_models.h): every model's state is a subset of
// the canonical [x y vx vy ax ay omega]. Mixing into model j is done in j's components; a model i
// that lacks one of them (CV has no acceleration, say) is augmented, for that component, with the
// moment-matched mean and variance of the models that do carry it, weighted by their mixing
// probabilities, and zero cross-covariance to its own components. This is the "unbiased mixing"
// idea of Granstrom, Willett and Bar-Shalom, "Systematic approach to IMM mixing for unequal
// dimension states", IEEE Trans. AES 51(4), 2015: filling with zeros (the naive scheme) would
// drag a CA model's acceleration towards 0 every cycle in proportion to the CV weight, and
// filling with the target model's own estimate would ignore the other carriers. With this fill
// the mixed mean and variance of each component equal those of the carriers' mixture: the
// mixture is unbiased; only the cross-covariance of a filled component with the common ones
// shrinks (by the carriers' total weight).
//
// Determinism: fixed loop orders, no threads, no randomness.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "lookout/core/time.h"
#include "lookout/tracking/kalman.h"
#include "lookout/tracking/motion_models.h"

namespace lookout::tracking {

struct ImmOptions {
  std::vector<MotionModel> models;
  // transition(i, j) = P(mode j now | mode i one step before); every row sums to 1. One step is
  // one Predict call: the matrix is per measurement cycle, not per second.
  Eigen::MatrixXd transition;
  Eigen::VectorXd initial_probabilities;  // sums to 1

  // Throws InputError naming `prefix`.field when a size, a probability or a model is wrong.
  void Validate(const std::string& source, const std::string& prefix) const;
};

// The paper's four models (CV, CA, left and right turn at +-turn_rate_rad_s), staying in a mode
// with probability `stay` and leaving to each other mode with (1 - stay) / 3.
ImmOptions FourModelImm(double cv_accel_psd, double ca_jerk_psd, double turn_rate_rad_s,
                        double turn_accel_psd, double stay);

struct ImmState {
  std::vector<Gaussian> modes;    // per model, in that model's own state space
  Eigen::VectorXd probabilities;  // mu_j (c_j after Predict, before Update)
  TimeNs time = 0;
};

// Every model starts from `prior`, given in the canonical components listed in `components`
// (e.g. {kX, kY, kVx, kVy}); a component the prior lacks starts at 0 with variance
// `unknown_variance` (accelerations, turn rate).
ImmState InitImm(const ImmOptions& options, const Gaussian& prior,
                 const std::vector<int>& components, double unknown_variance, TimeNs time);

// Moment-matched Gaussian of the mixture sum_i weights_i N(members_i), each member in the
// canonical components `member_components[i]`, expressed in `components`. Members lacking a
// component are filled as described above. Weights must be >= 0 and sum to 1.
Gaussian MomentMatch(const std::vector<std::vector<int>>& member_components,
                     const std::vector<Gaussian>& members, const Eigen::VectorXd& weights,
                     const std::vector<int>& components);

struct Mixing {
  Eigen::VectorXd predicted_probabilities;  // c_j
  Eigen::MatrixXd weights;                  // mu_i|j, column j sums to 1
  std::vector<Gaussian> mixed;              // the initial condition of each model
};
Mixing MixInto(const ImmOptions& options, const ImmState& state);  // steps 1-2

// Steps 1-3 over dt_s >= 0 (dt 0 still mixes: one call is one cycle of the Markov chain).
ImmState Predict(const ImmOptions& options, const ImmState& state, double dt_s);
// Predict to `time` >= state.time.
ImmState PredictTo(const ImmOptions& options, const ImmState& state, TimeNs time);

// The predicted position measurement for gating: per model and moment-matched over models.
struct ImmMeasurementPrediction {
  std::vector<MeasurementPrediction> per_mode;
  MeasurementPrediction combined;
};
ImmMeasurementPrediction PredictMeasurement(const ImmState& predicted, const Eigen::Matrix2d& R);

struct ImmUpdate {
  ImmState state;
  double log_likelihood = 0.0;  // log sum_j c_j L_j: the measurement's likelihood under the IMM
  Eigen::VectorXd mode_nis;     // per model
};
ImmUpdate Update(const ImmOptions& options, const ImmState& predicted, const Eigen::Vector2d& z,
                 const Eigen::Matrix2d& R);  // steps 4-5

// Step 6, in the canonical components `components` (by default position and velocity, which
// every model carries).
Gaussian Combine(const ImmOptions& options, const ImmState& state,
                 const std::vector<int>& components = {kX, kY, kVx, kVy});

}  // namespace lookout::tracking
