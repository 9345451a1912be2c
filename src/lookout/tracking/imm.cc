#include "lookout/tracking/imm.h"

#include <array>
#include <cassert>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "lookout/core/input_error.h"

namespace lookout::tracking {
namespace {

constexpr double kSumTolerance = 1e-9;

int IndexOf(const std::vector<int>& components, int c) {
  for (std::size_t i = 0; i < components.size(); ++i) {
    if (components[i] == c) return static_cast<int>(i);
  }
  return -1;
}

std::vector<std::vector<int>> ComponentsOf(const ImmOptions& options) {
  std::vector<std::vector<int>> out;
  for (const MotionModel& m : options.models) out.push_back(StateComponents(m.kind));
  return out;
}

Eigen::Index At(int i) { return static_cast<Eigen::Index>(i); }

void Require(bool ok, const std::string& source, const std::string& field,
             const std::string& problem) {
  if (!ok) throw InputError(source, 0, field, problem);
}

bool IsProbabilityVector(const Eigen::VectorXd& p) {
  return p.allFinite() && p.minCoeff() >= 0.0 && std::abs(p.sum() - 1.0) <= kSumTolerance;
}

}  // namespace

void ImmOptions::Validate(const std::string& source, const std::string& prefix) const {
  const auto m = static_cast<Eigen::Index>(models.size());
  Require(m >= 1, source, prefix + ".models", "needs at least one model");
  for (std::size_t i = 0; i < models.size(); ++i) {
    models[i].Validate(source, fmt::format("{}.models[{}]", prefix, i));
  }
  Require(transition.rows() == m && transition.cols() == m, source, prefix + ".transition",
          fmt::format("must be {0} x {0} (one row and column per model)", m));
  for (Eigen::Index i = 0; i < m; ++i) {
    Require(IsProbabilityVector(transition.row(i).transpose()), source,
            fmt::format("{}.transition[{}]", prefix, i),
            "must be probabilities (finite, >= 0) that sum to 1");
  }
  Require(initial_probabilities.size() == m && IsProbabilityVector(initial_probabilities), source,
          prefix + ".initial_probabilities",
          fmt::format("must be {} probabilities that sum to 1", m));
}

ImmOptions FourModelImm(double cv_accel_psd, double ca_jerk_psd, double turn_rate_rad_s,
                        double turn_accel_psd, double stay) {
  ImmOptions o;
  o.models = {ConstantVelocity(cv_accel_psd), ConstantAcceleration(ca_jerk_psd),
              CoordinatedTurn(turn_rate_rad_s, turn_accel_psd),
              CoordinatedTurn(-turn_rate_rad_s, turn_accel_psd)};
  o.transition = Eigen::MatrixXd::Constant(4, 4, (1.0 - stay) / 3.0);
  o.transition.diagonal().setConstant(stay);
  o.initial_probabilities = Eigen::VectorXd::Constant(4, 0.25);
  return o;
}

ImmState InitImm(const ImmOptions& options, const Gaussian& prior,
                 const std::vector<int>& components, double unknown_variance, TimeNs time) {
  ImmState state;
  state.time = time;
  state.probabilities = options.initial_probabilities;
  for (const MotionModel& model : options.models) {
    const std::vector<int>& own = StateComponents(model.kind);
    const auto n = static_cast<Eigen::Index>(own.size());
    Gaussian g{Eigen::VectorXd::Zero(n), Eigen::MatrixXd::Zero(n, n)};
    for (Eigen::Index a = 0; a < n; ++a) {
      const int pa = IndexOf(components, own[static_cast<std::size_t>(a)]);
      if (pa < 0) {
        g.cov(a, a) = unknown_variance;
        continue;
      }
      g.mean(a) = prior.mean(At(pa));
      for (Eigen::Index b = 0; b < n; ++b) {
        const int pb = IndexOf(components, own[static_cast<std::size_t>(b)]);
        if (pb >= 0) g.cov(a, b) = prior.cov(At(pa), At(pb));
      }
    }
    state.modes.push_back(std::move(g));
  }
  return state;
}

Gaussian MomentMatch(const std::vector<std::vector<int>>& member_components,
                     const std::vector<Gaussian>& members, const Eigen::VectorXd& weights,
                     const std::vector<int>& components) {
  // Canonical components are at most kFullStateSize: fixed-capacity vectors and matrices keep the
  // working set off the heap (the MHT calls this for every track hypothesis and scan).
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kFullStateSize, 1>;
  using SmallMatrix =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kFullStateSize, kFullStateSize>;
  const auto n = static_cast<Eigen::Index>(components.size());
  assert(n <= kFullStateSize);
  const std::size_t count = members.size();

  // where[i][a]: the index of components[a] in member i, -1 when the member lacks it.
  std::vector<std::array<int, kFullStateSize>> where(count);
  for (std::size_t i = 0; i < count; ++i) {
    for (Eigen::Index a = 0; a < n; ++a) {
      where[i][static_cast<std::size_t>(a)] =
          IndexOf(member_components[i], components[static_cast<std::size_t>(a)]);
    }
  }
  const auto at = [&](std::size_t i, Eigen::Index a) {
    return where[i][static_cast<std::size_t>(a)];
  };

  // The fill of each component: the moment-matched mean and variance over its carriers.
  SmallVector fill_mean = SmallVector::Zero(n);
  SmallVector fill_var = SmallVector::Zero(n);
  for (Eigen::Index a = 0; a < n; ++a) {
    double total = 0.0;
    std::size_t carriers = 0;
    for (std::size_t i = 0; i < count; ++i) {
      if (at(i, a) >= 0) {
        total += weights(static_cast<Eigen::Index>(i));
        ++carriers;
      }
    }
    assert(carriers > 0 && "a component no member carries");
    // Carriers that all have weight 0 (a mode the chain cannot reach) share equally.
    const auto weight_of = [&](std::size_t i) {
      return total > 0.0 ? weights(static_cast<Eigen::Index>(i)) / total
                         : 1.0 / static_cast<double>(carriers);
    };
    for (std::size_t i = 0; i < count; ++i) {
      const int p = at(i, a);
      if (p >= 0) fill_mean(a) += weight_of(i) * members[i].mean(At(p));
    }
    for (std::size_t i = 0; i < count; ++i) {
      const int p = at(i, a);
      if (p < 0) continue;
      const double d = members[i].mean(At(p)) - fill_mean(a);
      fill_var(a) += weight_of(i) * (members[i].cov(At(p), At(p)) + d * d);
    }
  }

  // Each member augmented to `components`, then the usual moment matching of the mixture.
  const auto augmented_mean = [&](std::size_t i) {
    SmallVector g = fill_mean;
    for (Eigen::Index a = 0; a < n; ++a) {
      const int pa = at(i, a);
      if (pa >= 0) g(a) = members[i].mean(At(pa));
    }
    return g;
  };
  SmallVector mean = SmallVector::Zero(n);
  for (std::size_t i = 0; i < count; ++i) {
    mean += weights(static_cast<Eigen::Index>(i)) * augmented_mean(i);
  }
  SmallMatrix cov = SmallMatrix::Zero(n, n);
  for (std::size_t i = 0; i < count; ++i) {
    SmallMatrix g = fill_var.asDiagonal();
    for (Eigen::Index a = 0; a < n; ++a) {
      const int pa = at(i, a);
      if (pa < 0) continue;
      for (Eigen::Index b = 0; b < n; ++b) {
        const int pb = at(i, b);
        if (pb >= 0) g(a, b) = members[i].cov(At(pa), At(pb));
      }
    }
    const SmallVector d = augmented_mean(i) - mean;
    cov += weights(static_cast<Eigen::Index>(i)) * (g + d * d.transpose());
  }
  return {Eigen::VectorXd(mean), Eigen::MatrixXd(0.5 * (cov + cov.transpose()))};
}

Mixing MixInto(const ImmOptions& options, const ImmState& state) {
  const auto m = static_cast<Eigen::Index>(options.models.size());
  const std::vector<std::vector<int>> components = ComponentsOf(options);
  Mixing out;
  out.predicted_probabilities = options.transition.transpose() * state.probabilities;
  out.weights = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const double c = out.predicted_probabilities(j);
    if (c > 0.0) {
      out.weights.col(j) = options.transition.col(j).cwiseProduct(state.probabilities) / c;
    } else {
      out.weights(j, j) = 1.0;  // an unreachable mode keeps its own estimate
    }
    out.mixed.push_back(MomentMatch(components, state.modes, out.weights.col(j),
                                    components[static_cast<std::size_t>(j)]));
  }
  return out;
}

