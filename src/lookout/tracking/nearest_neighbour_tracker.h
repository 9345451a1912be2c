#pragma once

// A single-target tracker around one ImmState: each scan, predict to the scan's time, gate the
// detections with the IMM's combined predicted measurement (chi-square gate on the Mahalanobis
// distance, 2 degrees of freedom), and update with the nearest detection inside the gate; with
// none, the track keeps the prediction.
//
// Nearest neighbour, not PDA: it is the data association the MHT will replace (the MHT keeps
// every gated hypothesis), and it keeps the evaluation a test of the filter rather than of the
// association weighting. Its known weakness: when the target is missed, a clutter detection in
// the gate is taken as the target.

#include <cstddef>

#include <Eigen/Core>

#include "lookout/core/time.h"
#include "lookout/tracking/imm.h"

namespace lookout::tracking {

struct TrackerOptions {
  ImmOptions imm;
  double measurement_std_m = 10.0;  // isotropic position noise of the detections
  double gate_probability = 0.99;   // of the chi-square gate (2 dof)

  void Validate(const std::string& source, const std::string& prefix) const;
  Eigen::Matrix2d R() const;
};

struct TrackStep {
  ImmState state;                 // after the update (or the prediction when nothing gated)
  bool associated = false;
  Eigen::Index detection = -1;    // column of the detection used
  double nis = 0.0;               // of the used detection against the combined prediction
  std::size_t skipped_non_finite = 0;  // detections with NaN or infinite coordinates
  bool skipped_out_of_order = false;   // the scan was older than the state: nothing changed
};

// One scan at `time`; `detections` is 2 x m, one detection a column. A scan older than the
// state (time going backwards) is skipped and flagged, the state returned unchanged: a tracker
// cannot un-predict, and the caller counts or refuses such input.
TrackStep TrackScan(const TrackerOptions& options, const ImmState& state, TimeNs time,
                    const Eigen::MatrixXd& detections);

}  // namespace lookout::tracking
