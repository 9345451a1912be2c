#pragma once

// Options of the extended grid's filter (docs/extended-grid.md steps 2-8), one plain struct with
// defaults and units in the names. Kept beside GridOptions rather than inside it so the filter can
// be configured and validated on its own; GridOptions keeps the window and the sensor model.

#include <array>
#include <string>

#include "lookout/grid/cluster_motion.h"
#include "lookout/grid/hidden_bodies.h"
#include "lookout/grid/scan_flow.h"

namespace lookout::grid {

// The class layer's classes, in layer order (docs/extended-grid.md, "what the grid holds").
enum class GridClass { kStatic = 0, kPedestrian, kCyclist, kVehicle, kUnknown };
inline constexpr int kGridClassCount = 5;
using ClassPmf = std::array<float, kGridClassCount>;

// The widest search window, in samples a side (window_size_cells, new_window_size_cells):
// the per-window scratch arrays of the stages are this long.
inline constexpr int kMaxWindowSideCells = 31;

struct FilterOptions {
  // --- step 2, association prediction (eq. 8-9)
  // Cells whose occupancy is at least this are moved ("worth moving"); the others stay in place.
  // Above the 0.5 prior so that unknown space costs nothing.
  double active_occupancy = 0.6;
  // Tracked occupancy (seen probability >= seen_threshold) keeps moving down to this
  // occupancy: an occluded object's mass spreads (eq. 8 with 0.5 measurements) and must keep
  // moving as it thins out, instead of freezing where it falls under active_occupancy.
  double tracked_min_occupancy = 0.05;
  // M: the search window of a tracked cell, centred on its predicted displacement V dt (not on
  // the cell itself, as in the paper: that is what lifts the paper's speed cap M/2 * cell / dt).
  int window_size_cells = 7;
  // Newly seen occupancy (seen probability S below seen_threshold) has no velocity yet: it is
  // searched in a coarse window of new_window_size_cells samples new_window_stride_cells apart,
  // i.e. displacements up to +-(size / 2) * stride cells = +-12 cells by default: 1.8 m per
  // cycle at 0.15 m, 22.5 m/s at 12.5 Hz. Coarse rather than dense: 13^2 = 169 candidates
  // instead of 25^2 = 625, and the measurement weighting (eq. 10) picks the occupied samples;
  // once the velocity is known the fine window takes over, centred on it.
  int new_window_size_cells = 13;
  int new_window_stride_cells = 2;
  // ... beside a dense (stride 1) core of +-new_window_dense_half_cells around the window's
  // centre (0: none): a coarse lattice has no sample at a walker's 0.6-0.8 cell a cycle.
  int new_window_dense_half_cells = 0;
  double seen_threshold = 0.5;
  // ... and so is occupancy whose velocity is not yet trusted (confidence below this): the
  // coarse window is then centred on the uncertain prediction, so an early wrong estimate
  // (a box's interior is ambiguous) can still be corrected by the next scans.
  double known_confidence = 0.25;
  // Predicted displacements are clamped to this many cells per cycle (a sanity bound: 40 m/s
  // at 0.15 m and 12.5 Hz is 21 cells).
  int max_displacement_cells = 24;
  // The motion model's memory, s: the velocity predicted for the next cycle is the estimate
  // times exp(-dt / velocity_persistence_s), a velocity that the measurements do not keep up
  // decays to zero. Why: along a straight surface (a wall beside the road, the side of a
  // parked car) and inside a solid region every displacement fits the scan equally well, so a
  // wrong velocity once there would be kept for ever (the aperture problem). A moving object's
  // edges keep its velocity up cycle after cycle. 3 s: on the catalogue, 1 s halves the
  // static false-dynamic rate again but biases a 3.75 m/s box 15 % low (the interior follows
  // the decayed prediction); 3 s keeps that bias under 3 %. Infinity: the paper's
  // constant-velocity prediction.
  double velocity_persistence_s = 3.0;
  // ... but only where the scan observes the source's cell (its measurement is not 1/2). Where
  // it does not (an occluder's shadow, the unseen inside of a body, beyond the range) no
  // measurement stops supporting the velocity, and the decay would only slow a hidden body
  // down: `fast-car`'s car, hidden for its last 0.8 s in the window, fell from 20 to 12.5 m/s
  // and scored 5.0 m/s of RMSE after its first second; carried as it is, 0.62 (docs/grid.md,
  // "A hidden body keeps its speed"). False: the decay everywhere.
  bool velocity_persists_unobserved = true;
  // sigma_C of eq. 8 per class: the standard deviation of the velocity change in one cycle,
  // m/s. A pedestrian can stop or turn within a step; a vehicle changes speed faster in
  // absolute terms but cannot turn on the spot; unknown is the widest. The position sigma is
  // sqrt(sum_c C(c) sigma_c^2) * dt, floored at min_sigma_cells cells.
  std::array<double, kGridClassCount> class_velocity_sigma_mps = {0.2, 1.0, 1.0, 1.5, 2.0};
  // Why a floor, and why small: the prediction's spread is also the mass that leaks into free
  // cells each cycle (eq. 10 weighs them down, it does not exclude them), which the sensor's
  // p_hit must win back; 0.4 cell keeps the leak of a static cell near 3 %.
  double min_sigma_cells = 0.4;
  // The prior of newly seen occupancy: its position sigma, m (about 6 cells).
  double new_sigma_m = 0.9;
  // ... mixed with a component of this probability that follows the prediction exactly (a
  // Gaussian of min_sigma_cells; for newly seen occupancy, V = 0: it stays in place): most newly
  // revealed occupancy is static structure, and a wide search alone would smear it over the
  // coarse window.
  double new_stay_probability = 0.5;
  // Occupancy that would get the wide window but whose displacement the scan pair measures gets
  // the fine window centred on it instead (scan_flow.h says why and how).
  ScanFlowOptions scan_flow;

