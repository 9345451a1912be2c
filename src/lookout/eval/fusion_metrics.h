#pragma once

// The fusion.* metric keys of cli-contract.md: the fused objects' positions against the
// truth, beside the lidar's and the camera's alone, and the consistency of the fused
// covariances (NEES).
//
// What is compared: each object's point is the middle of its footprint's side facing the
// lidar origin (seed 004: what both sensors' points are, stereo/oriented_box.h), so the truth
// compared with it is the same point of the true footprint, not its centre. Against the centre
// every estimate would carry a bias of half the object's depth (up to 2.25 m for a car seen
// end on, 0.9 m side on) that measures the choice of point, not the sensors.
//
// Matching, per frame: the fused objects that both sensors saw are matched one-to-one to the
// true actors by least total squared distance from the fused point to the true point, within
// match_radius_m (an optimal assignment, assignment/linear_assignment.h). The lidar-only and
// stereo-only errors are those of the two source objects of each matched fused object, against
// the same actor: all three RMSEs are over the same set of objects.
//
// NEES: e^T P^-1 e of the fused point (P its covariance) over the N matched objects; for a
// consistent, unbiased estimator its mean is chi-square with 2N degrees of freedom over N, and
// the band holds it with nees_band_probability when the errors are independent (consecutive
// frames are not quite: read the band as a guide, not a test at the stated level).

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/fusion/fused_object.h"
#include "lookout/sim/truth.h"
#include "lookout/stereo/oriented_box.h"
#include "lookout/stereo/stereo_point.h"

namespace lookout::eval {

// A true actor's footprint in the vehicle frame of the frame being scored.
struct TrueObject {
  int actor_index = 0;
  stereo::OrientedBox footprint;
};

// The actors of `frame` in the true vehicle frame at its stamp. A pedestrian (a circle of
// radius r) becomes the 2r square along its heading, as the simulated camera reports it.
std::vector<TrueObject> TrueObjectsInVehicleFrame(const sim::TruthFrame& frame);

// Each object's point: the middle of its footprint's side facing `viewpoint_m` (the lidar's
// origin), as both sensors define it; +infinity for an actor around the viewpoint (no side
// faces it: it cannot be scored).
std::vector<Eigen::Vector2d> TrueFrontPoints(std::span<const TrueObject> truth,
                                             const Eigen::Vector2d& viewpoint_m);

// One-to-one matching of `points` to `true_points` by least total squared distance, pairs
// further apart than radius_m forbidden (an optimal assignment): for each point the index of
// its true point, or -1.
std::vector<int> MatchToTruth(std::span<const Eigen::Vector2d> points,
                              std::span<const Eigen::Vector2d> true_points, double radius_m);

struct FusionMetricOptions {
  double match_radius_m = 2.0;  // the tracking metrics' matching distance (cli-contract.md)
  double nees_band_probability = 0.95;
  // Throws std::invalid_argument naming the first field out of range.
  void Validate() const;
};

struct NeesBand {
  double low = 0.0;
  double high = 0.0;
};

class FusionMetricsAccumulator {
 public:
  explicit FusionMetricsAccumulator(FusionMetricOptions options = {});

  // One lidar frame: the fused objects, the lidar objects and the stereo objects they came
  // from (the latter at the lidar stamp, FusionEngine::stereo_at_lidar_time), and the truth,
  // all in the vehicle frame at fused.stamp.
  void AddFrame(const fusion::FusedObjectFrame& fused, const LidarObjectFrame& lidar,
                std::span<const stereo::StereoPoint> stereo, std::span<const TrueObject> truth);

  std::int64_t matched() const { return count_; }
  // nullopt before anything was matched.
  std::optional<double> PositionRmse() const;
  std::optional<double> LidarOnlyRmse() const;
  std::optional<double> StereoOnlyRmse() const;
  std::optional<double> MeanNees() const;
  std::optional<NeesBand> MeanNeesBand() const;

  // fusion.position_rmse_m, fusion.lidar_only_rmse_m, fusion.stereo_only_rmse_m,
  // fusion.nees_mean, fusion.nees_band_low, fusion.nees_band_high, fusion.matched_objects;
  // and, for the diagnosis of the fused NEES, fusion.lidar_nees_mean and
  // fusion.stereo_nees_mean: each source's own NEES on the same objects (the same band holds
  // for each when its covariance is honest). Only the keys that have a value.
  std::map<std::string, double> Values() const;

 private:
  FusionMetricOptions options_;
  std::int64_t count_ = 0;
  double fused_squared_ = 0.0;
  double lidar_squared_ = 0.0;
  double stereo_squared_ = 0.0;
  double nees_sum_ = 0.0;
  double lidar_nees_sum_ = 0.0;
  double stereo_nees_sum_ = 0.0;
};

}  // namespace lookout::eval
