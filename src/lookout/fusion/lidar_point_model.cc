#include "lookout/fusion/lidar_point_model.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "lookout/core/planar_geometry.h"
#include "lookout/core/pose2.h"
#include "lookout/stereo/oriented_box.h"
#include "lookout/stereo/stereo_point.h"

namespace lookout::fusion {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

// A beam along the side would make its spacing on the side infinite: a cosine of incidence
// below this counts as this (as the segmentation's own spacing does).
constexpr double kMinCosineOfIncidence = 0.2;

void RequirePointModel(bool ok, const char* field, const char* what) {
  if (!ok) {
    throw std::invalid_argument(std::string("LidarPointModelOptions.") + field + ": " + what);
  }
}

// The heading variance of a segment `visible_m` long along `u` with the object's covariance:
// 12 times its offset variance over its length squared (the slope of a line fitted to evenly
// spread points).
double SegmentHeadingVariance(const Matrix2d& own, const Vector2d& u, double visible_m) {
  const Vector2d across(-u.y(), u.x());
  return 12.0 * across.dot(own * across) / (visible_m * visible_m);
}

// The segment's heading variance combined with the camera's `yaw_variance` (0: none): two
// measurements of one heading.
double CombinedHeadingVariance(double segment, double yaw_variance) {
  return yaw_variance > 0.0 ? 1.0 / (1.0 / segment + 1.0 / yaw_variance) : segment;
}

// Which side of `box` the truth's rule turns to the lidar: the side along `u` (the segment's)
// or the one across it, and the probability that it is the other under the box's centre and
// heading uncertainty. nullopt when the lidar is inside the box.
struct SideChoice {
  bool seen_faces = true;
  double other_side_probability = 0.0;
};
std::optional<SideChoice> ChooseSide(const stereo::OrientedBox& box,
                                     const Matrix2d& center_covariance, double heading_variance,
                                     const Vector2d& u, const Vector2d& lidar_origin_m) {
  const std::optional<stereo::FrontSegment> rule = stereo::FrontSegmentFacing(box, lidar_origin_m);
  if (!rule) return std::nullopt;
  const Vector2d rule_side = rule->end_m - rule->start_m;
  const Vector2d across(-u.y(), u.x());
  return SideChoice{
      std::abs(rule_side.dot(u)) >= std::abs(rule_side.dot(across)),
      stereo::OtherSideProbability(box, center_covariance, heading_variance, lidar_origin_m)};
}

// The moments of `front` with weight 1 - q and `back` with q; the ends of the likelier.
LidarSidePoint Mixture(const LidarSidePoint& front, const LidarSidePoint& back, double q) {
  LidarSidePoint out = q <= 0.5 ? front : back;
  const Vector2d difference = back.point_m - front.point_m;
  out.point_m = front.point_m + q * difference;
  out.covariance = (1.0 - q) * front.covariance + q * back.covariance +
                   q * (1.0 - q) * difference * difference.transpose();
  return out;
}

}  // namespace

void LidarPointModelOptions::Validate() const {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  RequirePointModel(positive(beam_spacing_rad), "beam_spacing_rad", "must be finite and > 0");
  RequirePointModel(std::isfinite(grid_cell_size_m) && grid_cell_size_m >= 0.0, "grid_cell_size_m",
                    "must be finite and >= 0");
  RequirePointModel(std::isfinite(max_round_diameter_m) && max_round_diameter_m >= 0.0,
                    "max_round_diameter_m", "must be finite and >= 0");
  RequirePointModel(std::isfinite(round_square_tolerance_m) && round_square_tolerance_m >= 0.0,
                    "round_square_tolerance_m", "must be finite and >= 0");
  RequirePointModel(std::isfinite(corner_min_segment_m) && corner_min_segment_m >= 0.0,
                    "corner_min_segment_m", "must be finite and >= 0");
  RequirePointModel(std::isfinite(camera_size_sigma_m) && camera_size_sigma_m >= 0.0,
                    "camera_size_sigma_m", "must be finite and >= 0");
  RequirePointModel(positive(range_sigma_m), "range_sigma_m", "must be finite and > 0");
  RequirePointModel(camera_side_max_angle_rad >= 0.0 && camera_side_max_angle_rad <= 0.5 * kPi,
                    "camera_side_max_angle_rad", "must be in [0, pi/2]");
  const auto footprint = footprints.FirstInvalidField();
  RequirePointModel(!footprint, footprint.value_or(""), "must be finite and > 0");
}

