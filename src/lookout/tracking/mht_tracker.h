#pragma once

// Reid's multiple-hypothesis tracker (D. B. Reid, "An algorithm for tracking multiple targets",
// IEEE Trans. AC 24(6), 1979; seed 004 section VII.A-C), hypothesis-oriented, in the form of
// Cox and Hingorani ("An efficient implementation of Reid's MHT algorithm and its evaluation for
// the purpose of visual tracking", IEEE PAMI 18(2), 1996): at each scan every kept global
// hypothesis is extended by its m best associations (hypothesis_ranking.h: gating clusters,
// Murty's method), and the m best children over all parents are kept.
//
// Each track hypothesis carries an IMM (imm.h: CV, CA, left turn, right turn). Track hypotheses
// are shared between the global hypotheses that hold them (immutable nodes): a track is
// predicted and gated once per scan however many hypotheses hold it, and a (track, detection)
// update is computed once, and only when a kept hypothesis makes it.
//
// Score of a global hypothesis (log of Reid's eq. 16, up to a constant of the scan):
//   log P(child) = log P(parent)
//                + sum over the parent's tracks, missed:   log(1 - PD PG)
//                + sum over the detections they took:      log PD + log g(z | track)
//                + sum over false alarms:                  log lambda_FA
//                + sum over new tracks:                    log lambda_NT
// g is the IMM's measurement likelihood sum_j c_j N(z; H x_j, S_j) (1/m^2), PG the gate's
// probability (g is not renormalised to the gate: PD PG g / PG = PD g), lambda_FA and lambda_NT
// densities per m^2 and scan; the probabilities are normalised over the kept hypotheses. PD is
// each track's own at each scan: lower where the sensors could not see it (SensorView,
// hidden_detection_probability), so that a hidden track is not held to account for the scan's
// silence, and does not take a detection another explanation fits better (occluded-pedestrian:
// a walker coasting behind a nearer one took a split return of that one, 10 m off its
// prediction, and ran off after it).
//
// Pruning after each scan: the m best children (m = hypotheses_m, the cap on their number),
// those below min_hypothesis_probability, and N-scan pruning (every hypothesis must descend from
// the one the best hypothesis descends from N scans back: decisions older than N scans are
// final). Track management (track_management.h) is applied in every branch; a track missed too
// often ends. The output is the best hypothesis's confirmed tracks (seed 004 VII.C: "the most
// probable branch"), with ids that belong to the track tree (the birth it comes from), so that a
// change of best hypothesis never renumbers a track. Deterministic: no threads, no hashing order
// in any result, ties broken by fixed orders (parent rank, then the child's rank).

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lookout/core/time.h"
#include "lookout/tracking/imm.h"
#include "lookout/tracking/track_management.h"
#include "lookout/tracking/tracker.h"

namespace lookout::tracking {

struct MhtOptions {
  TrackManagementOptions management;

  // The IMM of every track (docs/imm.md): fixed-rate left and right turns at +-turn_rate_rad_s.
  double cv_accel_psd = 0.3;             // m^2/s^3
  double ca_jerk_psd = 0.1;              // m^2/s^5
  // The CA model's jerk for pedestrian and cyclist tracks (IsVulnerable): a walker starts and
  // stops within a few tenths of a second (child-behind-parked-car's child, 0 -> 2.5 m/s in
  // 0.2 s and to a stop), a cyclist pulls out from rest within a second (cyclist-crossing), a
  // car changes its acceleration over seconds. 5 m^2/s^5 lets the acceleration's sigma grow 2.2
  // m/s^2 in a second; the vehicles' 0.1, 0.3 m/s^2. Measured at 0.5 / 1 / 2 / 5 / 10 for walkers
  // (docs/tracking-metrics.md, "A walker's start and stop"): the child's and the hidden walker's
  // tracks better at each step, the child's below the GNN's from 5; and for cyclists at 5.
  double walker_ca_jerk_psd = 5.0;  // m^2/s^5
  // A pedestrian or cyclist track unseen for longer than walker_coast_acceleration_s is predicted
  // with the CA mode's weight given to CV: with the walkers' jerk its acceleration's sigma grows 2
  // m/s^2 a second unmeasured, and a hidden walker's coasting prediction widened until a clutter
  // detection 3 m off took it
  // (MhtTrackerTest.AHiddenTrackCoastsThroughTheShadowAndIsNotDraggedOff); a hidden walker walks
  // on. Not from its first miss: one to three scans missed in the open need the CA mode's wider
  // gate to take the walker back after a lagging update (from the first miss,
  // MhtTrackerTest.IdsStayWhenTheBestHypothesisChanges lost a walker to a second track after three
  // misses). 0.5 s; 0.3 and 1.0 pass the same tests. Infinity: never.
  double walker_coast_acceleration_s = 0.5;
  double turn_rate_rad_s = 0.3;
  double turn_accel_psd = 0.3;           // m^2/s^3
  double mode_stay_probability = 0.98;   // per scan; leaving to each other mode: (1 - stay) / 3
  double initial_speed_sigma_mps = 5.0;  // velocity prior of a new track (a walker's: management)
  double initial_acceleration_sigma_mps2 = 2.0;  // CA's acceleration prior

