#include "lookout/tracking/mht_tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

#include "lookout/core/chi_square.h"
#include "lookout/core/input_error.h"
#include "lookout/tracking/hypothesis_ranking.h"

namespace lookout::tracking {

struct MhtTracker::Node {
  Track track;  // the output value, but for its id (the tree's, given on output)
  ImmState imm;
  std::uint64_t tree = 0;
};

namespace {

double LogSumExp(const std::vector<double>& x) {
  double best = -std::numeric_limits<double>::infinity();
  for (const double v : x) best = std::max(best, v);
  double sum = 0.0;
  for (const double v : x) sum += std::exp(v - best);
  return best + std::log(sum);
}

// log sum_j c_j N(z; z_j, S0_j + R), p predicted with R = 0: the IMM's measurement likelihood
// (imm.h's Update gives the same number, with the posterior that gating does not need).
double ImmLogLikelihood(const ImmState& predicted, const ImmMeasurementPrediction& p,
                        const Eigen::Vector2d& z, const Eigen::Matrix2d& R) {
  std::vector<double> terms;
  terms.reserve(p.per_mode.size());
  for (std::size_t j = 0; j < p.per_mode.size(); ++j) {
    const double c = predicted.probabilities(static_cast<Eigen::Index>(j));
    if (c > 0.0) {
      terms.push_back(std::log(c) +
                      GaussianLogLikelihood(z - p.per_mode[j].z, p.per_mode[j].S + R));
    }
  }
  return LogSumExp(terms);
}

// v' S^-1 v for a symmetric positive definite 2 x 2 S, written out: the gate runs for every
// (track hypothesis, detection) pair, and the general NormalisedSquare allocates.
double Nis2(const Eigen::Vector2d& v, const Eigen::Matrix2d& S) {
  const double det = S(0, 0) * S(1, 1) - S(0, 1) * S(1, 0);
  return (S(1, 1) * v.x() * v.x() - (S(0, 1) + S(1, 0)) * v.x() * v.y() + S(0, 0) * v.y() * v.y()) /
         det;
}

}  // namespace

void MhtOptions::Validate(const std::string& source) const {
  management.Validate(source);
  auto require = [&](bool ok, const char* field, const char* problem) {
    if (!ok) throw InputError(source, 0, field, problem);
  };
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  require(positive(cv_accel_psd), "cv_accel_psd", "must be > 0");
  require(positive(ca_jerk_psd), "ca_jerk_psd", "must be > 0");
  require(positive(walker_ca_jerk_psd), "walker_ca_jerk_psd", "must be > 0");
  require(walker_coast_acceleration_s >= 0.0, "walker_coast_acceleration_s",
          "must be >= 0 (infinity: never)");
  require(positive(turn_rate_rad_s), "turn_rate_rad_s", "must be > 0");
  require(positive(turn_accel_psd), "turn_accel_psd", "must be > 0");
  require(mode_stay_probability > 0.0 && mode_stay_probability < 1.0, "mode_stay_probability",
          "must be in (0, 1)");
  require(positive(initial_speed_sigma_mps), "initial_speed_sigma_mps", "must be > 0");
  require(positive(initial_acceleration_sigma_mps2), "initial_acceleration_sigma_mps2",
          "must be > 0");
  require(detection_probability > 0.0 && detection_probability < 1.0, "detection_probability",
          "must be in (0, 1)");
  require(
      hidden_detection_probability > 0.0 && hidden_detection_probability <= detection_probability,
      "hidden_detection_probability", "must be in (0, detection_probability]");
  require(gate_probability > 0.0 && gate_probability < 1.0, "gate_probability",
          "must be in (0, 1)");
  require(positive(clutter_density_per_m2), "clutter_density_per_m2", "must be > 0");
  require(positive(new_track_density_per_m2), "new_track_density_per_m2", "must be > 0");
  require(hypotheses_m >= 1, "hypotheses_m", "must be >= 1");
  require(n_scan >= 1, "n_scan", "must be >= 1");
  require(min_hypothesis_probability >= 0.0 && min_hypothesis_probability < 1.0,
          "min_hypothesis_probability", "must be in [0, 1)");
}

ImmOptions MhtImm(const MhtOptions& o) {
  return FourModelImm(o.cv_accel_psd, o.ca_jerk_psd, o.turn_rate_rad_s, o.turn_accel_psd,
                      o.mode_stay_probability);
}

ImmOptions MhtWalkerImm(const MhtOptions& o) {
  MhtOptions walker = o;
  walker.ca_jerk_psd = o.walker_ca_jerk_psd;
  return MhtImm(walker);
}

ImmState MhtTracker::CoastingModes(const Node& node, TimeNs stamp) const {
  const double unseen_s = ToSeconds(stamp - node.track.last_detected);
  if (!node.track.coasting || !IsVulnerable(node.track.object_class) ||
      unseen_s <= options_.walker_coast_acceleration_s) {
    return node.imm;
  }
  // FourModelImm's order: CV, CA, then the turns. Nothing has measured the acceleration for
  // longer than walker_coast_acceleration_s: the CA mode's weight goes to CV.
  ImmState s = node.imm;
  if (s.probabilities.size() < 2) return s;
  const Eigen::Vector2d cv_ca = s.probabilities.head<2>();
  s.probabilities.head<2>() = Eigen::Vector2d(cv_ca.sum(), 0.0);
  return s;
}

MhtTracker::MhtTracker(const MhtOptions& options) : options_(options) {
  options_.Validate();
  imm_ = MhtImm(options_);
  walker_imm_ = MhtWalkerImm(options_);
  hypotheses_.push_back(Hypothesis{});  // no track yet, probability 1
}

// What one scan computes once and the hypotheses share: each distinct track's prediction and
// gate, and the nodes made from them, created on first use.
struct MhtTracker::ScanWork {
  struct Gated {
    int detection = 0;
    double log_likelihood = 0.0;
    NodePtr updated;  // made when a kept hypothesis takes the pair; null if the track ends
    bool made = false;
  };
  struct Branches {
    const Node* node = nullptr;
    ImmState predicted;
    ViewFraction view;         // of the predicted track, SensorView
    double log_detect = 0.0;   // log PD of this track at this scan
    double log_miss = 0.0;     // log (1 - PD PG)
    std::vector<Gated> gated;  // increasing detection
    NodePtr missed;
    bool missed_made = false;
  };
  std::vector<Branches> branches;
  std::unordered_map<const Node*, std::size_t> index;  // lookup only: never iterated
  std::vector<NodePtr> births;                          // per detection, made on first use
};

bool MhtTracker::Step(TimeNs stamp, const std::vector<Detection>& all, const SensorView& view) {
  if (last_stamp_ && stamp <= *last_stamp_) {
    ++refused_;
    return false;
  }
  const std::vector<Detection> detections = UsableDetections(all);
  dropped_ += static_cast<std::int64_t>(all.size() - detections.size());
  const auto detection_count = static_cast<int>(detections.size());
  const double gate = ChiSquareQuantile(options_.gate_probability, 2.0);

  // 1. Predict and gate each distinct track hypothesis once.
  ScanWork work;
  work.births.resize(detections.size());
  for (const Hypothesis& h : hypotheses_) {
    for (const NodePtr& node : h.tracks) {
      if (!work.index.emplace(node.get(), work.branches.size()).second) continue;
      ScanWork::Branches b;
      b.node = node.get();
      b.predicted = PredictTo(ImmFor(node->track.object_class), CoastingModes(*node, stamp), stamp);
      const ImmMeasurementPrediction p = PredictMeasurement(b.predicted, Eigen::Matrix2d::Zero());
      // PD as the view has it at the predicted position (combined over the modes).
      b.view = view.View(p.combined.z, node->track.object_class);
      // A view that cannot say (NaN) is taken to have seen nothing.
      const double seen = std::isfinite(b.view.seen) ? std::clamp(b.view.seen, 0.0, 1.0) : 0.0;
      const double pd = seen * options_.detection_probability +
                        (1.0 - seen) * options_.hidden_detection_probability;
      b.log_detect = std::log(pd);
      b.log_miss = std::log1p(-pd * options_.gate_probability);
      for (int j = 0; j < detection_count; ++j) {
        const Detection& d = detections[static_cast<std::size_t>(j)];
        if (!ClassesCompatible(node->track.object_class, d.object_class)) continue;
        const ClassCentre z = MeasurementFor(d, node->track.object_class);
        const Eigen::Vector2d v = z.position_m - p.combined.z;
        // Written so that a NaN (a detection or a track far beyond any road, squares overflowing)
        // fails the gate and the score instead of passing them.
        if (!(Nis2(v, p.combined.S + z.covariance) <= gate)) continue;
        const double log_likelihood = ImmLogLikelihood(b.predicted, p, z.position_m, z.covariance);
        if (!std::isfinite(log_likelihood)) continue;
        b.gated.push_back({j, log_likelihood, {}});
      }
      work.branches.push_back(std::move(b));
    }
  }

  // 2. Each parent's m best associations, scored; the m best children over all parents.
  struct Child {
    double log_score = 0.0;
    std::size_t parent = 0;
    std::size_t rank = 0;
    std::vector<int> track_of_detection;
  };
  std::vector<Child> children;
  const auto m = static_cast<std::size_t>(options_.hypotheses_m);
  for (std::size_t h = 0; h < hypotheses_.size(); ++h) {
    const Hypothesis& parent = hypotheses_[h];
    AssociationProblem problem;
    problem.tracks = static_cast<int>(parent.tracks.size());
    problem.detections = detection_count;
    problem.false_alarm_cost = -std::log(options_.clutter_density_per_m2);
    problem.new_track_cost = -std::log(options_.new_track_density_per_m2);
    double base = parent.log_probability;
    for (std::size_t t = 0; t < parent.tracks.size(); ++t) {
      const ScanWork::Branches& b = work.branches[work.index.at(parent.tracks[t].get())];
      base += b.log_miss;
      for (const ScanWork::Gated& g : b.gated) {
        problem.pairs.push_back(
            {static_cast<int>(t), g.detection, -(b.log_detect + g.log_likelihood - b.log_miss)});
      }
    }
    std::vector<RankedAssociation> ranked = BestAssociations(problem, m);
    for (std::size_t r = 0; r < ranked.size(); ++r) {
      children.push_back({base - ranked[r].cost, h, r, std::move(ranked[r].track_of_detection)});
    }
  }
  std::stable_sort(children.begin(), children.end(), [](const Child& a, const Child& b) {
    return a.log_score > b.log_score;  // stable: equal scores keep (parent, rank) order
  });
  if (children.size() > m) children.resize(m);

  // 3. Pruning: normalise, drop the improbable, then N-scan pruning, and normalise again.
  const auto normalise = [&children] {
    std::vector<double> scores;
    for (const Child& c : children) scores.push_back(c.log_score);
    const double total = LogSumExp(scores);
    for (Child& c : children) c.log_score -= total;
  };
  normalise();
  const double min_log = std::log(options_.min_hypothesis_probability);
  children.erase(std::remove_if(children.begin() + 1, children.end(),
                                [&](const Child& c) { return c.log_score < min_log; }),
                 children.end());
  const auto ancestors_of = [&](const Child& c) {
    const Hypothesis& parent = hypotheses_[c.parent];
    std::vector<std::uint64_t> a{parent.id};
    for (const std::uint64_t id : parent.ancestors) {
      if (a.size() >= static_cast<std::size_t>(options_.n_scan)) break;
      a.push_back(id);
    }
    return a;
  };
  const std::vector<std::uint64_t> best_ancestors = ancestors_of(children.front());
  if (best_ancestors.size() == static_cast<std::size_t>(options_.n_scan)) {
    children.erase(std::remove_if(children.begin() + 1, children.end(),
                                  [&](const Child& c) {
                                    return ancestors_of(c).back() != best_ancestors.back();
                                  }),
                   children.end());
  }
  normalise();

  // 4. The kept children's track hypotheses, made once each.
  const auto finish = [&](Node& node, const Track& before) {
    node.track.stamp = stamp;
    node.track.state = Combine(ImmFor(node.track.object_class), node.imm);
    node.track.mode_probabilities = node.imm.probabilities;
    node.track.previous = TrackSnapshot{before.stamp, before.state};
  };
  const auto updated = [&](ScanWork::Branches& b, int j) -> NodePtr {
    ScanWork::Gated& g = *std::find_if(b.gated.begin(), b.gated.end(),
                                       [j](const ScanWork::Gated& x) { return x.detection == j; });
    if (!g.made) {
      g.made = true;
      const Detection& d = detections[static_cast<std::size_t>(j)];
      Track track = AfterDetection(options_.management, b.node->track, d, stamp);
      // The camera's evidence can end a track on a detection (a ghost): it takes the
      // detection with it.
      if (!Expired(options_.management, track)) {
        auto node = std::make_shared<Node>();
        node->tree = b.node->tree;
        const ClassCentre z = MeasurementFor(d, b.node->track.object_class);
        // The IMM the branch was predicted with (its parent's class).
        const ImmOptions& imm = ImmFor(b.node->track.object_class);
        node->imm = Update(imm, b.predicted, z.position_m, z.covariance).state;
        if (track.updates == 3) {
          // The third detection: the seen points' velocity, where surer (tracker.h).
          const Gaussian combined = Combine(imm, node->imm);
          const Gaussian seen =
              WithSeenVelocity(combined, track.early_seen_points,
                               options_.management.seen_velocity_agreement_probability);
          if (seen.mean != combined.mean || seen.cov != combined.cov) {
            const double sa = options_.initial_acceleration_sigma_mps2;
            node->imm = InitImm(imm, seen, {kX, kY, kVx, kVy}, sa * sa, stamp);
          }
        }
        node->track = std::move(track);
        finish(*node, b.node->track);
        g.updated = std::move(node);
      }
    }
    return g.updated;
  };
  const auto missed = [&](ScanWork::Branches& b) -> NodePtr {
    if (!b.missed_made) {
      b.missed_made = true;
      Track track = AfterMiss(options_.management, b.node->track, b.view, stamp);
      if (!Expired(options_.management, track)) {
        auto node = std::make_shared<Node>();
        node->tree = b.node->tree;
        node->imm = b.predicted;
        node->track = std::move(track);
        finish(*node, b.node->track);
        b.missed = std::move(node);
      }
    }
    return b.missed;
  };
  const auto born = [&](int j) -> NodePtr {
    NodePtr& slot = work.births[static_cast<std::size_t>(j)];
    if (!slot) {
      const Detection& d = detections[static_cast<std::size_t>(j)];
      auto node = std::make_shared<Node>();
      node->tree = next_tree_++;
      node->track = BornTrack(options_.management, d, stamp);
      const Gaussian prior = BirthState(d, InitialSpeedSigma(options_.management, d.object_class,
                                                             options_.initial_speed_sigma_mps));
      const double sa = options_.initial_acceleration_sigma_mps2;
      node->imm = InitImm(ImmFor(d.object_class), prior, {kX, kY, kVx, kVy}, sa * sa, stamp);
      node->track.state = Combine(ImmFor(d.object_class), node->imm);
      node->track.mode_probabilities = node->imm.probabilities;
      slot = std::move(node);
    }
    return slot;
  };

  std::vector<Hypothesis> next;
  next.reserve(children.size());
  for (const Child& c : children) {
    const Hypothesis& parent = hypotheses_[c.parent];
    Hypothesis h;
    h.id = next_hypothesis_++;
    h.log_probability = c.log_score;
    h.ancestors = ancestors_of(c);
    std::vector<int> detection_of_track(parent.tracks.size(), -1);
    for (int j = 0; j < detection_count; ++j) {
      const int t = c.track_of_detection[static_cast<std::size_t>(j)];
      if (t >= 0) detection_of_track[static_cast<std::size_t>(t)] = j;
    }
    for (std::size_t t = 0; t < parent.tracks.size(); ++t) {
      ScanWork::Branches& b = work.branches[work.index.at(parent.tracks[t].get())];
      NodePtr node = detection_of_track[t] >= 0 ? updated(b, detection_of_track[t]) : missed(b);
      if (node) h.tracks.push_back(std::move(node));
    }
    for (int j = 0; j < detection_count; ++j) {
      if (c.track_of_detection[static_cast<std::size_t>(j)] == kNewTrack) {
        h.tracks.push_back(born(j));
      }
    }
    std::sort(h.tracks.begin(), h.tracks.end(),
              [](const NodePtr& a, const NodePtr& b) { return a->tree < b->tree; });
    next.push_back(std::move(h));
  }
  if (children.front().parent != 0) ++switches_;
  hypotheses_ = std::move(next);
  last_stamp_ = stamp;

  // 5. Output: the best hypothesis's confirmed tracks. A tree gets its id the first time it is
  // output, in tree order; ids of trees no hypothesis holds any more are forgotten.
  confirmed_.clear();
  for (const NodePtr& node : hypotheses_.front().tracks) {
    if (node->track.status != TrackStatus::kConfirmed) continue;
    if (id_of_tree_.emplace(node->tree, next_id_).second) ++next_id_;
    confirmed_.push_back(Output(*node));
  }
  std::sort(confirmed_.begin(), confirmed_.end(),
            [](const Track& a, const Track& b) { return a.id < b.id; });
  std::vector<std::uint64_t> alive;
  for (const Hypothesis& h : hypotheses_) {
    for (const NodePtr& node : h.tracks) alive.push_back(node->tree);
  }
  std::sort(alive.begin(), alive.end());
  for (auto it = id_of_tree_.begin(); it != id_of_tree_.end();) {
    it = std::binary_search(alive.begin(), alive.end(), it->first) ? std::next(it)
                                                                    : id_of_tree_.erase(it);
  }
  return true;
}

Track MhtTracker::Output(const Node& node) const {
  Track t = node.track;
  const auto id = id_of_tree_.find(node.tree);
  t.id = id == id_of_tree_.end() ? 0 : id->second;
  return t;
}

std::vector<Track> MhtTracker::BestHypothesisTracks() const {
  std::vector<Track> out;
  for (const NodePtr& node : hypotheses_.front().tracks) out.push_back(Output(*node));
  return out;
}

std::vector<std::vector<Track>> MhtTracker::HypothesisTracks() const {
  std::vector<std::vector<Track>> out;
  for (const Hypothesis& h : hypotheses_) {
    std::vector<Track>& tracks = out.emplace_back();
    for (const NodePtr& node : h.tracks) tracks.push_back(Output(*node));
  }
  return out;
}

std::vector<double> MhtTracker::HypothesisProbabilities() const {
  std::vector<double> out;
  for (const Hypothesis& h : hypotheses_) out.push_back(std::exp(h.log_probability));
  return out;
}

std::size_t MhtTracker::TrackHypothesisCount() const {
  std::vector<const Node*> nodes;
  for (const Hypothesis& h : hypotheses_) {
    for (const NodePtr& node : h.tracks) nodes.push_back(node.get());
  }
  std::sort(nodes.begin(), nodes.end());
  return static_cast<std::size_t>(std::unique(nodes.begin(), nodes.end()) - nodes.begin());
}

}  // namespace lookout::tracking
