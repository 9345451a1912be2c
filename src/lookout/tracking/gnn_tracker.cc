#include "lookout/tracking/gnn_tracker.h"

#include <algorithm>
#include <cmath>

#include "lookout/assignment/linear_assignment.h"
#include "lookout/core/input_error.h"
#include "lookout/core/chi_square.h"
#include "lookout/tracking/motion_models.h"

namespace lookout::tracking {

void GnnOptions::Validate(const std::string& source) const {
  auto require = [&](bool ok, const char* field, const char* problem) {
    if (!ok) throw InputError(source, 0, field, problem);
  };
  require(std::isfinite(acceleration_psd) && acceleration_psd > 0.0, "acceleration_psd",
          "must be > 0");
  require(gate_probability > 0.0 && gate_probability < 1.0, "gate_probability",
          "must be in (0, 1)");
  require(std::isfinite(initial_speed_sigma_mps) && initial_speed_sigma_mps > 0.0,
          "initial_speed_sigma_mps", "must be > 0");
  TrackManagementOptions::Validate(source);
}

GnnTracker::GnnTracker(const GnnOptions& options) : options_(options) { options_.Validate(); }

bool GnnTracker::Step(TimeNs stamp, const std::vector<Detection>& all, const SensorView& view) {
  if (last_stamp_ && stamp <= *last_stamp_) {
    ++refused_;
    return false;
  }
  const std::vector<Detection> detections = UsableDetections(all);
  dropped_ += static_cast<std::int64_t>(all.size() - detections.size());
  const MotionModel cv = ConstantVelocity(options_.acceleration_psd);
  // Predict every track to this scan.
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    Track& t = tracks_[i];
    t.previous = TrackSnapshot{t.stamp, t.state};
    t.state = PredictState(cv, t.state, ToSeconds(stamp - t.stamp));
    t.stamp = stamp;
  }
  // Costs: the negative log-likelihood of each gated (track, detection) pair.
  const double gate = ChiSquareQuantile(options_.gate_probability, 2.0);
  Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(tracks_.size()),
                                                   static_cast<Eigen::Index>(detections.size()),
                                                   assignment::kForbidden);
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    for (std::size_t j = 0; j < detections.size(); ++j) {
      if (!ClassesCompatible(tracks_[i].object_class, detections[j].object_class)) continue;
      const ClassCentre z = MeasurementFor(detections[j], tracks_[i].object_class);
      const MeasurementPrediction p = PredictMeasurement(tracks_[i].state, z.covariance);
      const Eigen::Vector2d v = z.position_m - p.z;
      if (NormalisedSquare(v, p.S) > gate) continue;
      cost(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          -GaussianLogLikelihood(v, p.S);
    }
  }
  const assignment::Assignment a = assignment::SolveLinearAssignment(cost);
  std::vector<bool> used(detections.size(), false);
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    Track& t = tracks_[i];
    const int j = a.column_of_row[i];
    if (j == assignment::kUnassigned) {
      const ViewFraction seen = view.View(t.Position(), t.object_class);
      t = AfterMiss(options_, std::move(t), seen, stamp);
      continue;
    }
    const Detection& d = detections[static_cast<std::size_t>(j)];
    used[static_cast<std::size_t>(j)] = true;
    const ClassCentre z = MeasurementFor(d, t.object_class);
    t.state = UpdateState(t.state, z.position_m, z.covariance).posterior;
    t = AfterDetection(options_, std::move(t), d, stamp);
    if (t.updates == 3) {
      t.state = WithSeenVelocity(t.state, t.early_seen_points,
                                 options_.seen_velocity_agreement_probability);
    }
  }
  // Delete tracks missed too often (in order, so ids stay sorted).
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [&](const Track& t) { return Expired(options_, t); }),
                tracks_.end());
  // New tentative tracks from the detections no track took.
  for (std::size_t j = 0; j < detections.size(); ++j) {
    if (used[j]) continue;
    const Detection& d = detections[j];
    Track t = BornTrack(options_, d, stamp);
    t.id = next_id_++;
    t.state = BirthState(
        d, InitialSpeedSigma(options_, d.object_class, options_.initial_speed_sigma_mps));
    tracks_.push_back(t);
  }
  last_stamp_ = stamp;
  return true;
}

std::vector<Track> GnnTracker::ConfirmedTracks() const {
  std::vector<Track> out;
  for (const Track& t : tracks_) {
    if (t.status == TrackStatus::kConfirmed) out.push_back(t);
  }
  return out;
}

}  // namespace lookout::tracking