double EndResolutionVariance(double beam_spacing_m, double cell_size_m) {
  const double one_end = (beam_spacing_m * beam_spacing_m + cell_size_m * cell_size_m) / 12.0;
  return 2.0 * one_end / 4.0;
}

double HiddenExtentVariance(double visible_m, double side_m) {
  const double hidden = std::max(0.0, side_m - visible_m);
  return hidden * hidden / 12.0;
}

double BoxHiddenExtentVariance(double visible_m, double length_m, double width_m) {
  const double longer = std::max(length_m, width_m);
  const double shorter = std::min(length_m, width_m);
  if (visible_m > shorter) return HiddenExtentVariance(visible_m, longer);
  const double p_length = 1.0 - (2.0 / kPi) * std::atan(shorter / longer);
  return p_length * HiddenExtentVariance(visible_m, longer) +
         (1.0 - p_length) * HiddenExtentVariance(visible_m, shorter);
}

Matrix2d RoundBodyCovariance(double radius_m, const Vector2d& ray, double depth_r) {
  const Vector2d along = ray.normalized();
  const Vector2d across(-along.y(), along.x());
  const double r2 = radius_m * radius_m;
  // E[(k - cos t)^2] = k^2 - 2 k E[cos t] + E[cos^2 t], E[cos t] = 2 sqrt 2 / pi,
  // E[cos^2 t] = 1/2 + 1/pi, t uniform on [-pi/4, pi/4].
  const double var_along =
      r2 * (depth_r * depth_r - 4.0 * std::sqrt(2.0) / kPi * depth_r + 0.5 + 1.0 / kPi);
  const double var_across = r2 * (0.5 - 1.0 / kPi);
  return var_along * along * along.transpose() + var_across * across * across.transpose();
}

ObjectClass MostLikelyLidarClass(const LidarObject& object) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < object.class_pmf.size(); ++i) {
    if (object.class_pmf[i] > object.class_pmf[best]) best = i;
  }
  return kAllObjectClasses[best];
}

std::optional<double> RoundBodyRadius(const PairedBody& body,
                                      const LidarPointModelOptions& options) {
  const double larger = std::max(body.length_m, body.width_m);
  const bool boxed = std::isfinite(larger) && larger > 0.0;
  if (!boxed) {
    if (body.object_class != ObjectClass::kPedestrian) return std::nullopt;
    return options.footprints.pedestrian_radius_m;
  }
  // The shape decides: a car the camera calls a pedestrian is no circle either.
  if (larger > options.max_round_diameter_m) return std::nullopt;
  if (body.object_class != ObjectClass::kPedestrian &&
      std::abs(body.length_m - body.width_m) > options.round_square_tolerance_m) {
    return std::nullopt;
  }
  return 0.5 * larger;
}

LidarObject ReadAsBody(const LidarObject& object, const PairedBody& body,
                       const LidarPointModelOptions& options) {
  LidarObject read = object;
  if (object.has_arc_reading && options.round_body && RoundBodyRadius(body, options)) {
    read.SetFront(object.arc_reading);
  }
  return read;
}

Matrix2d LidarPointCovariance(const LidarObject& object, ObjectClass object_class,
                              const Vector2d& lidar_origin_m,
                              const LidarPointModelOptions& options) {
  return LidarPointCovariance(object, PairedBody{object_class, 0.0, 0.0}, lidar_origin_m, options);
}

