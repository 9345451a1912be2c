#pragma once

// Seed 004 VI.B, Bayesian fusion of two position measurements of one object, in matrix form.
// The paper writes, for laser P_L, R_L and vision P_V, R_V:
//     1/R = 1/R_L + 1/R_V,      P = (P_L/R_L + P_V/R_V) / (1/R_L + 1/R_V)
// which for matrices is the information-weighted mean:
//     R = (R_L^-1 + R_V^-1)^-1,  P = R (R_L^-1 P_L + R_V^-1 P_V)
// the product of the two Gaussian likelihoods, renormalised. Both errors are taken as
// independent (two sensors, separate processing).

#include <Eigen/Core>

namespace lookout::fusion {

struct Gaussian2 {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
};

// Both covariances must be symmetric positive definite.
Gaussian2 FuseGaussians(const Gaussian2& a, const Gaussian2& b);

// The same two measurements when their errors are correlated, E[e_a e_b^T] = `cross` (two
// estimates sharing an input: the lidar's side point turned by the camera's heading,
// shared_heading.h): the linear unbiased estimate of least covariance (Bar-Shalom and Campo,
// 1986, "The effect of the common process noise on the two-sensor fused-track covariance"),
//     S = A + B - C - C^T,  K = (A - C) S^-1,  mean = a + K (b - a),  P = A - K (A - C)^T
// which for C = 0 is FuseGaussians. Where b repeats a's error whole (B = C = A), P = A: a
// shared error is not averaged away. The joint covariance [[A, C], [C^T, B]] must be positive
// semidefinite and S positive definite.
Gaussian2 FuseCorrelated(const Gaussian2& a, const Gaussian2& b, const Eigen::Matrix2d& cross);

// How much two measurements of one point disagree beyond what their covariances allow: their
// difference's d^2 under a.covariance + b.covariance (2 dof, chi-square when the pair is right
// and both covariances are) against `quantile`, the chi-square quantile of a probability.
// max(1, d^2 / quantile): 1 for all but the rarest consistent pairs; beyond, the factor by which
// both covariances must grow for the difference to sit on the quantile. Scaling both by it
// leaves FuseGaussians' mean where it was and scales the fused covariance by it: the
// disagreement itself is the evidence that one of the two (a pair on a neighbour's segment,
// a point on another side of the body) is off by more than it says. Both covariances positive
// definite, quantile > 0.
// `cross`: the two errors' cross-covariance E[e_a e_b^T], where they share one (the difference's
// covariance is then A + B - C - C^T).
double DisagreementScale(const Gaussian2& a, const Gaussian2& b, double quantile,
                         const Eigen::Matrix2d& cross = Eigen::Matrix2d::Zero());

// The second moment about `about` of a Gaussian: its covariance and its mean's offset.
Eigen::Matrix2d SpreadAbout(const Eigen::Vector2d& about, const Gaussian2& g);

// Two estimates of one point that disagree beyond `quantile` (d^2 as DisagreementScale takes
// it): the covariance about `kept.mean` of two hypotheses, kept right with weight
// w = quantile / d^2, or other right with 1 - w, the share of d^2 their covariances do not
// explain:
//     w kept.covariance + (1 - w) SpreadAbout(kept.mean, other)
// The mean is not moved: the kept estimate is the one to report while it may be right.
// kept.covariance where they agree within the quantile; continuous there (w = 1); it tends to
// the other's covariance and the whole offset as d^2 grows. Unlike DisagreementScale's factor,
// which grows every axis alike, the spread lies along the offset, at its length. Both
// covariances positive definite, quantile > 0.
Eigen::Matrix2d DisagreementMixture(const Gaussian2& kept, const Gaussian2& other, double quantile);

// A pair `a`, `b` fused into `fused` whose two points disagree beyond `quantile` (d^2 under
// a.covariance + b.covariance): the disagreement is no longer two understated covariances but
// one of the two points on something else (a neighbour's segment, the lamp post a walker
// passes). The covariance about fused.mean of three hypotheses: the fusion right with weight
// w = quantile / d^2, a right or b right with (1 - w) / 2 each:
//     w fused.covariance + (1 - w) / 2 (SpreadAbout(m, a) + SpreadAbout(m, b))
// fused.covariance within the quantile, continuous at it. `cross` as DisagreementScale's.
// Covariances positive definite, quantile > 0.
Eigen::Matrix2d TwoBodiesMixture(const Gaussian2& fused, const Gaussian2& a, const Gaussian2& b,
                                 double quantile,
                                 const Eigen::Matrix2d& cross = Eigen::Matrix2d::Zero());

// The squared Mahalanobis distance of `difference` under `covariance` (positive definite).
double MahalanobisSquared(const Eigen::Vector2d& difference, const Eigen::Matrix2d& covariance);

}  // namespace lookout::fusion
