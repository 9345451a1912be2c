#include "lookout/lidar/localiser.h"

#include <algorithm>
#include <cmath>

#include "lookout/core/random.h"
#include "lookout/lidar/motion_model.h"
#include "lookout/lidar/resampling.h"
#include "lookout/lidar/scan_matcher.h"

namespace lookout::lidar {
namespace {

bool Finite(const Pose2& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.yaw);
}

Pose2 Interpolate(const Pose2& a, const Pose2& b, double s) {
  return Pose2(a.translation + s * (b.translation - a.translation),
               WrapAngle(a.yaw + s * WrapAngle(b.yaw - a.yaw)));
}

}  // namespace

ParticleEstimate EstimateFromParticles(std::span<const Particle> particles) {
  ParticleEstimate e;
  if (particles.empty()) return e;
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  double s = 0.0;
  double c = 0.0;
  double total = 0.0;
  for (const Particle& p : particles) {
    const double w = std::exp(p.log_weight);
    t += w * p.pose.translation;
    s += w * std::sin(p.pose.yaw);
    c += w * std::cos(p.pose.yaw);
    total += w;
  }
  e.mean = Pose2(t / total, std::atan2(s, c));
  for (const Particle& p : particles) {
    const double w = std::exp(p.log_weight) / total;
    const Eigen::Vector3d d(p.pose.x() - e.mean.x(), p.pose.y() - e.mean.y(),
                            WrapAngle(p.pose.yaw - e.mean.yaw));
    e.covariance += w * d * d.transpose();
  }
  return e;
}

LidarLocaliser::LidarLocaliser(const SlamOptions& options)
    : options_(options), map_((options.Validate(), options.map)) {}

bool LidarLocaliser::AddOdometry(TimeNs t, const Pose2& odometry) {
  if (!Finite(odometry) || (!odometry_.empty() && t < odometry_.back().t)) {
    ++rejected_;
    return false;
  }
  if (!odometry_.empty() && odometry_.back().t == t) {
    odometry_.back().pose = odometry;
  } else {
    odometry_.push_back({t, odometry});
  }
  DropOldHistory(t);
  return true;
}

void LidarLocaliser::DropOldHistory(TimeNs newest) {
  const TimeNs keep = FromSeconds(options_.history_s);
  // Keep one reading (and one scan) at or before the window's start so that it stays covered.
  while (odometry_.size() > 1 && odometry_[1].t <= newest - keep) odometry_.pop_front();
  while (scans_.size() > 1 && scans_[1].state.stamp <= newest - keep) scans_.pop_front();
}

std::optional<Pose2> LidarLocaliser::OdometryAt(TimeNs t) const {
  if (odometry_.empty() || t < odometry_.front().t) return std::nullopt;
  if (t >= odometry_.back().t) {
    if (t - odometry_.back().t > FromSeconds(options_.max_extrapolation_s)) return std::nullopt;
    return odometry_.back().pose;
  }
  const auto after = std::upper_bound(
      odometry_.begin(), odometry_.end(), t,
      [](TimeNs value, const OdometryReading& r) { return value < r.t; });
  const auto before = std::prev(after);
  const double s = static_cast<double>(t - before->t) / static_cast<double>(after->t - before->t);
  return Interpolate(before->pose, after->pose, s);
}

std::optional<EgoState> LidarLocaliser::PoseAt(TimeNs t) const {
  const auto after = std::upper_bound(
      scans_.begin(), scans_.end(), t,
      [](TimeNs value, const ScanState& s) { return value < s.state.stamp; });
  if (after == scans_.begin()) return std::nullopt;
  const ScanState& scan = *std::prev(after);
  if (t == scan.state.stamp) return scan.state;
  const std::optional<Pose2> odometry = OdometryAt(t);
  if (!odometry) return std::nullopt;
  EgoState state = scan.state;
  state.stamp = t;
  state.pose = scan.state.pose * (scan.odometry.Inverse() * *odometry);
  state.pose.yaw = WrapAngle(state.pose.yaw);
  return state;
}

void LidarLocaliser::Predict(const Pose2& increment) {
  Rng rng(DeriveSeed(options_.filter.seed, "lidar.motion",
                     static_cast<std::uint64_t>(scan_index_)));
  for (Particle& p : particles_) p.pose = SampleMotion(p.pose, increment, options_.motion, rng);
}