Matrix2d LidarPointCovariance(const LidarObject& object, const PairedBody& body,
                              const Vector2d& lidar_origin_m,
                              const LidarPointModelOptions& options) {
  const ObjectClass object_class = body.object_class;
  Matrix2d covariance = object.point_covariance;
  const Vector2d ray = object.point_m - lidar_origin_m;
  const double range = ray.norm();
  if (!(range > 0.0) || !std::isfinite(range)) return covariance;
  const std::optional<double> radius = RoundBodyRadius(body, options);
  const bool radius_term = options.round_body && radius.has_value();
  if (radius_term) {
    covariance += RoundBodyCovariance(
        *radius, ray, object.cell_count == 0 ? kSegmentationRoundBodyDepth : kGridRoundBodyDepth);
  }
  const Vector2d segment = object.front_end_m - object.front_start_m;
  const double visible = segment.norm();
  const Vector2d beam = ray / range;
  // The side's direction; a segment of one cell runs across the ray.
  const Vector2d u = visible > 1e-9 ? Vector2d(segment / visible) : Vector2d(-beam.y(), beam.x());
  // The segmentation bounds each end of its segment from the scan itself (the next beam past
  // it, or the shadow hiding it); the grid's ends are cells at its extreme bearings, bounded
  // by nothing the grid reports.
  if (!options.grid_extent || object.cell_count == 0) {
    // The scan's bounds can be wrong where the camera measures the side longer than the
    // segment: the rest of it is hidden at one end or the other.
    const double side = body.facing_side_m.norm();
    if (options.camera_side && !radius_term && side > 0.0) {
      const double cos_to_facing = std::abs(u.dot(body.facing_side_m)) / side;
      if (visible < options.corner_min_segment_m) {
        // Too short for its direction to be the side's (two or three returns centimetres
        // apart, their line the range noise's): the spread the scan puts along it may lie
        // along the camera's side as well.
        const Vector2d f = body.facing_side_m / side;
        covariance += u.dot(object.point_covariance * u) * f * f.transpose();
      } else if (cos_to_facing >= std::cos(options.camera_side_max_angle_rad)) {
        covariance += HiddenExtentVariance(visible, side) * u * u.transpose();
      } else if (cos_to_facing > std::sin(options.camera_side_max_angle_rad)) {
        // Oblique to both of the box's sides: a chord across a corner, too short to split
        // into an L. It covers its projection of the facing side; the rest is hidden.
        const Vector2d f = body.facing_side_m / side;
        covariance += HiddenExtentVariance(visible * cos_to_facing, side) * f * f.transpose();
      }
      if (options.side_heading && visible >= options.corner_min_segment_m) {
        // The spread along the segment lies along the true side, which the segment's heading
        // misses by its error (LidarPointModelOptions::side_heading).
        const Vector2d v(-u.y(), u.x());
        covariance +=
            u.dot(covariance * u) *
            CombinedHeadingVariance(SegmentHeadingVariance(object.point_covariance, u, visible),
                                    body.yaw_variance) *
            v * v.transpose();
      }
    }
    return covariance;
  }
  const double cos_incidence = std::abs(Cross(beam, u));
  const double spacing =
      range * options.beam_spacing_rad / std::max(cos_incidence, kMinCosineOfIncidence);
  double var_along = EndResolutionVariance(spacing, options.grid_cell_size_m);
  switch (object_class) {
    case ObjectClass::kPedestrian:
      var_along += HiddenExtentVariance(visible, 2.0 * options.footprints.pedestrian_radius_m);
      break;
    case ObjectClass::kCyclist:
    case ObjectClass::kCar:
    case ObjectClass::kTruck: {
      const ClassFootprints::Box b = options.footprints.BoxOf(object_class);
      var_along += BoxHiddenExtentVariance(visible, b.length_m, b.width_m);
      break;
    }
    case ObjectClass::kUnknown:
    case ObjectClass::kPole:
      break;
  }
  covariance += var_along * u * u.transpose();
  return covariance;
}

