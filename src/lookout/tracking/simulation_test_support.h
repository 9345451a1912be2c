#pragma once

// Simulated targets for the tracking tests: truth by the models' own transitions with process
// noise drawn from their Q, and position measurements with isotropic noise. Fixed seeds.

#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Core>

#include "lookout/core/random.h"
#include "lookout/tracking/motion_models.h"

namespace lookout::tracking::testing {

inline Eigen::VectorXd DrawNormal(Rng& rng, const Eigen::MatrixXd& cov) {
  Eigen::VectorXd e(cov.rows());
  for (Eigen::Index i = 0; i < e.size(); ++i) e(i) = rng.Normal();
  // An eigen-decomposition tolerates the semi-definite Q of the models.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(cov);
  return eig.eigenvectors() * (eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal() * e);
}

// The truth after `steps` transitions of `model` (with its process noise when `noisy`).
inline std::vector<Eigen::VectorXd> SimulateTruth(Rng& rng, const MotionModel& model,
                                                  Eigen::VectorXd x, int steps, double dt,
                                                  bool noisy) {
  std::vector<Eigen::VectorXd> out;
  for (int k = 0; k < steps; ++k) {
    const Transition t = Propagate(model, x, dt);
    x = t.x;
    if (noisy) x += DrawNormal(rng, t.Q);
    out.push_back(x);
  }
  return out;
}

inline Eigen::Vector2d Measure(Rng& rng, const Eigen::VectorXd& x, double sigma) {
  return Eigen::Vector2d{x(0) + sigma * rng.Normal(), x(1) + sigma * rng.Normal()};
}

}  // namespace lookout::tracking::testing
