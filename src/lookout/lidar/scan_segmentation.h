#pragma once

// Segmentation of one scan into objects (seed 004 sections IV.C-D): "Objects are extracted
// from these laser hit points by a segmentation algorithm. Each segment found is considered as
// a separate object. An object is marked as dynamic if at least one of its constituting laser
// points is classified as dynamic ... We also calculate the polar coordinates of center of
// gravity (centroid) of each segment."
//
// Clusters: consecutive returns in beam order, split where two neighbours are further apart
// than the adaptive breakpoint distance of Borges and Aldon (2004, "Line extraction in 2D range
// images for mobile robotics"):
//   D_max = r_prev sin(dphi) / sin(lambda - dphi) + k sigma_r,
// dphi the angle between the two beams: the distance two returns of one surface can be apart
// when the surface is seen at grazing incidence lambda, plus the range noise. It grows with
// range as beams spread. Up to max_gap_beams missing returns (dropouts, NaN) may lie between
// two points of one cluster; dphi then spans the gap. Beyond the paper: a step within D_max
// with twice its noise term is the noise's where the cluster's line and the returns' after it
// agree (SegmentationOptions::join_noise_breaks).
//
// Per cluster (a LidarObject, vehicle frame):
//   front segment  the total-least-squares line of the points, split once at the point
//                  furthest from it when the points form an L (two sides of a box); the front
//                  is the side the ray from the box's centre to the lidar leaves through, as
//                  stereo::FrontSegmentFacing defines it for the camera and the truth. A small
//                  L symmetric in its returns is a round body's arc: kept whole, moved towards
//                  the lidar to the body's nearest point. Its ends are the projections of its
//                  first and last points on the line. A small L a circle fits within the
//                  noise carries that arc's reading too (arc_reading), for the camera to choose.
//   point_m        the front segment's middle; covariance from the range and bearing noise
//                  (the line's offset, sigma_r^2 / n across it) and from where the ends really
//                  are, along it: the object's edge lies anywhere between the last return on
//                  it and the first beam that would have seen the side go on, one beam spacing
//                  past an end seen free, up to the far edge of the shadow of whatever nearer
//                  hides an end (or max_side_length_m less what is seen);
//   centroid       mean of the points; range and bearing of it from the lidar's origin;
//   extent         the points' bounding rectangle in the front segment's axes (a box seen on
//                  one or two sides gets its sides' directions);
//   velocity       none: one scan says nothing of motion. Zero with velocity_unknown_sigma_mps
//                  on each axis, so fusion and tracking give it no weight;
//   dynamic        any point dynamic (the paper's rule);
//   class          unknown (a scan's outline does not tell a pedestrian from a pole).
// Listed: the dynamic objects (the paper's list) and those the map has not seen yet
// (SegmentationOptions::report_unmapped), or every object (dynamic_only false).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/lidar/hit_classification.h"