ArcCentre ArcPieceCentre(double radius_m, double chord_m, int returns, double start_min_m,
                         double start_max_m, double radius_step_m) {
  const double r = radius_m;
  const int n = std::max(1, returns);
  // The near half-circle's depth in front of the centre, integrated across:
  // int sqrt(r^2 - y^2) dy = (y sqrt(r^2 - y^2) + r^2 asin(y / r)) / 2.
  const auto integral = [](double rr, double y) {
    const double t = std::clamp(y / rr, -1.0, 1.0);
    return 0.5 * rr * rr * (t * std::sqrt(std::max(0.0, 1.0 - t * t)) + std::asin(t));
  };
  // The returns' mean depth in front of the centre for a piece starting at a (its n returns
  // evenly spaced over the chord, the first and the last at its ends: the beams sample the arc
  // evenly across the ray, and a few returns near the silhouette are not their continuous
  // mean), and the centre's offset across from the piece's middle. Beyond kDenseReturns the
  // sum by the trapezoid rule, (n - 1) / n of the integral's mean and the ends' halves, within
  // a millimetre of it (LidarPointModelTest.ArcPieceCentreIsWhereTheCircleIs), without a
  // square root per return.
  constexpr int kDenseReturns = 32;
  const auto depth_at = [](double rr, double y) {
    return std::sqrt(std::max(0.0, rr * rr - y * y));
  };
  const auto at = [&](double rr, double a) {
    double depth = 0.0;
    if (n > kDenseReturns && chord_m > 0.0) {
      const double mean = (integral(rr, a + chord_m) - integral(rr, a)) / chord_m;
      depth = (n - 1.0) / n * mean + (depth_at(rr, a) + depth_at(rr, a + chord_m)) / (2.0 * n);
    } else {
      for (int k = 0; k < n; ++k) {
        depth += depth_at(rr, n > 1 ? a + chord_m * k / (n - 1) : a + 0.5 * chord_m);
      }
      depth /= n;
    }
    return Vector2d(depth, -(a + 0.5 * chord_m));
  };
  constexpr int kSteps = 16;
  const auto moments = [&](double rr, double lo, double hi, Matrix2d* covariance) {
    Vector2d mean = Vector2d::Zero();
    Matrix2d second = Matrix2d::Zero();
    for (int k = 0; k < kSteps; ++k) {
      const Vector2d v = at(rr, lo + (hi - lo) * (k + 0.5) / kSteps);
      mean += v;
      second += v * v.transpose();
    }
    mean /= kSteps;
    if (covariance) *covariance = second / kSteps - mean * mean.transpose();
    return mean;
  };
  ArcCentre out;
  out.mean_m = moments(r, start_min_m, start_max_m, &out.covariance);
  // The centre's depth behind the returns as the radius grows by the step, the chord as seen
  // and the piece's place, anchored to the silhouette, scaled with it.
  const double dr = std::max(radius_step_m, 1e-4 * std::max(r, 1e-3));
  const double scale = (r + dr) / r;
  const double deeper = moments(r + dr, start_min_m * scale, start_max_m * scale, nullptr).x();
  out.depth_radius_slope = (deeper - out.mean_m.x()) / dr;
  return out;
}

