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

// How much two measurements of one point disagree beyond what their covariances allow: their
// difference's d^2 under a.covariance + b.covariance (2 dof, chi-square when the pair is right
// and both covariances are) against `quantile`, the chi-square quantile of a probability.
// max(1, d^2 / quantile): 1 for all but the rarest consistent pairs; beyond, the factor by which
// both covariances must grow for the difference to sit on the quantile. Scaling both by it
// leaves FuseGaussians' mean where it was and scales the fused covariance by it: the
// disagreement itself is the evidence that one of the two (a pair on a neighbour's segment,
// a point on another side of the body) is off by more than it says. Both covariances positive
// definite, quantile > 0.
double DisagreementScale(const Gaussian2& a, const Gaussian2& b, double quantile);

// The squared Mahalanobis distance of `difference` under `covariance` (positive definite).
double MahalanobisSquared(const Eigen::Vector2d& difference, const Eigen::Matrix2d& covariance);

}  // namespace lookout::fusion
