#pragma once

// The tracking baseline of the tracking issue: global nearest neighbour (one optimal
// assignment per scan) with a single constant-velocity Kalman filter per track, and the track
// management the MHT shares: tentative tracks from unassociated detections, confirmed after one
// update when both sensors saw the object and after three otherwise, coasting (prediction only)
// through misses, deleted after a number of consecutive misses that depends on the class.
//
// Gating: a detection may join a track only inside the chi-square gate of the innovation (2 dof)
// and when their classes are compatible (no pedestrian joins a car's track; unknown joins
// anything). Deterministic: ties and orders follow the input order and track ids.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lookout/core/object_class.h"
#include "lookout/core/time.h"
#include "lookout/tracking/kalman.h"
#include "lookout/tracking/track_management.h"
#include "lookout/tracking/tracker.h"

namespace lookout::tracking {

// The track management fields (confirmation, misses per class) are inherited, so that they keep
// the names they had before the MHT came to share them.
struct GnnOptions : TrackManagementOptions {
  double acceleration_psd = 2.0;        // CV process noise, m^2/s^3
  double gate_probability = 0.999;      // chi-square gate, 2 dof
  double initial_speed_sigma_mps = 5.0; // velocity prior of a new track but a walker's

  // Throws lookout::InputError naming the first field out of range.
  void Validate(const std::string& source = "tracker options") const;
};

class GnnTracker final : public Tracker {
 public:
  explicit GnnTracker(const GnnOptions& options = {});

  // One scan at `stamp`. A stamp not after the previous scan's is refused: nothing changes and
  // the call returns false (the caller logs it). Detections with a non-finite field or a
  // covariance that is not symmetric positive definite are dropped and counted.
  using Tracker::Step;
  bool Step(TimeNs stamp, const std::vector<Detection>& detections,
            const SensorView& view) override;

  // Every track, tentative ones included.
  const std::vector<Track>& tracks() const { return tracks_; }
  std::vector<Track> ConfirmedTracks() const override;
  std::int64_t dropped_detections() const override { return dropped_; }
  std::int64_t refused_scans() const override { return refused_; }

 private:
  GnnOptions options_;
  std::vector<Track> tracks_;
  std::uint32_t next_id_ = 1;
  std::optional<TimeNs> last_stamp_;
  std::int64_t dropped_ = 0;
  std::int64_t refused_ = 0;
};

}  // namespace lookout::tracking
