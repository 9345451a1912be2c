#pragma once

// Localisation of the vehicle in its own local map (seed 004 IV.A): a particle filter whose
// particles are moved by a motion model (the car-like bicycle, or a differential drive for
// robot logs), pulled onto the map by scan matching, weighted by the laser likelihood field
// and resampled when their effective number falls; the scan is then added to the map at the
// estimated pose (incremental mapping). One map, built at the estimate, shared by all
// particles: a localiser with a memory, not a full SLAM with a map per particle, so loops are
// not closed (docs/lidar-slam.md).
//
// Per scan, with N particles and B matching points:
//   1. predict:  each particle samples the motion model on the odometry increment;
//   2. match:    one correlative search and Gauss-Newton fit around the odometry's prediction
//                of the last estimate; every particle is moved by the correction it found
//                (their spread is kept);
//   3. refine:   a few Gauss-Newton steps per particle on the likelihood field;
//   4. weigh:    w_i *= p(scan | pose_i, map)^(matcher.effective_beams / B);
//   5. resample: low-variance, when ESS < resample_ess_share N;
//   6. estimate: weighted mean and covariance of the particles;
//   7. map:      insert the scan at the estimate.
// Cost: the search is O(window poses x B) lookups once, steps 3-4 O(N x B x iterations).
//
// Deterministic: every random draw comes from an Rng seeded with DeriveSeed(seed, stream,
// scan index); nothing depends on threads.

#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "lookout/core/ego_state.h"
#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/lidar/local_map.h"
#include "lookout/lidar/slam_options.h"

namespace lookout::lidar {

struct Particle {
  Pose2 pose;
  double log_weight = 0.0;  // log of the normalised weight
};

// The weighted mean pose (circular mean of the headings) and the (x, y, yaw) covariance of
// particles whose log-weights are normalised.
struct ParticleEstimate {
  Pose2 mean;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};
ParticleEstimate EstimateFromParticles(std::span<const Particle> particles);

class LidarLocaliser final : public EgoPoseSource {
 public:
  // Validates the options (lookout::InputError).
  explicit LidarLocaliser(const SlamOptions& options = {});

  // Raw odometry (the odometry frame's pose of the vehicle) in time order, for PoseAt between
  // scans. Readings going back in time or not finite are refused and counted.
  bool AddOdometry(TimeNs t, const Pose2& odometry);

  // One scan with the raw odometry pose at its stamp: runs the filter and maps every return
  // of the scan (LocaliseScan, then MapScan with all returns). The first scan fixes the map
  // frame at its odometry pose. Refused (nullopt, counted) when its stamp is earlier than the
  // previous scan's or its odometry is not finite.
  std::optional<EgoState> AddScan(const LidarScan& scan, const Pose2& odometry);

  // The two halves of AddScan, for a caller that decides what to map from the scan localised
  // against the map as it was (the lidar chain classifies the hits in between and maps only
  // the static ones). LocaliseScan runs steps 1-6 and records the estimate; MapScan inserts
  // returns (vehicle frame) at the estimate of the last LocaliseScan: `hits` end in occupied
  // cells, `free_ends` only clear space, `empty_ends` (beams that saw nothing) clear it up to
  // the first occupied cell, `bare_hits` mark their cells only (LocalMap::InsertScan). A
  // MapScan without an accepted LocaliseScan before it does nothing.
  std::optional<EgoState> LocaliseScan(const LidarScan& scan, const Pose2& odometry);
  void MapScan(const LidarScan& scan, std::span<const Eigen::Vector2d> hits,
               std::span<const Eigen::Vector2d> free_ends,
               std::span<const Eigen::Vector2d> empty_ends = {},
               std::span<const Eigen::Vector2d> bare_hits = {});

  // The latest scan estimate at or before t composed with the odometry since (interpolated
  // between readings; held for up to max_extrapolation_s past the newest). The covariance is
  // the scan estimate's. nullopt before the first scan or outside the kept history.
  std::optional<EgoState> PoseAt(TimeNs t) const override;

  const LocalMap& map() const { return map_; }
  std::span<const Particle> particles() const { return particles_; }
  std::int64_t scans_processed() const { return scan_index_; }
  std::int64_t resample_count() const { return resamples_; }
  std::int64_t rejected_count() const { return rejected_; }

 private:
  struct ScanState {
    EgoState state;
    Pose2 odometry;
  };
  struct OdometryReading {
    TimeNs t;
    Pose2 pose;
  };
  std::optional<Pose2> OdometryAt(TimeNs t) const;
  void Predict(const Pose2& increment);
  void Correct(std::span<const Eigen::Vector2d> points, const Pose2& increment,
               const Pose2& predicted);
  void DropOldHistory(TimeNs newest);

  SlamOptions options_;
  LocalMap map_;
  std::vector<Particle> particles_;
  std::deque<ScanState> scans_;
  std::deque<OdometryReading> odometry_;
  std::int64_t scan_index_ = 0;
  std::int64_t resamples_ = 0;
  std::int64_t rejected_ = 0;
};

}  // namespace lookout::lidar