namespace {

// Where the scan places the piece of a round body's arc it saw: an end seen free lies within a
// beam spacing of the circle's silhouette or short of it (the last returns at grazing
// incidence split off), an end hidden by something nearer may have the rest of the circle
// behind it. Where the hidden extent past one end can hold the whole of the diameter's missing
// part and past the other cannot, the piece is the silhouette's edge on that other side: the
// walker half behind another shows the edge that sticks out. That other end's silhouette lies
// within its own hidden extent, a beam spacing where the scan sees it free, more where a
// nearer body's shadow covers part of the way (a walker between two others: taken within a
// spacing, such pieces were 0.2-0.3 m off across against 0.04 m of sigma in the crowd).
// Where neither can, the piece lies between the two silhouettes, the missing part shared
// between its ends in a way the scan does not tell: anywhere on the near half-circle (for a
// whole arc, where nothing is missing, one place). Where both can, the rest may lie past
// either end or be shared between them: anywhere on the near half-circle too. That is most
// often a walker seen whole but for less than a beam spacing at each end (each free end's
// extent, a spacing, holds the little that is missing), and also a piece between two nearer
// bodies' shadows. Until 2026-12-06 both were taken a radius behind their middle instead: the
// whole arcs a few centimetres too deep where the grazing returns split off, the pieces
// between shadows as deep as the circle's flank, 0.13-0.17 m off along the ray against 3 cm of
// sigma in the crowd (docs/fusion.md, "Two bodies in one pair"). The chord is the piece's
// extent across the ray, clamped to the diameter; its returns, those on it.
struct ArcPiece {
  double chord_m = 0.0;
  double start_min_m = 0.0, start_max_m = 0.0;  // ArcPieceCentre's
  int returns = 0;
};
// `across`: the ray to the object turned a quarter left, unit.
ArcPiece PlacedArcPiece(const LidarObject& object, const Vector2d& across, double radius_m,
                        double spacing_m) {
  const double chord = std::clamp(std::abs((object.front_end_m - object.front_start_m).dot(across)),
                                  0.0, 2.0 * radius_m);
  const double missing = 2.0 * radius_m - chord;
  // The returns on the piece: the object's, but where the segmentation split an L and took one
  // leg for the front, only that leg's, a beam spacing apart across its chord. Counted whole,
  // the crowd's split arcs had side points at NEES 3.8 (docs/fusion.md, "Two bodies in one
  // pair").
  const int returns = std::min(static_cast<int>(object.point_count),
                               static_cast<int>(std::lround(chord / spacing_m)) + 1);
  // Such a leg (its chord under 0.85 of what the object's returns span a beam spacing apart)
  // has the L's corner for one end, not the arc's, which says nothing of where the silhouette
  // is. Placed by its hidden extents as a piece, the crowd's split arcs were at fused NEES 2.84
  // where whole ones were at 2.02.
  const double returns_span = (static_cast<double>(object.point_count) - 1.0) * spacing_m;
  if (object.point_count >= 3 && chord < 0.85 * returns_span) {
    return ArcPiece{chord, -radius_m, radius_m - chord, returns};
  }
  // The hidden extents past the piece's low and high ends across the ray.
  const bool start_low = (object.front_start_m - object.front_end_m).dot(across) <= 0.0;
  const double hidden_low = start_low ? object.hidden_start_m : object.hidden_end_m;
  const double hidden_high = start_low ? object.hidden_end_m : object.hidden_start_m;
  const bool low_holds = hidden_low >= missing;
  const bool high_holds = hidden_high >= missing;
  if (low_holds == high_holds) return ArcPiece{chord, -radius_m, radius_m - chord, returns};
  // The silhouette lies within the other end's hidden extent: a beam spacing where the scan
  // sees it free, less than the missing part (it does not hold).
  const double edge = std::min(std::max(spacing_m, low_holds ? hidden_high : hidden_low), missing);
  if (low_holds) return ArcPiece{chord, radius_m - chord - edge, radius_m - chord, returns};
  return ArcPiece{chord, -radius_m, -radius_m + edge, returns};
}

// The round body's point with the camera's heading (LidarPointModelOptions::round_body_heading,
// whose comment gives the model). `seen` where the camera gives no heading, the radius is
// unknown or the lidar would stand inside the square.
LidarSidePoint TurnedSquareSidePoint(const LidarObject& object, const LidarSidePoint& seen,
                                     const PairedBody& body, const Vector2d& lidar_origin_m,
                                     const LidarPointModelOptions& options) {
  const double facing = body.facing_side_m.norm();
  const std::optional<double> radius = RoundBodyRadius(body, options);
  const Vector2d ray = object.point_m - lidar_origin_m;
  const double range = ray.norm();
  if (!options.round_body || !options.round_body_heading || !(facing > 0.0) ||
      !(body.yaw_variance > 0.0) || !radius || !(range > 0.0) || !std::isfinite(range)) {
    return seen;
  }
  const Vector2d beam = ray / range;
  const Vector2d across(-beam.y(), beam.x());
  const bool grid = object.cell_count > 0;
  stereo::OrientedBox square;
  square.yaw_rad = std::atan2(body.facing_side_m.y(), body.facing_side_m.x());
  square.length_m = 2.0 * *radius;
  square.width_m = 2.0 * *radius;
  const double visible = (object.front_end_m - object.front_start_m).norm();
  const double spacing = grid ? options.grid_cell_size_m : range * options.beam_spacing_rad;
  const double noise = options.range_sigma_m * options.range_sigma_m;
  Matrix2d center_covariance;
  // A piece the scan places on the circle (PlacedArcPiece: at an edge, or between the two
  // silhouettes): the centre behind it as the circle puts it (ArcPieceCentre), not a radius
  // behind its middle. Its spread: the depth's and the offset's over where the piece lies, the
  // range noise on the mean of its n returns (along the ray, and across it, where the n
  // returns' chord places the centre), and the radius's error as the side's middle feels it.
  // Before, the crowd's pieces of two to four returns, mostly edges, were 0.14 m off across the
  // ray against 0.10 m of sigma, and 9 cm too deep (docs/fusion.md, "A walker's edge"); whole
  // arcs taken for a radius behind their middle were 3-5 cm too deep where the grazing returns
  // had split off, and the range noise of one return along and half of it across made the
  // well-seen walkers' points 3-10 times too wide in variance (docs/fusion.md, "A whole arc's
  // centre").
  // The radius's error: half the camera's size error.
  const double radius_sigma = 0.5 * options.camera_size_sigma_m;
  double depth_radius_slope = kGridRoundBodyDepth;
  const std::optional<ArcPiece> piece =
      grid ? std::nullopt : std::optional(PlacedArcPiece(object, across, *radius, spacing));
  if (piece) {
    const ArcCentre centre = ArcPieceCentre(*radius, piece->chord_m, piece->returns,
                                            piece->start_min_m, piece->start_max_m, radius_sigma);
    const double returns = std::max(1, piece->returns);
    depth_radius_slope = centre.depth_radius_slope;
    square.center_m = object.point_m - object.round_body_shift_m + centre.mean_m.x() * beam +
                      centre.mean_m.y() * across;
    Matrix2d own = centre.covariance;
    own(0, 0) += noise / returns;
    own(1, 1) += noise / returns;
    Matrix2d axes;
    axes.col(0) = beam;
    axes.col(1) = across;
    center_covariance = axes * own * axes.transpose();
  } else {
    // The grid's object (cells, no returns to place on the circle): the centre
    // kGridRoundBodyDepth radii behind the point; its covariance, the arc's own: along the ray
    // the range noise and a cell's width; across it the unseen rest of the diameter, the range
    // noise's share at the chord's two ends and a cell's width. The radius's error comes
    // below, once the square's facing side is known.
    square.center_m = object.point_m + kGridRoundBodyDepth * *radius * beam;
    const double var_along = noise + spacing * spacing / 12.0;
    const double var_across =
        HiddenExtentVariance(visible, 2.0 * *radius) + 0.5 * noise + spacing * spacing / 24.0;
    center_covariance =
        var_along * beam * beam.transpose() + var_across * across * across.transpose();
  }
  const std::optional<stereo::FrontSegment> front =
      stereo::FrontSegmentFacing(square, lidar_origin_m);
  if (!front) return seen;
  // The radius's error as the side's middle feels it: the centre moves depth_radius_slope
  // times it away from the lidar (kGridRoundBodyDepth for the grid's point; where the circle
  // puts it behind the scan's piece, ArcPieceCentre) and the side's middle the radius back
  // towards it along its normal, so it moves by slope beam + m per metre of radius (m: from the
  // centre to the facing side's middle): little along the ray where a whole arc's square faces
  // the lidar square on, and across it where the square is turned. Taken whole along the ray
  // it made the walkers' side points 2-4 times too wide there (docs/fusion.md, "A whole arc's
  // centre"); taken along the ray only, for the scan's pieces, a turned square's side was
  // 1.5 times too narrow across (docs/fusion.md, "Two bodies in one pair").
  const Vector2d radius_slope =
      depth_radius_slope * beam + (front->midpoint_m - square.center_m) / *radius;
  center_covariance += radius_sigma * radius_sigma * radius_slope * radius_slope.transpose();
  // A chord longer than the diameter holds another body at one end or the other (a child
  // 6 cm from a pushchair, one segment to the scan): this body anywhere along it.
  if (visible > 2.0 * *radius) {
    const Vector2d u = (object.front_end_m - object.front_start_m) / visible;
    center_covariance += HiddenExtentVariance(2.0 * *radius, visible) * u * u.transpose();
  }
  // A segment deeper along the ray than a radius is no arc of one circle (an arc's returns lie
  // within a radius of its nearest point in depth): another body stands in it, nearer or
  // further (a lamp post in front of a walker in the crowd, one segment to the scan), and this
  // body's side lies at either end of that depth, which the camera's depth cannot tell.
  const double depth_extent = std::abs((object.front_end_m - object.front_start_m).dot(beam));
  if (!grid && depth_extent > *radius) {
    center_covariance += 0.25 * depth_extent * depth_extent * beam * beam.transpose();
  }
  stereo::HeadingShare share;
  const std::optional<stereo::CartesianPoint> side = stereo::ExpectedFrontPoint(
      square, center_covariance, body.yaw_variance, lidar_origin_m, &share);
  if (!side) return seen;
  // The square's facing side as the front, so that its normal, a radius behind the middle,
  // leads to the square's centre (the tracking stage's centre of a walker).
  return LidarSidePoint{side->point_m, side->covariance, front->start_m, front->end_m, share};
}

}  // namespace