  // --- step 4, interaction constraints (eq. 11)
  // No convergence: a move j -> i is weighted by exp(-excess^2 / (2 sigma^2)), excess being the
  // occupancy mass that i would hold beyond 1.
  double no_convergence_sigma = 0.3;
  // Rigidity: a move is weighted by how well its displacement agrees with those of the linked
  // neighbours, a Gaussian of this width in cells.
  double rigidity_sigma_cells = 1.0;
  // The link strength of eq. 11 is min(1, gain D): D = sum_a P(a) P'(a) of eq. 15 is at most
  // sum_a P(a)^2, about 0.3 for the sharpest pmfs a 0.15 m grid holds (sigma ~ 0.5 cell), so D
  // itself never says "certainly one body". A gain of 3 makes a rigid box's velocities agree
  // better (rms spread 0.28 instead of 0.37 m/s at 3 m/s) but biases its mean (+0.4 m/s) and
  // saturates the links of the random reference worlds; 1 (D as the paper has it) for now.
  double rigidity_link_gain = 1.0;
  bool enable_rigidity_constraint = true;
  // Where a linked neighbour's window is on another lattice (another centre or stride: a tracked
  // cell beside a newly seen one, or two tracked cells whose predictions round apart), its pmf
  // enters the rigidity term through a Gaussian of its two moments (false), or through the
  // blurred pmf summed exactly (true: the literal eq. 11, matched to 1e-7 by the reference).
  // False by default: exact, the catalogue's figures move both ways (docs/grid.md, 2026-12-02:
  // pushchair-group false dynamic 0.025 -> 0.001 but static-world-drive 0.025 -> 0.031 and
  // left-turn-across-path MOTA 0.77 -> 0.14).
  bool rigidity_exact_across_lattices = false;
  bool enable_no_convergence_constraint = true;

  // --- step 5, occupancy (eq. 12-13)
  // gamma: the renewal rate. Space that no association covers (a cell whose content moved out
  // and nothing moved in) gets the occupancy prior gamma / 2: renewed towards unknown.
  double renewal_rate = 0.5;
  // Occupancy is kept inside [min, 1 - min] so that a cell stays revisable.
  double occupancy_clamp = 0.02;

  // --- step 6, velocity (eq. 14)
  // Weight of the new displacement estimate against the carried velocity, for a confident
  // carried velocity (a velocity of zero confidence is replaced).
  double velocity_blend = 0.3;
  // The displacement spread (cells^2) at which the confidence is one half.
  double confidence_spread_cells2 = 2.0;
  // The observed confidence is multiplied by M^moved_share_exponent, M the moved share of the
  // carried mass (the part of it that step 2's "stays in place" component did not carry, where
  // the prediction is no motion): occupancy explained by staying is no evidence of motion. 0:
  // off. 0.5 with the dense core met the false-dynamic goal (docs/grid.md, 2026-12-02).
  double moved_share_exponent = 0.0;
  // Where a source's mass survived (its per-source mean displacement, eq. 14 as built): false,
  // weighted by the target's posterior occupancy O; true, only into targets the scan did not see
  // free, weighted by the occupancy evidence max(0, 2 O - 1). Why: a fast body's first
  // association puts most of its mass on its old cells and the free road around (odds 0.43
  // each), whose posterior stays 0.1-0.3 and drags the mean towards zero.
  bool survival_needs_evidence = false;

  // --- between steps 7 and 8: each rigid cluster's displacement measured whole from the scan
  // pair and given to its cells (cluster_motion.h says why and how).
  ClusterMotionOptions cluster_motion;
  // Beyond the paper: a rigid body the scan stops seeing carried whole through the shadow
  // (hidden_bodies.h says why and how).
  HiddenBodyOptions hidden_bodies;

  // --- step 8, classes
  double class_floor = 0.01;           // mixed in uniformly each cycle: classes stay revisable
  double extent_radius_cells = 6.0;    // the local extent proxy's box half-size
  // A cell the scan does not observe that moves at least this fast gets no extent cue. The cue
  // counts the hits around the cell; of a body carried through a shadow or out of view
  // (hidden_bodies.h) there are none, which read as a small footprint: near-miss's car, carried
  // out of view, became a cyclist within a few cycles (class accuracy 0.91 -> 0.21 with step 5
  // of the hidden bodies). Faster than a walker (the speed cue's pedestrian range, 2.5 m/s, and
  // its 0.5 m/s softness) a small footprint can only mean a cyclist, and such a cell keeps the
  // class it had when seen. Slower, the cue stays: at 0.5 m/s the hidden walkers of a group,
  // misread as one large body while seen, kept that class and the spread it brings (the
  // crossing group's velocity error 0.446 -> 0.464, the crowd's false-dynamic rate 0.0100 ->
  // 0.0121).
  double unobserved_mover_speed_mps = 3.0;
  double stereo_weight = 1.0;          // exponent on the stereo likelihood

  // Throws lookout::InputError naming the first field out of range.
  void Validate(const std::string& source = "filter options") const;
};

}  // namespace lookout::grid
