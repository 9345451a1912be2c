#pragma once

// How far a lidar object's point (the middle of its front segment) may lie from the point it
// stands for, the middle of the object's side facing the lidar (docs/fusion.md, "The lidar
// point's covariance"). Each source reports what its own measurement knows: the segmentation
// the range noise and the segment's hidden ends, the grid a cell's quantisation and its cells'
// spread. What the scan cannot tell is added here, term by term, each a pure function of the
// object's geometry and its class:
//   - the ends' resolution: a grid object's ends are cell centres of its extreme bearings, its
//     true edge up to a beam spacing past the last return and anywhere in the end cell;
//   - the hidden extent: a grid object seen over less than its class's typical side has the
//     rest hidden at one end or the other (the segmentation measures this from the scan);
//   - the round body: a pedestrian is a circle to the laser, whose visible arc's middle is not
//     the middle of the 2r square side the truth and the camera take, along the heading;
//   - the camera's side: a segment shorter than the side the camera's box turns to the lidar
//     has the rest of that side hidden at one end or the other, wherever the scan put its ends;
//     a chord oblique to both of the box's sides covers only its projection of that side; a
//     piece too short for its direction to be the side's spreads along the side as along it.
// FacingSidePoint goes further where the segment is another side of the box (a corner view).
// FuseObjects applies it to the objects the camera paired, with the camera's class and box (it
// classifies from appearance and measures the size; a segmentation object has no class of its
// own); an unknown class adds no class term.

#include <Eigen/Core>
#include <optional>

#include "lookout/core/class_footprint.h"
#include "lookout/core/messages.h"
#include "lookout/core/object_class.h"
#include "lookout/stereo/stereo_point.h"

namespace lookout::fusion {

struct LidarPointModelOptions {
  // The round body, for the pedestrians of either source. On since 2026-12-03, when the
  // segmentation's point for an arc became its nearest point: the pedestrians' fused NEES
  // 6-14 times nearer its band, their fused RMSE 18-29 % lower, and the crowd's tracking
  // better (docs/fusion.md, "The round body on by default").
  bool round_body = true;
  // The round body's square turned as the camera's box (FacingSidePoint): the truth's and the
  // camera's point for a pedestrian is the middle of the side of its 2r square, along its
  // heading, that faces the lidar. The camera measures the heading (the simulated one to 0.05
  // rad); without it RoundBodyCovariance spreads the side over a quarter turn (0.13 m across
  // the ray for r = 0.3 m, against 1.5 cm with the heading). With it the camera's square stands
  // on the arc's centre, depth_r radii beyond the lidar's point on the ray, and the point is
  // its facing side's middle (stereo::ExpectedFrontPoint: the heading's variance, and the other
  // side's chance near 45 degrees), from the centre's covariance of a round body's arc: the
  // range noise and the radius along the ray; across it the unseen rest of the diameter,
  // uniform at either end (HiddenExtentVariance of the chord against 2r: edge returns at
  // grazing incidence dropped or split off), and the ends' noise and beam spacing; a chord
  // longer than the diameter holds another body besides, this one anywhere along it. Not the
  // segment's own covariance: a two-return arc's direction is noise, and the hidden extents
  // along it (up to a car's side) put the camera's depth in charge where the lidar measured
  // it; in the crowd, a walker's camera object 1 m off so placed made a track of its own
  // (docs/fusion.md, "A walker's square turned by the camera's heading"). The scan's arc, or
  // a piece of it, has the centre where the circle puts it behind that piece
  // (ArcPieceCentre), across and in depth: at its edge where one end is in a nearer body's
  // shadow that could hide the rest and the other is not, anywhere on the near half-circle
  // otherwise. A grid object (cells, no returns) has it depth_r radii behind its point
  // (docs/fusion.md, "A walker's edge", "A whole arc's centre", "Two bodies in one pair").
  bool round_body_heading = true;
  // The scanner's range noise (1 sigma; the simulator's), for the round body's arc: a
  // LidarObject carries none.
  double range_sigma_m = 0.03;
  // The ends' resolution and the hidden extent, for the grid's objects. Off: on, right-turn-
  // cyclist's tracking IDF1 (grid objects) falls from 0.95 to 0.64 (docs/fusion.md, "The lidar
  // point's covariance").
  bool grid_extent = false;
  // The side the camera measures, for a body that is not round: a segment shorter than the
  // camera box's side facing the lidar has the rest of that side hidden at either end, the
  // hidden extent's spread with the camera's side length (HiddenExtentVariance). For the
  // segmentation's objects, whose ends the scan bounds, and the grid's while grid_extent is
  // off. A segment oblique to both of the box's sides (a corner's chord, too short to split
  // into an L: cyclist-crossing's largest NEES, 952, a 0.42 m chord 0.8 m from the side's
  // middle) covers its projection of the side, the rest hidden along the side; one shorter
  // than corner_min_segment_m has the spread the scan gave it along its direction along the
  // side too (a 2 cm piece of a cyclist at 3 m: NEES 160).
  bool camera_side = true;
  // The side's heading, with camera_side: the spread along a segment (its own and the camera
  // side's) lies along the true side, which the segment's heading misses by its error; across
  // the segment, the spread times the heading variance (the segment's, 12 times its offset
  // variance over its length squared, combined with the camera's). Not for segments shorter
  // than corner_min_segment_m (the spread along the camera's side holds them). Without it a
  // metre of hidden side stood on a line known to a hundredth of a radian and pinned the fused
  // point across it (intersafe-fig9's car, 1.84 m of its 4.5 m side: fused NEES 21 for an
  // error of 3 cm).
  bool side_heading = true;
  // ...when the segment runs along that side: within this angle of it. A segment across it is
  // another side (a corner view, FacingSidePoint); between the two, a chord.
  double camera_side_max_angle_rad = 0.5;
  // The corner view, for a body that is not round (FacingSidePoint): the side facing the
  // lidar judged on a box standing on the lidar's segment with the camera's sizes, and where
  // that is the side across the segment, its middle from the segment's corner. Not for
  // segments shorter than corner_min_segment_m, whose direction is the noise's.
  bool corner_view = true;
  double corner_min_segment_m = 0.25;
  // The camera box's sides' error (1 sigma), which the transferred point's half side carries.
  // The simulated camera's sizes are exact; a real one's are not, and it reports no variance.
  double camera_size_sigma_m = 0.1;
  // The scanner's angle between neighbouring beams (the simulator's 0.25 deg) and the grid's
  // cell size (GridOptions::cell_size_m): a LidarObject carries neither.
  double beam_spacing_rad = 0.25 * 3.14159265358979323846 / 180.0;
  double grid_cell_size_m = 0.15;
  // A class's typical footprint (core/class_footprint.h).
  ClassFootprints footprints;
  // A round body whatever the camera's class (RoundBodyRadius): the camera reports a circle as
  // its 2r square; a box whose sides differ by at most round_square_tolerance_m and whose
  // larger side is at most max_round_diameter_m is one. The simulated camera's boxes are exact;
  // a real one's sides would need the tolerance of its size noise.
  double max_round_diameter_m = 0.8;
  double round_square_tolerance_m = 0.05;

