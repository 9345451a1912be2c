#pragma once

// Options of the lidar chain's localisation and local mapping (seed 004 section IV.A), one
// plain struct per part and one for the whole. Units are in the names; Validate() names the
// first field out of range. docs/lidar-slam.md explains the defaults.

#include <cstdint>
#include <string>

namespace lookout::lidar {

// The local occupancy map (local_map.h).
struct MapOptions {
  double cell_size_m = 0.05;
  // Side of the square moving window, in cells; a power of two (the circular buffer wraps
  // indices with a mask). 4096 x 0.05 m = 204.8 m: a whole building of the CARMEN logs fits.
  int window_cells = 4096;
  // The window recentres on the vehicle when it is further than this share of the window's
  // side from the window's centre (so at least (0.5 - share) of the side is always mapped
  // ahead of the vehicle). What leaves the window is forgotten.
  double recentre_share = 0.25;
  // Clamped log-odds (Thrun, Burgard, Fox, Probabilistic Robotics, ch. 9): the clamp keeps a
  // cell able to change its mind after many agreeing observations.
  float log_odds_hit = 0.9f;
  float log_odds_miss = -0.3f;
  float log_odds_min = -2.0f;
  float log_odds_max = 3.5f;
  // A cell whose log-odds exceed this counts as occupied for the likelihood field.
  float occupied_log_odds = 0.5f;
  // The likelihood field stores the distance to the nearest occupied cell up to this value.
  double field_max_distance_m = 0.6;
  // Beams are inserted up to this range (a hit further away only clears space up to it).
  double max_insert_range_m = 40.0;
  // ... and from this range on: nearer, a ray updates nothing (a hit there is left out). For a
  // map that only the far returns read (the lidar chain's far map), whose near part another
  // map holds.
  double min_insert_range_m = 0.0;

  void Validate(const std::string& source = "lidar map options") const;
};

enum class MotionModelKind { kBicycle, kDifferentialDrive };

// Noise of the motion models (motion_model.h). The odometry increment between two scans is
// perturbed in the model's own parameters before it is applied to a particle.
struct MotionModelOptions {
  MotionModelKind kind = MotionModelKind::kDifferentialDrive;
  // Differential drive (Probabilistic Robotics table 5.6): variances a1 rot^2 + a2 trans^2 for
  // the rotations, a3 trans^2 + a4 (rot1^2 + rot2^2) for the translation.
  double alpha1 = 0.05;  // rad^2 / rad^2
  double alpha2 = 0.01;  // rad^2 / m^2
  double alpha3 = 0.05;  // m^2 / m^2
  double alpha4 = 0.01;  // m^2 / rad^2
  // Bicycle (car-like): the increment is an arc of signed length s driven at steering angle
  // delta = atan(wheelbase * curvature); s gets relative noise, delta absolute noise.
  double wheelbase_m = 2.7;
  double max_steering_rad = 0.6;
  double arc_length_noise = 0.1;        // 1-sigma of s, relative to |s|
  double steering_noise_rad = 0.02;     // 1-sigma of delta

  void Validate(const std::string& source = "lidar motion options") const;
};

// The scan matcher (scan_matcher.h).
struct MatcherOptions {
  // Beam endpoints used for matching and weighting: consecutive kept points are at least this
  // far apart (subsampling that keeps the scan's shape, not every n-th beam).
  double point_spacing_m = 0.2;
  int max_points = 160;
  double min_range_m = 0.1;
  // Likelihood field: a point at distance d from the nearest occupied cell has likelihood
  // z_hit exp(-d^2 / (2 sigma^2)) + z_rand (Probabilistic Robotics 6.4).
  double sigma_m = 0.1;
  double z_rand = 0.05;
  // The beams of a scan are not independent (the map is shared, errors correlate): a scan's
  // summed log-likelihood counts as this many independent beams, against the odometry prior
  // in the matcher and between particles in the filter.
  double effective_beams = 8.0;
  // Correlative search: a coarse grid of poses scored with a wider kernel, then a fine grid
  // around the best, then Gauss-Newton. The window grows with the odometry increment; it is
  // also the odometry prior (window = 2 sigma), which decides where the scan alone cannot (a
  // corridor's axis).
  double search_xy_base_m = 0.15;
  double search_xy_per_m = 0.25;       // extra half-width per metre travelled
  double search_yaw_base_rad = 0.06;
  double search_yaw_per_rad = 0.25;    // extra half-width per radian turned
  double search_yaw_per_m = 0.05;      // extra half-width per metre travelled
  double max_search_xy_m = 0.8;
  double max_search_yaw_rad = 0.4;
  // When the coarse search's best heading lies on the edge of its window, the true heading may
  // lie beyond it (an odometry heading error larger than the window expects: csail's scan 292,
  // 0.18 rad against a 0.17 rad window). The heading window is then extended band by band (each
  // band as wide as the window) while the best stays on the edge, up to this many times the
  // window; the prior stays the window's. 1 turns it off. The extra bands cost only where the
  // edge is hit.
  double search_yaw_edge_extend = 1.0;
  // The coarse grid steps whole cells (lookups need no rounding); the fine grid steps one cell
  // and fine_step_rad over +-1 coarse step around the coarse best; Gauss-Newton goes below.
  int coarse_step_cells = 2;
  double coarse_step_rad = 0.01;
  double coarse_sigma_m = 0.2;
  double fine_step_rad = 0.0025;
  int gauss_newton_iterations = 6;

  void Validate(const std::string& source = "lidar matcher options") const;
};

struct ParticleFilterOptions {
  int particle_count = 30;
  // Resample when the effective sample size falls below this share of the particle count.
  double resample_ess_share = 0.5;
  // Gauss-Newton iterations refining each particle after the correlative search.
  int particle_refine_iterations = 8;
  // With it, each particle's refinement carries the odometry prior centred on the particle's
  // own motion sample (sigma: half the search window), so each particle moves to its own
  // posterior mode: the scan decides the directions it constrains, the odometry the others
  // (a corridor's axis, an open road). Without it the refinement has no prior and the
  // correlative search's pick along such an axis stays.
  bool refine_with_prior = false;
  // Share of the odometry prior (centred on the particle's motion sample, sigma half the
  // search window) in each particle's weight after its refinement. The refinement moves a
  // particle to the scan's nearest optimum without a prior; with it, a particle that a fit
  // slid far from its motion sample (along a corridor, to another optimum) must earn that
  // distance in the scan's likelihood. 0 weighs by the scan alone.
  double weight_prior_share = 0.0;
  std::uint64_t seed = 4;

  void Validate(const std::string& source = "lidar particle filter options") const;
};

struct SlamOptions {
  MapOptions map;
  MotionModelOptions motion;
  MatcherOptions matcher;
  ParticleFilterOptions filter;
  // PoseAt() keeps this much history and refuses to extrapolate further than
  // max_extrapolation_s past the newest odometry.
  double history_s = 2.0;
  double max_extrapolation_s = 0.5;

  void Validate(const std::string& source = "lidar slam options") const;
};

}  // namespace lookout::lidar
