#pragma once

// Indicators beyond the paper's TTC (issue: risk quantification):
//   - the collision probability, by sampling the object's initial position and velocity from
//     its track covariance (seeded Monte Carlo): the share of samples whose footprint meets the
//     ego's inside the horizon. Each sample moves by the nominal prediction plus its offsets,
//     dp + dv t, its footprint turned as the nominal one: exact for straight motion, first
//     order for a predicted turn;
//   - the post-encroachment time (PET): the smallest time gap between the ego and the object
//     occupying the same place (their footprints overlapping at steps i and j: |t_i - t_j|). 0
//     is a collision; a few tenths of a second, a near miss.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "lookout/risk/footprint.h"

namespace lookout::risk {

struct SamplingInput {
  Eigen::Matrix2d position_covariance = Eigen::Matrix2d::Zero();  // m^2, PSD
  Eigen::Matrix2d velocity_covariance = Eigen::Matrix2d::Zero();  // (m/s)^2, PSD
};

// Standard normal draws, four per sample (position x, y, velocity x, y), from `seed`. One set
// serves every object of a risk step (common random numbers): each object's probability is
// still an unbiased estimate, and drawing once instead of per object is what makes 1000
// samples for 30 tracks fit in a millisecond.
std::vector<Eigen::Vector4d> DrawStandardNormals(int samples, std::uint64_t seed);

// `object`: the nominal prediction, footprints without the covariance margin. The share of the
// samples (`normals`, mapped through the covariances' square roots) whose footprint meets the
// ego's. Pure.
double CollisionProbability(const FootprintTrack& ego, const FootprintTrack& object, double dt_s,
                            const SamplingInput& sampling,
                            const std::vector<Eigen::Vector4d>& normals);

// nullopt when the two never occupy the same place within the horizon. Pure.
std::optional<double> PostEncroachmentTime(const FootprintTrack& ego,
                                           const FootprintTrack& object, double dt_s);

}  // namespace lookout::risk
