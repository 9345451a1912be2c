#pragma once

// Scan matching against the local map's likelihood field: the laser likelihood that weighs
// the particles, a correlative search over a window of poses (Olson, "Real-time correlative
// scan matching", ICRA 2009: score every pose of a grid, coarse then fine), and a local
// optimisation by Gauss-Newton on the interpolated distance field (as Hector SLAM does on its
// occupancy map). Pure functions of the map, the points and the options.

#include <Eigen/Core>
#include <span>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/core/pose2.h"
#include "lookout/lidar/local_map.h"
#include "lookout/lidar/slam_options.h"

namespace lookout::lidar {

// The returns of a scan in the vehicle frame: every valid return (for mapping), and the
// subsample used for matching and weighting. Beams that are NaN, shorter than min_range_m,
// infinite or at the scanner's maximum range (no return) are left out.
struct ScanPoints {
  std::vector<Eigen::Vector2d> all;
  std::vector<Eigen::Vector2d> match;
};
ScanPoints ExtractScanPoints(const LidarScan& scan, const MatcherOptions& options);

// log(z_hit exp(-d^2 / (2 sigma^2)) + z_rand), z_hit = 1 - z_rand: the likelihood-field beam
// model (Probabilistic Robotics 6.4) at distance d from the nearest obstacle.
double PointLogLikelihood(double distance_m, const MatcherOptions& options);

// The sum of PointLogLikelihood over `points` (vehicle frame) placed at `pose`, nearest cell.
double ScanLogLikelihood(const LocalMap& map, const Pose2& pose,
                         std::span<const Eigen::Vector2d> points, const MatcherOptions& options);

// Half-widths of the correlative search for an odometry increment: uncertainty grows with the
// distance travelled and the angle turned. The same numbers are 2 sigma of the odometry prior.
struct SearchWindow {
  double xy_m = 0.0;
  double yaw_rad = 0.0;
};

// A Gaussian prior on the pose (the odometry's prediction): independent x, y and yaw.
struct PosePrior {
  Pose2 mean;
  double sigma_xy_m = 1.0;
  double sigma_yaw_rad = 1.0;
};
PosePrior PriorFromWindow(const Pose2& mean, const SearchWindow& window);
// The log of the prior's density at `pose`, up to its constant: -0.5 (Mahalanobis distance)^2.
double PriorLogDensity(const PosePrior& prior, const Pose2& pose);
SearchWindow SearchWindowFor(const Pose2& increment, const MatcherOptions& options);

// The best pose of the coarse and then the fine grid around `initial`, by the points' summed
// log-likelihood (nearest cell; the coarse grid with the wider coarse_sigma_m), scaled to
// effective_beams, plus the log of the prior centred on `initial`. Without the prior a
// corridor's axis is a ridge of equal scores and the pick along it is noise. Ties keep the
// first pose in a fixed order (the centre first).
Pose2 CorrelativeSearch(const LocalMap& map, std::span<const Eigen::Vector2d> points,
                        const Pose2& initial, const SearchWindow& window,
                        const MatcherOptions& options);

struct Refinement {
  Pose2 pose;
  // sigma^2 H^-1 of the last iteration: (x, y, yaw) covariance of the fit, m^2 and rad^2.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  int iterations = 0;
};
// Gauss-Newton on sum_i rho(d(T p_i)) (d the interpolated field, rho the Cauchy loss that
// bounds the pull of points far from any mapped obstacle) plus, with a prior, its negative log
// in the same units (weight sigma^2 B / effective_beams), at most `iterations` steps, stopping
// when a step would raise the cost.
Refinement RefineGaussNewton(const LocalMap& map, std::span<const Eigen::Vector2d> points,
                             const Pose2& initial, int iterations, const MatcherOptions& options,
                             const PosePrior* prior = nullptr);

// CorrelativeSearch then RefineGaussNewton with options.gauss_newton_iterations, both with the
// prior PriorFromWindow(initial, window).
Refinement MatchScan(const LocalMap& map, std::span<const Eigen::Vector2d> points,
                     const Pose2& initial, const SearchWindow& window,
                     const MatcherOptions& options);

}  // namespace lookout::lidar