  // Hypothesis scores.
  double detection_probability = 0.9;      // PD
  // PD of a track the sensors could not see (SensorView): hidden tracks are seldom detected,
  // so a hidden track's miss costs next to nothing and a detection it takes costs it much.
  // A track seen by a fraction v (ViewFraction::seen) has
  // PD = v PD + (1 - v) hidden_detection_probability.
  // Not 0: a view is judged at the predicted position, which may be off (a walker stepping
  // out from behind a parked car is seen before its prediction is).
  double hidden_detection_probability = 0.05;
  double gate_probability = 0.999;         // PG, chi-square gate with 2 dof
  double clutter_density_per_m2 = 1e-4;    // lambda_FA: false alarms per m^2 and scan
  double new_track_density_per_m2 = 1e-3;  // lambda_NT: new targets per m^2 and scan

  // Pruning.
  int hypotheses_m = 10;  // global hypotheses kept per scan, and Murty's m for each parent
  int n_scan = 3;         // N-scan pruning depth, scans
  double min_hypothesis_probability = 1e-4;

  // Throws lookout::InputError naming the first field out of range.
  void Validate(const std::string& source = "mht options") const;
};

// The four-model IMM the tracks carry.
ImmOptions MhtImm(const MhtOptions& options);
// The same for pedestrian and cyclist tracks (IsVulnerable): the CA model's jerk
// walker_ca_jerk_psd. The same models (a track whose class becomes known changes options, not
// state).
ImmOptions MhtWalkerImm(const MhtOptions& options);
// Walkers and cyclists: the road users who start and stop within a second (walker_ca_jerk_psd).
inline bool IsVulnerable(ObjectClass c) {
  return c == ObjectClass::kPedestrian || c == ObjectClass::kCyclist;
}

class MhtTracker final : public Tracker {
 public:
  explicit MhtTracker(const MhtOptions& options = {});

  using Tracker::Step;
  bool Step(TimeNs stamp, const std::vector<Detection>& detections,
            const SensorView& view) override;
  std::vector<Track> ConfirmedTracks() const override { return confirmed_; }
  std::int64_t dropped_detections() const override { return dropped_; }
  std::int64_t refused_scans() const override { return refused_; }

  // Every track of the best hypothesis, tentative ones too (id 0 until first confirmed), in
  // track-tree order.
  std::vector<Track> BestHypothesisTracks() const;
  // The kept global hypotheses' probabilities, best first (they sum to 1).
  std::vector<double> HypothesisProbabilities() const;
  // Every kept hypothesis's tracks (ids as in BestHypothesisTracks), best first.
  std::vector<std::vector<Track>> HypothesisTracks() const;
  // Distinct track hypotheses held by the kept global hypotheses.
  std::size_t TrackHypothesisCount() const;
  // Scans whose best hypothesis does not descend from the previous scan's best.
  std::int64_t best_hypothesis_switches() const { return switches_; }

  const MhtOptions& options() const { return options_; }

 private:
  struct Node;  // one track hypothesis (mht_tracker.cc)
  using NodePtr = std::shared_ptr<const Node>;
  struct Hypothesis {
    std::vector<NodePtr> tracks;  // in track-tree order
    double log_probability = 0.0;
    std::uint64_t id = 0;
    std::vector<std::uint64_t> ancestors;  // the hypotheses it descends from, latest first, <= N
  };
  struct ScanWork;

  Track Output(const Node& node) const;

  MhtOptions options_;
  ImmOptions imm_;
  ImmOptions walker_imm_;
  // The IMM state a track is predicted from (walker_coast_acceleration_s).
  ImmState CoastingModes(const Node& node, TimeNs stamp) const;
  // The IMM of a track of class `c`.
  const ImmOptions& ImmFor(ObjectClass c) const { return IsVulnerable(c) ? walker_imm_ : imm_; }
  std::vector<Hypothesis> hypotheses_;  // best first
  std::map<std::uint64_t, std::uint32_t> id_of_tree_;
  std::vector<Track> confirmed_;
  std::uint64_t next_tree_ = 1;
  std::uint64_t next_hypothesis_ = 1;
  std::uint32_t next_id_ = 1;
  std::optional<TimeNs> last_stamp_;
  std::int64_t dropped_ = 0;
  std::int64_t refused_ = 0;
  std::int64_t switches_ = 0;
};

}  // namespace lookout::tracking