  // Throws std::invalid_argument naming the first field out of range.
  void Validate() const;
};

// The variance of a side's middle along the side when each of its two ends lies anywhere in a
// width of `beam_spacing_m` (past the last return: the edge is between it and the next beam)
// and, independently, of `cell_size_m` (the end cell's extent): each end's variance is
// (s^2 + c^2) / 12, the middle's a quarter of the sum of both ends'. m^2.
double EndResolutionVariance(double beam_spacing_m, double cell_size_m);

// The variance of the visible middle about the side's middle when `visible_m` of a side
// `side_m` long is seen and the rest, H = side - visible, lies hidden at either end in any
// share: the offset is uniform on [-H/2, H/2], H^2 / 12. Zero when the whole side is seen.
double HiddenExtentVariance(double visible_m, double side_m);

// The same for a box of `length_m` by `width_m` of which `visible_m` of the front is seen,
// the side unknown: longer than the width, it is the length side; else it is the width side or
// a length side in part, each by the chance a view from a uniformly random direction has its
// front on that side, 1 - (2/pi) atan(W / L) for the length (the side with the larger apparent
// extent is the front: L |sin| > W |cos|).
double BoxHiddenExtentVariance(double visible_m, double length_m, double width_m);

// The second moments of the lidar's point for a circle (radius `radius_m`) about the middle
// of the side facing the lidar of the 2r square along the body's heading, unknown and uniform.
// The lidar's point lies `depth_r` radii in front of the centre on the ray: the segmentation's
// is the arc's nearest point (1: scan_segmentation.h moves the returns' line there); the
// grid's the middle of its cells at their mean depth, which seen from afar, the beams sampling
// the arc evenly across the ray, is (pi / 4) r in front. The square's facing side has its
// normal within 45 deg of the ray, at an angle t uniform on [-pi/4, pi/4], its middle at
// r (cos t, sin t) in (along, across) ray axes. Along: r^2 E[(k - cos t)^2]
// = r^2 (k^2 - 4 sqrt 2 k / pi + 1/2 + 1/pi): 1.8 % of r^2 for k = 1, 2.1 % for pi / 4;
// across: r^2 E[sin^2 t] = r^2 (1/2 - 1/pi), 18 % of r^2 (0.13 m for r = 0.3 m). `ray` points
// from the lidar to the object (any length but zero); the covariance is in the same axes.
inline constexpr double kSegmentationRoundBodyDepth = 1.0;
inline constexpr double kGridRoundBodyDepth = 0.25 * kPi;
Eigen::Matrix2d RoundBodyCovariance(double radius_m, const Eigen::Vector2d& ray, double depth_r);

// The centre of a circle of radius `radius_m` seen as a piece of its near arc `chord_m` wide
// across the ray, `returns` returns evenly spaced over it, the piece's start anywhere in
// [start_min_m, start_max_m] (offsets from the centre across the ray, within [-r, r - chord]),
// uniformly: the centre's mean offset from the returns' mean (their mean depth, their chord's
// middle) and its covariance, in (along the ray away from the lidar, across it) axes, the across
// axis the ray turned a quarter left; and how far the centre lies behind the returns per metre
// of error in the radius, the chord as seen and the piece's place anchored to the silhouette:
// the secant over `radius_step_m` (the radius's own error, 1 sigma), not the derivative, which
// is infinite where the piece's end reaches the far silhouette (a return there lies at a depth
// that goes as the square root of the radius's change). A whole arc densely sampled: (pi / 4) r
// deep, across 0; an edge piece: shallower (0.15 m for 0.1 m of a 0.3 m circle), r - c / 2
// across.
struct ArcCentre {
  Eigen::Vector2d mean_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  double depth_radius_slope = 0.0;
};
ArcCentre ArcPieceCentre(double radius_m, double chord_m, int returns, double start_min_m,
                         double start_max_m, double radius_step_m);

// What the camera says of the body a lidar object was paired with: its class and its box's
// sides (0 when there is no box).
struct PairedBody {
  ObjectClass object_class = ObjectClass::kUnknown;
  double length_m = 0.0;
  double width_m = 0.0;
  // The box's side that faces the lidar (the camera's front segment, by the truth's rule),
  // from one end to the other; zero when unknown.
  Eigen::Vector2d facing_side_m = Eigen::Vector2d::Zero();
  // The box's heading variance (rad^2); 0 when unknown.
  double yaw_variance = 0.0;
};

// The radius of the body if it is round to the laser, nullopt if not: a pedestrian whose box
// is no wider than max_round_diameter_m, or a body of any class whose box is a small square
// (the options above); a box wider than that is no circle whatever the class. The camera names a
// class wrongly now and then (the simulated one in 1 of 10 objects) but measures the shape: a
// walker it calls a car or a pole is still a circle to the laser, and without this term its point's
// covariance was the segmentation's few square centimetres (the crowd's fused NEES: its 9 %
// misnamed walkers held half of the sum, docs/fusion.md, "A round body whatever its class").
// The radius is half the box's larger side; a pedestrian without a box has the footprint's.
std::optional<double> RoundBodyRadius(const PairedBody& body,
                                      const LidarPointModelOptions& options);

// The lidar object as the camera's body reads it: where the scan read a small L as a round
// body's arc too (LidarObject::has_arc_reading) and the body is round (RoundBodyRadius, with
// options.round_body), the arc, whole; else the object as it is. A walker half hidden by
// another shows part of its arc, which the segmentation takes for an L and one leg for the
// front: the crowd's such legs had fused points at NEES 2.8 where whole arcs had 2.0
// (docs/fusion.md, "A small L read as an arc"). Pure.
LidarObject ReadAsBody(const LidarObject& object, const PairedBody& body,
                       const LidarPointModelOptions& options);

// The lidar object's point covariance with the terms above added for an object paired with
// `body`, seen from `lidar_origin_m` (vehicle frame, as the object): the round body for round
// bodies (RoundBodyRadius), from either source; the ends' resolution and the hidden extent, by
// the body's class, for the grid's objects (cell_count > 0), whose ends the scan does not
// bound; else, for a body that is not round, the camera's side; each as `options` switches it.
// An object the terms do not apply to: its own covariance.
Eigen::Matrix2d LidarPointCovariance(const LidarObject& object, const PairedBody& body,
                                     const Eigen::Vector2d& lidar_origin_m,
                                     const LidarPointModelOptions& options);
// The same for a body known by its class alone (no box).
Eigen::Matrix2d LidarPointCovariance(const LidarObject& object, ObjectClass object_class,
                                     const Eigen::Vector2d& lidar_origin_m,
                                     const LidarPointModelOptions& options);

// A side's middle as the lidar measures it, and the side (its ends).
struct LidarSidePoint {
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
  Eigen::Vector2d front_start_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d front_end_m = Eigen::Vector2d::Zero();
  // What of the error the camera's heading makes, where the point was turned by it (a round
  // body's square): shared with the camera's own point (shared_heading.h). Zero elsewhere.
  stereo::HeadingShare heading_share;
};

// The lidar's estimate of the middle of the side facing it, for an object paired with `body`:
// the point the fusion takes. The segment is one side of the body; at a corner view another may
// face the lidar (a cyclist's 1.7 m side seen whole while its end, at a grazing angle, returned
// too few beams to make an L: right-turn-cyclist's largest NEES, 2,500-2,700, were such points
// 0.85 m along and 0.3 m across from the end's middle). Which side faces is judged by the
// truth's rule (stereo::FrontSegmentFacing) on a box standing on the segment: its side
// through the segment's corner (its end nearer to the lidar along the side), headed as the
// segment and the camera's box together say (below), running away from the lidar, with the
// camera's length and width (which of them lies along the segment: the
// camera's box's side that does, within camera_side_max_angle_rad). Not on the camera's box
// itself: its heading and depth are the camera's, tenths of a radian and metres, where the
// segment's heading is hundredths (with the camera's box, intersafe-fig8's oncoming truck, its
// front seen whole, took a third of its long side's middle: fused error 1.25 m). The other
// side's middle lies half its length from the corner. Its covariance: along the segment, the
// corner's (the true corner anywhere in what the scan could not see past the segment's end,
// LidarObject::hidden_start_m / hidden_end_m, up to what the camera's side leaves: h^2 / 3
// about the end, with the returns' own variance along; where the source does not say, twice
// the middle's variance along) and the half side turned by the heading error: the segment's (12
// times its offset variance over its length squared, the slope of a line fitted to evenly spread
// points) and the camera's heading, two measurements of one heading, combined by their variances,
// in the box's direction too (a 0.27 m piece of a car's front alone gave 3 rad of sigma, and
// pushchair-group's oncoming car, its front's middle seen right, half its long side's middle:
// fused error 0.87 m; a 0.42 m corner piece of cyclist-crossing's cyclist, 0.5 rad off its
// side, put the side's middle 0.7 m outside the body);
// across, the segment's offset and the half side's (camera_size_sigma_m / 2)^2. The box's side
// choice weighs 1 - q and the other q (stereo::OtherSideProbability with the corner's
// covariance and the segment's heading variance); the point is the mixture's moments, its ends
// the likelier side's. The segment itself when none of this applies: a round body, no box, a
// segment too short or oblique to both of the box's sides, or the lidar facing the segment
// between its ends (no end of it visible).
// First, a segment the scan moved as a round body's arc (LidarObject::round_body_shift_m) goes
// back where its returns put it when the camera's box is no circle (RoundBodyRadius): a box's
// end seen head on between a return on each side looks as round to the scan
// (right-turn-cyclist's cyclist 6 cm nearer than its end: NEES 52 and 42).
LidarSidePoint FacingSidePoint(const LidarObject& object, const PairedBody& body,
                               const Eigen::Vector2d& lidar_origin_m,
                               const LidarPointModelOptions& options);
// The same with the object's point covariance under the model already at hand
// (LidarPointCovariance with the same arguments): FuseObjects keeps it on the lidar object too.
// `object` itself keeps the covariance its source gave: the segment's heading and offset are
// read from it (handed an object whose covariance was the model's, right-turn-cyclist's fused
// NEES went 1.64 -> 1.20).
LidarSidePoint FacingSidePoint(const LidarObject& object, const Eigen::Matrix2d& point_covariance,
                               const PairedBody& body, const Eigen::Vector2d& lidar_origin_m,
                               const LidarPointModelOptions& options);

// The most likely class of a lidar object's pmf (the first of equal ones, unknown first): the
// class for objects the camera did not see, once the model is applied to them.
ObjectClass MostLikelyLidarClass(const LidarObject& object);

}  // namespace lookout::fusion