ImmState Predict(const ImmOptions& options, const ImmState& state, double dt_s) {
  assert(dt_s >= 0.0);
  Mixing mixing = MixInto(options, state);
  ImmState out;
  out.time = state.time;
  out.probabilities = mixing.predicted_probabilities;
  for (std::size_t j = 0; j < options.models.size(); ++j) {
    out.modes.push_back(PredictState(options.models[j], mixing.mixed[j], dt_s));
  }
  return out;
}

ImmState PredictTo(const ImmOptions& options, const ImmState& state, TimeNs time) {
  assert(time >= state.time && "the caller refuses time going backwards");
  ImmState out = Predict(options, state, ToSeconds(time - state.time));
  out.time = time;
  return out;
}

ImmMeasurementPrediction PredictMeasurement(const ImmState& predicted, const Eigen::Matrix2d& R) {
  ImmMeasurementPrediction out;
  out.combined.z.setZero();
  out.combined.S.setZero();
  for (std::size_t j = 0; j < predicted.modes.size(); ++j) {
    out.per_mode.push_back(PredictMeasurement(predicted.modes[j], R));
    out.combined.z += predicted.probabilities(static_cast<Eigen::Index>(j)) * out.per_mode[j].z;
  }
  for (std::size_t j = 0; j < predicted.modes.size(); ++j) {
    const Eigen::Vector2d d = out.per_mode[j].z - out.combined.z;
    out.combined.S += predicted.probabilities(static_cast<Eigen::Index>(j)) *
                      (out.per_mode[j].S + d * d.transpose());
  }
  return out;
}