LidarSidePoint FacingSidePoint(const LidarObject& object, const PairedBody& body,
                               const Vector2d& lidar_origin_m,
                               const LidarPointModelOptions& options) {
  return FacingSidePoint(object, LidarPointCovariance(object, body, lidar_origin_m, options), body,
                         lidar_origin_m, options);
}

LidarSidePoint FacingSidePoint(const LidarObject& object, const Matrix2d& point_covariance,
                               const PairedBody& body, const Vector2d& lidar_origin_m,
                               const LidarPointModelOptions& options) {
  const bool round = RoundBodyRadius(body, options).has_value();
  // A segment the scan took for a round body's arc, moved to its nearest point, goes back where
  // the returns put it when the camera's box is no circle.
  const Vector2d unmoved = round ? Vector2d::Zero() : Vector2d(-object.round_body_shift_m);
  LidarSidePoint seen{object.point_m + unmoved,
                      point_covariance,
                      object.front_start_m + unmoved,
                      object.front_end_m + unmoved,
                      {}};
  const double facing = body.facing_side_m.norm();
  if (round) return TurnedSquareSidePoint(object, seen, body, lidar_origin_m, options);
  if (!options.corner_view || !(facing > 0.0)) return seen;
  const Vector2d segment = object.front_end_m - object.front_start_m;
  const double visible = segment.norm();
  if (!(visible >= options.corner_min_segment_m) || visible <= 0.0) return seen;
  const Vector2d along_segment = segment / visible;
  const double cos_to_facing = std::abs(along_segment.dot(body.facing_side_m)) / facing;
  const bool along_facing = cos_to_facing >= std::cos(options.camera_side_max_angle_rad);
  const bool across_facing = cos_to_facing <= std::sin(options.camera_side_max_angle_rad);
  if (!along_facing && !across_facing) return seen;
  // The segment's heading and offset, from its own covariance.
  const Vector2d across_segment(-along_segment.y(), along_segment.x());
  const Matrix2d& own = object.point_covariance;
  const double offset_variance = across_segment.dot(own * across_segment);
  // The corner is the segment's end, the true corner anywhere in what the scan could not see
  // past it (up to what the camera's side leaves, below): the second moment about the end,
  // h^2 / 3, with the returns' own variance along besides. Where the source does not say,
  // twice the middle's variance along (the two ends' errors taken equal).
  const double along_variance = along_segment.dot(own * along_segment);
  double corner_variance = 2.0 * along_variance;
  const double segment_heading_variance = SegmentHeadingVariance(own, along_segment, visible);
  // The camera's heading of the same side, turned to the segment's sense; the two combined by
  // their variances (the segment's alone when the camera gives none).
  Vector2d camera_side = body.facing_side_m / facing;
  if (across_facing) camera_side = Vector2d(-camera_side.y(), camera_side.x());
  if (camera_side.dot(along_segment) < 0.0) camera_side = -camera_side;
  const double heading_variance =
      CombinedHeadingVariance(segment_heading_variance, body.yaw_variance);
  const double camera_weight =
      body.yaw_variance > 0.0
          ? segment_heading_variance / (segment_heading_variance + body.yaw_variance)
          : 0.0;
  const double turn =
      camera_weight * std::atan2(Cross(along_segment, camera_side), along_segment.dot(camera_side));
  const Vector2d u = Eigen::Rotation2Dd(turn) * along_segment;
  // The corner: the segment's end nearer to the lidar along the side.
  const double lidar_along = (lidar_origin_m - seen.front_start_m).dot(u);
  const double end_along = (seen.front_end_m - seen.front_start_m).dot(u);
  if (lidar_along >= 0.0 && lidar_along <= end_along) return seen;
  const Vector2d corner = lidar_along < 0.0 ? seen.front_start_m : seen.front_end_m;
  const Vector2d inward = lidar_along < 0.0 ? u : Vector2d(-u);
  Vector2d away(-u.y(), u.x());
  if (away.dot(corner - lidar_origin_m) < 0.0) away = -away;
  // The camera's sides: which lies along the segment, which across.
  const double across_side = std::abs(facing - body.length_m) <= std::abs(facing - body.width_m)
                                 ? body.width_m
                                 : body.length_m;
  const double seen_length = along_facing ? facing : across_side;
  const double other_length = along_facing ? across_side : facing;
  const double hidden = lidar_along < 0.0 ? object.hidden_start_m : object.hidden_end_m;
  if (hidden > 0.0) {
    const double corner_hidden = std::clamp(seen_length - visible, 0.0, hidden);
    corner_variance = corner_hidden * corner_hidden / 3.0 + along_variance;
  }
  const double half = 0.5 * other_length;
  const double size_variance = 0.25 * options.camera_size_sigma_m * options.camera_size_sigma_m;
  const LidarSidePoint other_side{
      corner + half * away,
      (corner_variance + half * half * heading_variance) * u * u.transpose() +
          (offset_variance + size_variance) * away * away.transpose(),
      corner,
      corner + other_length * away,
      {}};

  // The box on the segment, and the truth's rule on it.
  stereo::OrientedBox box;
  box.center_m = corner + 0.5 * seen_length * inward + half * away;
  const Vector2d length_axis = seen_length >= other_length ? u : away;
  box.yaw_rad = std::atan2(length_axis.y(), length_axis.x());
  box.length_m = std::max(seen_length, other_length);
  box.width_m = std::min(seen_length, other_length);
  const Matrix2d center_covariance = corner_variance * u * u.transpose() +
                                     offset_variance * away * away.transpose() +
                                     size_variance * Matrix2d::Identity();
  const std::optional<SideChoice> choice =
      ChooseSide(box, center_covariance, heading_variance, u, lidar_origin_m);
  if (!choice) return seen;
  return Mixture(choice->seen_faces ? seen : other_side, choice->seen_faces ? other_side : seen,
                 choice->other_side_probability);
}

}  // namespace lookout::fusion
