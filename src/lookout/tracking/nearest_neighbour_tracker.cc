#include "lookout/tracking/nearest_neighbour_tracker.h"

#include <cmath>
#include <limits>

#include "lookout/core/input_error.h"
#include "lookout/core/chi_square.h"

namespace lookout::tracking {

void TrackerOptions::Validate(const std::string& source, const std::string& prefix) const {
  imm.Validate(source, prefix + ".imm");
  if (!(std::isfinite(measurement_std_m) && measurement_std_m > 0.0)) {
    throw InputError(source, 0, prefix + ".measurement_std_m", "must be finite and > 0");
  }
  if (!(gate_probability > 0.0 && gate_probability < 1.0)) {
    throw InputError(source, 0, prefix + ".gate_probability", "must be in (0, 1)");
  }
}

Eigen::Matrix2d TrackerOptions::R() const {
  return Eigen::Matrix2d::Identity() * measurement_std_m * measurement_std_m;
}

TrackStep TrackScan(const TrackerOptions& options, const ImmState& state, TimeNs time,
                    const Eigen::MatrixXd& detections) {
  if (time < state.time) {
    TrackStep skipped;
    skipped.state = state;
    skipped.skipped_out_of_order = true;
    return skipped;
  }
  const Eigen::Matrix2d R = options.R();
  const ImmState predicted = PredictTo(options.imm, state, time);
  const MeasurementPrediction gate = PredictMeasurement(predicted, R).combined;
  const double threshold = ChiSquareQuantile(options.gate_probability, 2.0);
  TrackStep step;
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < detections.cols(); ++i) {
    if (!detections.col(i).allFinite()) {
      ++step.skipped_non_finite;
      continue;
    }
    const double d2 = NormalisedSquare(detections.col(i) - gate.z, gate.S);
    if (d2 <= threshold && d2 < best) {  // strict: the first of equal distances wins
      best = d2;
      step.detection = i;
    }
  }
  if (step.detection < 0) {
    step.state = predicted;
    return step;
  }
  step.associated = true;
  step.nis = best;
  step.state = Update(options.imm, predicted, detections.col(step.detection), R).state;
  return step;
}

}  // namespace lookout::tracking