ImmUpdate Update(const ImmOptions& options, const ImmState& predicted, const Eigen::Vector2d& z,
                 const Eigen::Matrix2d& R) {
  const auto m = static_cast<Eigen::Index>(options.models.size());
  ImmUpdate out;
  out.state.time = predicted.time;
  out.mode_nis.resize(m);
  // Work in logs: a far measurement gives likelihoods that underflow a double.
  Eigen::VectorXd log_weight(m);
  double best = -std::numeric_limits<double>::infinity();
  for (Eigen::Index j = 0; j < m; ++j) {
    UpdateResult u = UpdateState(predicted.modes[static_cast<std::size_t>(j)], z, R);
    out.mode_nis(j) = u.nis;
    const double c = predicted.probabilities(j);
    log_weight(j) = c > 0.0 ? u.log_likelihood + std::log(c)
                            : -std::numeric_limits<double>::infinity();
    best = std::max(best, log_weight(j));
    out.state.modes.push_back(std::move(u.posterior));
  }
  Eigen::VectorXd w(m);
  for (Eigen::Index j = 0; j < m; ++j) w(j) = std::exp(log_weight(j) - best);
  const double sum = w.sum();
  out.state.probabilities = w / sum;
  out.log_likelihood = best + std::log(sum);
  return out;
}

Gaussian Combine(const ImmOptions& options, const ImmState& state,
                 const std::vector<int>& components) {
  return MomentMatch(ComponentsOf(options), state.modes, state.probabilities, components);
}

}  // namespace lookout::tracking