namespace lookout::lidar {

struct SegmentationOptions {
  // Borges-Aldon: the grazing incidence angle beyond which a surface is split, the range noise
  // of the scanner (1-sigma) and the noise multiple.
  double breakpoint_incidence_rad = 10.0 * kPi / 180.0;
  double range_noise_m = 0.03;
  double breakpoint_noise_sigmas = 3.0;
  // Two neighbouring returns the map calls one static and the other not (dynamic, or unknown:
  // a walker's edge return in cells the map has not settled), further apart than this, are two
  // objects whatever Borges-Aldon's distance allows: a walker passing behind
  // a lamp post 0.5 m nearer at 17.6 m is within D_max (0.54 m there), and one cluster of the
  // two gave the walker's camera object the post's face as its lidar point
  // (docs/fusion.md). Within one body neighbouring returns lie closer (a walker's arc: a few
  // centimetres at that range). 0: off.
  double class_break_m = 0.3;
  // A break the noise could have made (beyond Borges and Aldon's distance, within it with
  // twice its noise term) parts nothing where the cluster's line and the returns' after it
  // predict each other within breakpoint_noise_sigmas of the noise: a side seen from a few
  // decimetres, its returns a millimetre apart, otherwise comes apart wherever two neighbours'
  // range noise differs by more than the noise term (scan_segmentation.cc,
  // OneSurfaceAcrossTheBreak; docs/lidar-chain.md).
  bool join_noise_breaks = true;
  // Missing returns (no return, NaN) bridged inside one cluster.
  int max_gap_beams = 2;
  // Clusters with fewer returns are dropped (a lone return is noise as often as an object).
  int min_points = 2;
  // A cluster is split into two sides when a point lies further than this from the line of
  // all its points and further than breakpoint_noise_sigmas range sigmas, as rare from the
  // noise of all its n returns as that many sigmas is of one (n P(|z| > d / sigma_r) at most
  // P(|z| > k): 4.6 sigmas for 600 returns).
  double corner_split_m = 0.1;
  // ... and when one of the two sides is at least this long. A round body (a pedestrian, a
  // pole) shows an arc that bends by its radius, whose halves are chords under r sqrt 2
  // (0.49 m for the catalogue's widest pedestrian, r = 0.35 m): its point is the whole arc's
  // middle. The boxes' long sides are 1.8 m (a cyclist) and more.
  double min_box_side_m = 0.7;
  // Whether a small L's corner lies mid-way through its returns (an arc) is judged, where its
  // two chords from the ends are within arc_max_chord_ratio of each other, at the middle of the
  // returns within arc_top_sigmas range sigmas of the furthest one's distance from the chord:
  // on an arc's flat top the noise picks the furthest anywhere (within 2 sigmas of it over +-37
  // degrees of a half circle of r = 0.3 m, whose chords there are within a factor of 2). 0:
  // the furthest return alone, as before 2026-12-05.
  double arc_top_sigmas = 2.0;
  double arc_max_chord_ratio = 2.0;
  // A small L (both sides under min_box_side_m) that is no arc by the balance above is read as
  // an arc as well (LidarObject::arc_reading) where a circle through its returns, bulging
  // towards the lidar, leaves residuals the range noise makes with at least this probability
  // (a chi-square of n - 3 degrees of freedom). A walker half hidden by another shows part of
  // its arc, whose furthest return from the chord is off the middle of its returns: of the
  // crowd's 114 small Ls, most are such arcs. 0: off.
  double arc_reading_probability = 0.99;
  // Report only the dynamic objects (the paper's list, IV.D); false keeps static ones too.
  bool dynamic_only = true;
  // With dynamic_only, report the unmapped objects too (every return unknown: on cells the map
  // has not seen, or not often enough to say), not dynamic (LidarObject::dynamic false).
  // Why: the map cannot yet say whether they move, but the camera can say what they are. At
  // t = 0 the map is empty and every return unknown; the crowd's walkers the camera saw then
  // were camera-only detections, confirmed after three updates where a pair of both sensors is
  // confirmed after one (tracking/track_management.h). Beyond the paper, whose list holds
  // dynamic objects only. Alone they make no track: the tracking stage leaves out a lidar-only
  // object that is not dynamic (app/tracking_stage.h).
  bool report_unmapped = true;
  // The longest side an object is taken to have (a car's length): a side hidden in part by
  // something nearer, or running out of the field of view, goes on at most this far less
  // what is seen. Bounds the point's variance along the side.
  double max_side_length_m = 5.0;
  // 1-sigma of each velocity axis of an object that has no velocity estimate.
  double velocity_unknown_sigma_mps = 100.0;

  void Validate(const std::string& source = "lidar segmentation options") const;
};

// Borges-Aldon's D_max (core/breakpoint_distance.h) for two returns dphi apart, the first at
// range r_prev, with the options' incidence and noise.
double BreakpointDistance(double r_prev_m, double dphi_rad, const SegmentationOptions& options);

// One cluster: the beams it holds, first to last, in scan order.
struct ScanCluster {
  std::vector<std::size_t> beams;
};

struct SegmentationStats {
  std::int64_t clusters = 0;
  std::int64_t dropped_small = 0;  // under min_points
  std::int64_t no_returns = 0;     // beams that were not returns
};

// Whether return `i` stands: static in `classes` and not on a mover's own trace
// (`on_moving_trace`, one per beam or empty: none is).
inline bool IsStanding(std::span<const HitClass> classes,
                       std::span<const std::uint8_t> on_moving_trace, std::size_t i) {
  return classes[i] == HitClass::kStatic &&
         !(i < on_moving_trace.size() && on_moving_trace[i] != 0);
}

// The clusters of `scan` (every return, whatever its class); `classes` (one per beam, or empty:
// none known) only splits at class_break_m. Pure; O(beams).
// `on_moving_trace` (one per beam, or empty): static returns on a mover's own trace
// (StaticOnMovingTrace), which the class break takes for the mover's.
std::vector<ScanCluster> ClusterScan(const LidarScan& scan, std::span<const HitClass> classes,
                                     const SegmentationOptions& options, double min_range_m,
                                     SegmentationStats* stats = nullptr,
                                     std::span<const std::uint8_t> on_moving_trace = {});

// Whether any beam of `cluster` is dynamic in `classes` (empty: none is).
bool HasDynamicBeam(const ScanCluster& cluster, std::span<const HitClass> classes);

// Whether every beam of `cluster` is unknown in `classes` (false for empty `classes`).
bool IsUnmapped(const ScanCluster& cluster, std::span<const HitClass> classes);

// The objects of `clusters` of `scan` (ClusterScan), described as above.
LidarObjectFrame DescribeClusters(const LidarScan& scan, std::span<const ScanCluster> clusters,
                                  std::span<const HitClass> classes, const Pose2& ego_pose,
                                  const SegmentationOptions& options);

// The objects of one scan: cluster, then describe each (see above). `classes` holds one class
// per beam (ClassifyHits); an empty span means "unknown" for every return, for a caller
// without a map. The frame is stamped with the scan, carries its mount and `ego_pose` (the
// vehicle in the odometry frame). Ids count from 1 in scan order. Pure.
LidarObjectFrame SegmentScan(const LidarScan& scan, std::span<const HitClass> classes,
                             const Pose2& ego_pose, const SegmentationOptions& options,
                             double min_range_m, SegmentationStats* stats = nullptr);

}  // namespace lookout::lidar