void LidarLocaliser::Correct(std::span<const Eigen::Vector2d> points, const Pose2& increment,
                             const Pose2& predicted) {
  const MatcherOptions& m = options_.matcher;
  // Search once around the odometry's prediction of the last estimate; every particle takes
  // the same correction, keeping the spread the motion model gave them. The prediction, not the
  // particles' mean: that mean is a Monte Carlo draw of it, off by the motion noise over the
  // square root of the particle count (4 cm and 1.5 deg a metre with 30 particles on the robot
  // logs), and along a corridor's axis, where the scan does not decide, the prior's centre is
  // the answer, so the draw's noise went straight into the estimate and made it seed-dependent.
  const SearchWindow window = SearchWindowFor(increment, m);
  const Pose2 matched = MatchScan(map_, points, predicted, window, m).pose;
  const Pose2 correction = matched * predicted.Inverse();
  const double scale = m.effective_beams / static_cast<double>(points.size());
  std::vector<double> log_weights(particles_.size());
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    Particle& p = particles_[i];
    const PosePrior prior = PriorFromWindow(p.pose, window);
    p.pose = correction * p.pose;
    p.pose = RefineGaussNewton(map_, points, p.pose, options_.filter.particle_refine_iterations,
                               m, options_.filter.refine_with_prior ? &prior : nullptr)
                 .pose;
    log_weights[i] = p.log_weight + scale * ScanLogLikelihood(map_, p.pose, points, m) +
                     options_.filter.weight_prior_share * PriorLogDensity(prior, p.pose);
  }
  std::vector<double> w = NormaliseLogWeights(log_weights);
  const double n = static_cast<double>(particles_.size());
  if (EffectiveSampleSize(w) < options_.filter.resample_ess_share * n) {
    Rng rng(DeriveSeed(options_.filter.seed, "lidar.resample",
                       static_cast<std::uint64_t>(scan_index_)));
    const std::vector<std::size_t> kept = LowVarianceResample(w, rng.Uniform());
    std::vector<Particle> next;
    next.reserve(kept.size());
    for (std::size_t k : kept) next.push_back({particles_[k].pose, -std::log(n)});
    particles_ = std::move(next);
    ++resamples_;
  } else {
    for (std::size_t i = 0; i < particles_.size(); ++i) {
      particles_[i].log_weight = w[i] > 0.0 ? std::log(w[i]) : -1e300;
    }
  }
}

void LidarLocaliser::MapScan(const LidarScan& scan, std::span<const Eigen::Vector2d> hits,
                             std::span<const Eigen::Vector2d> free_ends,
                             std::span<const Eigen::Vector2d> empty_ends,
                             std::span<const Eigen::Vector2d> bare_hits) {
  if (scans_.empty() || scans_.back().state.stamp != scan.stamp) return;
  const Pose2& pose = scans_.back().state.pose;
  map_.RecentreOn(pose.translation);
  const auto to_map = [&pose](std::span<const Eigen::Vector2d> points) {
    std::vector<Eigen::Vector2d> out;
    out.reserve(points.size());
    for (const Eigen::Vector2d& p : points) out.push_back(pose * p);
    return out;
  };
  map_.InsertScan(pose * scan.mount.translation, to_map(hits), to_map(free_ends),
                  to_map(empty_ends), to_map(bare_hits));
}

std::optional<EgoState> LidarLocaliser::AddScan(const LidarScan& scan, const Pose2& odometry) {
  const std::optional<EgoState> state = LocaliseScan(scan, odometry);
  if (state) MapScan(scan, ExtractScanPoints(scan, options_.matcher).all, {});
  return state;
}

std::optional<EgoState> LidarLocaliser::LocaliseScan(const LidarScan& scan,
                                                     const Pose2& odometry) {
  if (!Finite(odometry) || (!scans_.empty() && scan.stamp < scans_.back().state.stamp)) {
    ++rejected_;
    return std::nullopt;
  }
  AddOdometry(scan.stamp, odometry);
  const ScanPoints points = ExtractScanPoints(scan, options_.matcher);

  EgoState state;
  state.stamp = scan.stamp;
  if (scans_.empty()) {
    // The first scan fixes the map frame: the odometry frame, at the odometry's pose.
    const double n = static_cast<double>(options_.filter.particle_count);
    particles_.assign(static_cast<std::size_t>(options_.filter.particle_count),
                      Particle{odometry, -std::log(n)});
    state.pose = odometry;
  } else {
    const ScanState& previous = scans_.back();
    const Pose2 increment = previous.odometry.Inverse() * odometry;
    Predict(increment);
    if (map_.HasOccupied() && points.match.size() >= 3) {
      Correct(points.match, increment, previous.state.pose * increment);
    }
    const ParticleEstimate estimate = EstimateFromParticles(particles_);
    state.pose = estimate.mean;
    state.covariance = estimate.covariance;
    const double dt = ToSeconds(scan.stamp - previous.state.stamp);
    if (dt > 0.0) {
      const Pose2 moved = previous.state.pose.Inverse() * state.pose;
      state.speed_mps = moved.x() / dt;
      state.yaw_rate_radps = WrapAngle(moved.yaw) / dt;
    }
  }
  scans_.push_back({state, odometry});
  DropOldHistory(scan.stamp);
  ++scan_index_;
  return state;
}

}  // namespace lookout::lidar
