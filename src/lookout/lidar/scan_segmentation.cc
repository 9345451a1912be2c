#include "lookout/lidar/scan_segmentation.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

#include "lookout/core/breakpoint_distance.h"
#include "lookout/core/chi_square.h"
#include "lookout/core/input_error.h"
#include "lookout/core/planar_geometry.h"

namespace lookout::lidar {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

// A cosine of incidence below this is treated as this: a beam along a surface would otherwise
// make the beam spacing on it infinite.
constexpr double kMinIncidenceCosine = 0.2;

struct Line {
  Vector2d mean = Vector2d::Zero();
  Vector2d direction = Vector2d::UnitX();  // unit, oriented from the first point to the last
};

// Total least squares: the principal axis of the points' scatter through their mean.
Line FitLine(std::span<const Vector2d> points) {
  Line line;
  for (const Vector2d& p : points) line.mean += p;
  line.mean /= static_cast<double>(points.size());
  if (points.size() < 2) return line;
  Matrix2d scatter = Matrix2d::Zero();
  for (const Vector2d& p : points) scatter += (p - line.mean) * (p - line.mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Matrix2d> eigen(scatter);
  line.direction = eigen.eigenvectors().col(1);  // the larger eigenvalue's
  if (line.direction.dot(points.back() - points.front()) < 0.0) line.direction = -line.direction;
  return line;
}

Vector2d Project(const Line& line, const Vector2d& p) {
  return line.mean + line.direction * line.direction.dot(p - line.mean);
}

// Each point's distance from the chord first-last (from the first point where the two ends
// coincide).
std::vector<double> ChordDistances(std::span<const Vector2d> points) {
  const Vector2d a = points.front();
  const Vector2d chord = points.back() - a;
  const double length = chord.norm();
  std::vector<double> distances;
  distances.reserve(points.size());
  for (const Vector2d& p : points) {
    const Vector2d d = p - a;
    distances.push_back(length > 0.0 ? std::abs(Cross(chord, d)) / length : d.norm());
  }
  return distances;
}

// The index of the inner point furthest from the chord (ChordDistances), and its distance.
std::pair<std::size_t, double> FurthestFromChord(std::span<const double> distances) {
  std::size_t best = 0;
  double best_distance = 0.0;
  for (std::size_t k = 1; k + 1 < distances.size(); ++k) {
    const double distance = distances[k];
    if (distance > best_distance) {
      best_distance = distance;
      best = k;
    }
  }
  return {best, best_distance};
}

// The cluster's points on its front side, seen from `lidar`: the half-open index range
// [begin, end), and whether the cluster is a round body's arc.
//
// An L is two sides of a box; the front is the side the truth and the camera take
// (stereo::FrontSegmentFacing): the one the ray from the box's centre to the viewer leaves
// through. Both sides of an L are seen end to end (a convex body hides nothing of the sides it
// shows), so the L is the box: the corner, the sides' directions and lengths, the centre half
// way along both. The ray leaves through side 1 (normal along side 2) when
// |u . d2| / (l2 / 2) >= |u . d1| / (l1 / 2), u from the centre to the viewer, d unit. Seen
// from afar this is the side that spans the larger angle; near, it is not (a cyclist 5 m
// ahead and aside shows more returns on its end than its side while the ray from its middle
// leaves through the side). An end hidden by something nearer makes its side look shorter,
// which only errs towards the other side where the two are close.
//
// A small L (both sides under min_box_side_m) whose corner lies mid-way through its returns is
// a round body's arc (a pedestrian, a pole): seen from outside, an arc is symmetric about the
// ray to its centre, and its halves' chords meet at a right angle as an L's sides do. A box's
// end seen nearly along its side shows the side over a few returns only (a cyclist head-on:
// its end and the start of its side, which grazes the beams and breaks off), so stays an L.
struct FrontSideRange {
  std::size_t begin = 0, end = 0;
  bool round_body = false;
  // A small L a circle fits too (SegmentationOptions::arc_reading_probability).
  bool arc_reading = false;
};

// Whether a circle through `points` bulging towards `lidar` (its centre further from the lidar
// than `corner`) leaves residuals the range noise alone would exceed with probability at least
// 1 - `probability`: their sum of squares under sigma_r^2 times the chi-square quantile of
// n - 3 degrees of freedom.
// Kasa's algebraic fit (x^2 + y^2 + D x + E y + F = 0 by least squares): closed form, and
// near the geometric fit for arcs of a quarter circle and more, which an L's two sides span;
// the test takes the geometric residuals of its circle. Three points fit any circle: false.
bool CircleFits(std::span<const Vector2d> points, const Vector2d& lidar, const Vector2d& corner,
                double range_noise_m, double probability) {
  const auto n = static_cast<Eigen::Index>(points.size());
  if (n < 4 || !(probability > 0.0)) return false;
  Eigen::MatrixX3d design(n, 3);
  Eigen::VectorXd rhs(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Vector2d& p = points[static_cast<std::size_t>(k)];
    design.row(k) << p.x(), p.y(), 1.0;
    rhs(k) = -p.squaredNorm();
  }
  const Eigen::Vector3d def = design.colPivHouseholderQr().solve(rhs);
  const Vector2d center = -0.5 * def.head<2>();
  const double radius_squared = center.squaredNorm() - def(2);
  if (!(radius_squared > 0.0) || !std::isfinite(radius_squared)) return false;
  if ((center - lidar).norm() <= (corner - lidar).norm()) return false;
  const double radius = std::sqrt(radius_squared);
  double residuals = 0.0;
  for (const Vector2d& p : points) {
    const double r = (p - center).norm() - radius;
    residuals += r * r;
  }
  return residuals <= range_noise_m * range_noise_m *
                          ChiSquareQuantile(probability, static_cast<double>(n) - 3.0);
}

// The middle index of the inner points within `tolerance_m` of `furthest_m` from the chord
// (ChordDistances, FurthestFromChord's distance).
std::size_t NearFurthestMiddle(std::span<const double> distances, double furthest_m,
                               double tolerance_m) {
  std::size_t first = 0, last = 0;
  bool any = false;
  for (std::size_t k = 1; k + 1 < distances.size(); ++k) {
    if (distances[k] >= furthest_m - tolerance_m) {
      if (!any) first = k;
      last = k;
      any = true;
    }
  }
  return (first + last) / 2;
}

FrontSideRange FrontSide(std::span<const Vector2d> points, const Vector2d& lidar,
                         const SegmentationOptions& options) {
  const FrontSideRange whole{0, points.size(), false, false};
  if (points.size() < 3) return whole;
  const std::vector<double> chord_distances = ChordDistances(points);
  const auto [corner, distance] = FurthestFromChord(chord_distances);
  const double threshold =
      std::max(options.corner_split_m, options.breakpoint_noise_sigmas * options.range_noise_m);
  if (distance <= threshold) return whole;
  // The furthest of n returns from a line lies beyond k sigma_r by noise alone about n times as
  // often as one return does: the corner must be as unlikely from the noise of all n as
  // k sigma_r is of one, n P(|z| > d / sigma_r) <= P(|z| > k). A side seen from 0.3 m, 600
  // returns under 3 cm of range noise, otherwise splits at one of them 10 cm off (3.3 sigma:
  // one return in a thousand) and its front is half of it.
  if (options.range_noise_m > 0.0) {
    const double z = distance / options.range_noise_m;
    if (static_cast<double>(points.size()) * std::erfc(z / std::sqrt(2.0)) >
        std::erfc(options.breakpoint_noise_sigmas / std::sqrt(2.0))) {
      return whole;
    }
  }
  // The corner belongs to both sides.
  const Vector2d side_1 = points.front() - points[corner];
  const Vector2d side_2 = points.back() - points[corner];
  const double l1 = side_1.norm();
  const double l2 = side_2.norm();
  // An arc's returns lie near the furthest distance from the chord over much of its middle,
  // so the noise picks the furthest anywhere there (SegmentationOptions::arc_top_sigmas): a
  // walker's whole arc seen from 10 m split at its fifth return of sixteen was taken for an L,
  // its first four returns dropped from the front and the side's middle 3-5 cm too deep. Where
  // the split is balanced as an arc's top would be, the returns' balance is judged at the
  // middle of the returns within that noise of the furthest; a cyclist's L seen end on, a side
  // three times its end, keeps its corner.
  const auto balanced = [&](std::size_t split) {
    const std::size_t returns_1 = split + 1;
    const std::size_t returns_2 = points.size() - split;
    return std::max(returns_1, returns_2) < 2 * std::min(returns_1, returns_2);
  };
  const bool arc_like_split = std::max(l1, l2) <= options.arc_max_chord_ratio * std::min(l1, l2);
  const bool arc = balanced(corner) ||
                   (arc_like_split &&
                    balanced(NearFurthestMiddle(chord_distances, distance,
                                                options.arc_top_sigmas * options.range_noise_m)));
  const bool small = std::max(l1, l2) < options.min_box_side_m;
  if (small && arc) return {0, points.size(), true, false};
  const Vector2d to_lidar = lidar - (points[corner] + 0.5 * (side_1 + side_2));
  const bool first_is_front =
      std::abs(to_lidar.dot(side_2)) * l1 * l1 >= std::abs(to_lidar.dot(side_1)) * l2 * l2;
  FrontSideRange front = first_is_front ? FrontSideRange{0, corner + 1, false, false}
                                        : FrontSideRange{corner, points.size(), false, false};
  front.arc_reading = small && CircleFits(points, lidar, points[corner], options.range_noise_m,
                                          options.arc_reading_probability);
  return front;
}

// Spacing of two neighbouring beams where they meet a surface of direction `along`, at range r.
double BeamSpacingOnSurface(const Vector2d& from_lidar, const Vector2d& along, double dphi_rad) {
  const double r = from_lidar.norm();
  if (r <= 0.0) return 0.0;
  const Vector2d beam = from_lidar / r;
  const double cos_incidence = std::abs(Cross(beam, along));
  return r * dphi_rad / std::max(cos_incidence, kMinIncidenceCosine);
}

// How far the object's edge may lie beyond the front segment's outer end `end_point` (the
// return of beam `end_beam`), stepping through the beams outward by `step` (+1 or -1) and along
// the side's line in the direction `outward`. A beam whose return lies nearer than the line
// (by more than the range noise) hides whatever is behind it, so the side may go on there; the
// first beam that returns at or behind the line, or returns nothing, bounds it: the edge lies
// between the end and that beam's crossing of the line. For an end seen free this is one beam
// spacing; past the scan's field of view, or where the line runs off the beams, `cap_m`.
double HiddenExtent(const LidarScan& scan, std::size_t end_beam, int step, const Line& line,
                    const Vector2d& end_point, const Vector2d& outward, double margin_m,
                    double cap_m) {
  const Vector2d lidar = scan.mount.translation;
  for (std::ptrdiff_t k = static_cast<std::ptrdiff_t>(end_beam) + step;
       k >= 0 && k < static_cast<std::ptrdiff_t>(scan.ranges_m.size()); k += step) {
    const std::size_t i = static_cast<std::size_t>(k);
    const double a = scan.mount.yaw + scan.BeamAngle(i);
    const Vector2d beam(std::cos(a), std::sin(a));
    const double denominator = Cross(beam, line.direction);
    if (std::abs(denominator) < 1e-9) return cap_m;
    const double lambda = Cross(line.mean - lidar, line.direction) / denominator;
    if (lambda <= 0.0) return cap_m;
    const double extent = outward.dot(lidar + lambda * beam - end_point);
    if (extent >= cap_m) return cap_m;
    const bool hidden =
        IsReturn(scan, i, 0.0) && static_cast<double>(scan.ranges_m[i]) < lambda - margin_m;
    if (!hidden) return std::max(extent, 0.0);
  }
  return cap_m;
}

// The front of a cluster's returns [begin, end) (FrontSide's, or the whole cluster read as an
// arc): its ends, middle and the middle's covariance, and how far each end may run on unseen;
// for a round body's arc, moved to the body's nearest point. `points`: the cluster's returns.
struct FrontRead {
  LidarObject::FrontReading reading;
  Vector2d direction = Vector2d::UnitX();  // the front's line, first return to last
};
FrontRead ReadFront(const LidarScan& scan, const ScanCluster& cluster,
                    std::span<const Vector2d> points, std::size_t begin, std::size_t end,
                    bool round_body, const SegmentationOptions& options) {
  const std::size_t n = points.size();
  LidarObject::FrontReading r;
  const std::span<const Vector2d> front(points.data() + begin, end - begin);
  const Line line = FitLine(front);
  r.front_start_m = Project(line, front.front());
  r.front_end_m = Project(line, front.back());
  r.point_m = 0.5 * (r.front_start_m + r.front_end_m);
  if (round_body) {
    // The point is the middle of the side facing the lidar, which for a round body is its
    // nearest point, r in front of its centre on the ray. The beams sample the arc evenly
    // across the ray, so the line through the returns' mean lies (pi / 4) r in front of the
    // centre: the segment moves (1 - pi / 4) r towards the lidar, r half its chord.
    const Vector2d from_lidar = r.point_m - scan.mount.translation;
    const double range = from_lidar.norm();
    const double radius = 0.5 * (r.front_end_m - r.front_start_m).norm();
    if (range > 0.0) {
      const Vector2d shift = -(1.0 - 0.25 * kPi) * radius / range * from_lidar;
      r.front_start_m += shift;
      r.front_end_m += shift;
      r.point_m += shift;
      r.round_body_shift_m = shift;
    }
  }

  // Covariance of the middle in the segment's axes (u along, v across).
  const Vector2d u = line.direction;
  const Vector2d v(-u.y(), u.x());
  const Vector2d lidar = scan.mount.translation;
  const double dphi = std::abs(scan.angle_increment_rad);
  const double sigma_r2 = options.range_noise_m * options.range_noise_m;
  // Where each end of the side really is: a corner (the L's) lies within one beam spacing of
  // its return; an outer end of the cluster lies anywhere between its last return and the
  // first beam that would have seen the side go on (HiddenExtent: one beam spacing where the
  // end is seen free, up to the shadow's far edge where something nearer hides it, capped at
  // max_side_length_m less what is seen). Each end's offset e_i, outward, uniform on [0, h_i];
  // the middle moves by (e_2 - e_1) / 2 along the side. The point stays the visible middle (a
  // shift by the mean would move a pedestrian half hidden by another by metres, for a prior of
  // car-sized sides), so its variance along is the offset's second moment about zero,
  // (h_1^2 + h_2^2) / 48 + (h_2 - h_1)^2 / 16, plus the range noise's component along the
  // surface at each end (below).
  const double seen_m = (r.front_end_m - r.front_start_m).norm();
  const double margin = options.breakpoint_noise_sigmas * options.range_noise_m;
  const auto extent = [&](bool at_start) {
    const std::size_t k = at_start ? begin : end - 1;
    const Vector2d& p = points[k];
    const double spacing = BeamSpacingOnSurface(p - lidar, u, dphi);
    const bool outer = at_start ? begin == 0 : end == n;
    if (!outer) return spacing;
    const double cap = std::max(spacing, options.max_side_length_m - seen_m);
    return HiddenExtent(scan, cluster.beams[k], at_start ? -1 : 1, line,
                        at_start ? r.front_start_m : r.front_end_m, at_start ? -u : u, margin, cap);
  };
  // The line runs from the front's first beam to its last (FitLine), so the start's outward
  // is -u, beam index down.
  const double h1 = extent(true);
  const double h2 = extent(false);
  r.hidden_start_m = h1;
  r.hidden_end_m = h2;
  // Each end is a return's projection on the line: its range noise, along the ray, moves it
  // along the side by sigma_r times the cosine between the ray and the side, and the middle by
  // half that. A side seen face on (a car's rear ahead) has almost none along it; before
  // 2026-12-06 each end took the whole sigma_r ("at most"), and the boxes' fused points were
  // too wide (right-turn-cyclist's pairs at NEES 1.16 but for one mispair at 40;
  // docs/fusion.md, "The range noise along a side").
  const auto along_share = [&](const Vector2d& p) {
    const Vector2d ray = p - lidar;
    const double range = ray.norm();
    return range > 0.0 ? u.dot(ray) / range : 1.0;
  };
  const double c1 = along_share(front.front());
  const double c2 = along_share(front.back());
  const double noise_along = sigma_r2 * (c1 * c1 + c2 * c2) / 4.0;
  const double var_along = (h1 * h1 + h2 * h2) / 48.0 + (h2 - h1) * (h2 - h1) / 16.0 + noise_along;
  const double var_across = sigma_r2 / static_cast<double>(front.size());
  Matrix2d axes;
  axes.col(0) = u;
  axes.col(1) = v;
  r.point_covariance =
      axes * Eigen::Vector2d(var_along, var_across).asDiagonal() * axes.transpose();

  return FrontRead{r, u};
}

LidarObject DescribeCluster(const LidarScan& scan, const ScanCluster& cluster,
                            std::span<const HitClass> classes, const SegmentationOptions& options) {
  std::vector<Vector2d> points;
  points.reserve(cluster.beams.size());
  LidarObject o;
  for (std::size_t i : cluster.beams) {
    points.push_back(ReturnPoint(scan, i));
    if (!classes.empty() && classes[i] == HitClass::kDynamic) o.dynamic = true;
  }
  const std::size_t n = points.size();
  o.point_count = static_cast<std::uint32_t>(n);

  const FrontSideRange side = FrontSide(points, scan.mount.translation, options);
  const FrontRead front =
      ReadFront(scan, cluster, points, side.begin, side.end, side.round_body, options);
  o.SetFront(front.reading);
  if (side.arc_reading) {
    o.has_arc_reading = true;
    o.arc_reading = ReadFront(scan, cluster, points, 0, n, true, options).reading;
  }
  const Vector2d u = front.direction;
  const Vector2d v(-u.y(), u.x());

  Vector2d centroid = Vector2d::Zero();
  for (const Vector2d& p : points) centroid += p;
  o.centroid_m = centroid / static_cast<double>(n);
  const Vector2d in_lidar = scan.mount.Inverse() * o.centroid_m;
  o.range_m = in_lidar.norm();
  o.bearing_rad = std::atan2(in_lidar.y(), in_lidar.x());

  double u_min = std::numeric_limits<double>::infinity(), u_max = -u_min;
  double v_min = u_min, v_max = -u_min;
  for (const Vector2d& p : points) {
    const double a = u.dot(p), b = v.dot(p);
    u_min = std::min(u_min, a);
    u_max = std::max(u_max, a);
    v_min = std::min(v_min, b);
    v_max = std::max(v_max, b);
  }
  o.length_m = u_max - u_min;
  o.width_m = v_max - v_min;
  o.yaw_rad = std::atan2(u.y(), u.x());
  if (o.width_m > o.length_m) {
    std::swap(o.length_m, o.width_m);
    o.yaw_rad = WrapAngle(o.yaw_rad + 0.5 * kPi);
  }

  o.velocity_mps = Vector2d::Zero();
  const double sigma_v = options.velocity_unknown_sigma_mps;
  o.velocity_covariance = Matrix2d::Identity() * (sigma_v * sigma_v);
  o.class_pmf.fill(0.0);
  o.class_pmf[static_cast<std::size_t>(ObjectClass::kUnknown)] = 1.0;
  return o;
}

}  // namespace

void SegmentationOptions::Validate(const std::string& source) const {
  auto check = [&](bool ok, const char* field, const char* problem) {
    if (!ok) throw InputError(source, 0, field, problem);
  };
  check(std::isfinite(breakpoint_incidence_rad) && breakpoint_incidence_rad > 0.0 &&
            breakpoint_incidence_rad < 0.5 * kPi,
        "breakpoint_incidence_rad", "must be in (0, pi/2)");
  check(std::isfinite(range_noise_m) && range_noise_m >= 0.0, "range_noise_m",
        "must be finite and >= 0");
  check(std::isfinite(breakpoint_noise_sigmas) && breakpoint_noise_sigmas >= 0.0,
        "breakpoint_noise_sigmas", "must be finite and >= 0");
  check(std::isfinite(class_break_m) && class_break_m >= 0.0, "class_break_m",
        "must be finite and >= 0");
  check(max_gap_beams >= 0, "max_gap_beams", "must be >= 0");
  check(min_points >= 1, "min_points", "must be >= 1");
  check(std::isfinite(corner_split_m) && corner_split_m > 0.0, "corner_split_m",
        "must be finite and > 0");
  check(std::isfinite(min_box_side_m) && min_box_side_m >= 0.0, "min_box_side_m",
        "must be finite and >= 0");
  check(std::isfinite(arc_top_sigmas) && arc_top_sigmas >= 0.0, "arc_top_sigmas",
        "must be finite and >= 0");
  check(std::isfinite(arc_max_chord_ratio) && arc_max_chord_ratio >= 1.0, "arc_max_chord_ratio",
        "must be finite and >= 1");
  check(std::isfinite(arc_reading_probability) && arc_reading_probability >= 0.0 &&
            arc_reading_probability < 1.0,
        "arc_reading_probability", "must be in [0, 1)");
  check(std::isfinite(max_side_length_m) && max_side_length_m > 0.0, "max_side_length_m",
        "must be finite and > 0");
  check(std::isfinite(velocity_unknown_sigma_mps) && velocity_unknown_sigma_mps > 0.0,
        "velocity_unknown_sigma_mps", "must be finite and > 0");
}

double BreakpointDistance(double r_prev_m, double dphi_rad, const SegmentationOptions& options) {
  return lookout::BreakpointDistance(r_prev_m, dphi_rad, options.breakpoint_incidence_rad,
                                     options.breakpoint_noise_sigmas * options.range_noise_m);
}

namespace {

// Whether the returns before a soft break (the cluster so far) and after it (up to the next
// hard break) lie on one line within the range noise: a side seen from a few decimetres, its
// returns a millimetre apart along it, parts wherever two neighbours' ranges differ by more
// than the noise term (3 sigma_r on one range, where the difference of two has sqrt 2 sigma_r:
// 3.4 % of neighbours; straight-crossing-path's car 0.25 m from the lidar before the contact
// came apart in ten pieces). A line seen from the origin is linear in inverse range:
// 1 / r = a cos(phi) + b sin(phi), exactly, for any line off the origin, the noise on r
// (sigma_r, so sigma_r / r^2 on 1 / r): each side's line, fitted by weighted least squares to
// its up to kJoinFitReturns returns next to the break, predicts the ranges of the other side's
// up to kJoinTestReturns returns next to it, whose mean difference must lie within
// noise_sigmas of its spread (the returns' sigma_r^2 / m and the line's at their mean
// bearing). A total-least-squares line would not do: a few centimetres of returns under 3 cm
// of range noise have no direction. Two bodies one behind the other differ in range by more
// than the noise of a few returns' mean; a leg's arc is no line.
constexpr std::size_t kJoinFitReturns = 50;
constexpr std::size_t kJoinTestReturns = 10;
// Fewer returns than this (besides the one at the break) have no line to speak of; with a lone
// return or two joined to a run (a walker's edge return beside a wall) the leg-tracker bag's
// real scans gave the MHT 51 false tracks against 27.
constexpr std::size_t kJoinMinReturns = 3;
bool OneSurfaceAcrossTheBreak(std::span<const Vector2d> before_break,
                              std::span<const Vector2d> after_break, double sigma_r,
                              double noise_sigmas) {
  // The two returns at the break are left out: the noise that parted them is in one or both.
  if (before_break.size() <= kJoinMinReturns || after_break.size() <= kJoinMinReturns) {
    return false;
  }
  const auto before = before_break.first(before_break.size() - 1);
  const auto after = after_break.subspan(1);
  const auto bearing = [](const Vector2d& p) { return Vector2d(p.normalized()); };
  const auto predicts = [&](std::span<const Vector2d> fit, std::span<const Vector2d> test) {
    // Weighted by each return's range as the line puts it: weights from the measured ranges
    // favour the returns the noise put further (r^4: +-12 % of noise on 0.25 m is +-50 % of
    // weight) and pull the line out by centimetres. A first pass weighs them all alike.
    Eigen::LDLT<Matrix2d> solver;
    Vector2d line = Vector2d::Zero();
    for (int pass = 0; pass < 2; ++pass) {
      Matrix2d information = Matrix2d::Zero();
      Vector2d moment = Vector2d::Zero();
      for (const Vector2d& p : fit) {
        const Vector2d g = bearing(p);
        const double predicted = pass == 0 ? 1.0 : 1.0 / line.dot(g);
        const double weight = std::pow(predicted, 4) / (sigma_r * sigma_r);
        information += weight * g * g.transpose();
        moment += weight * g / p.norm();
      }
      solver.compute(information);
      if (solver.info() != Eigen::Success || !(solver.rcond() > 1e-12)) return false;
      line = solver.solve(moment);
      if (!(line.dot(bearing(fit.front())) > 0.0 && line.dot(bearing(fit.back())) > 0.0)) {
        return false;
      }
    }
    double difference = 0.0;
    double mean_range = 0.0;
    Vector2d mean_bearing = Vector2d::Zero();
    for (const Vector2d& p : test) {
      const double inverse = line.dot(bearing(p));
      if (!(inverse > 0.0)) return false;  // the line does not run past this bearing
      difference += p.norm() - 1.0 / inverse;
      mean_range += p.norm();
      mean_bearing += bearing(p);
    }
    const double k = static_cast<double>(test.size());
    difference /= k;
    mean_range /= k;
    mean_bearing /= k;
    const double line_variance =
        std::pow(mean_range, 4) * mean_bearing.dot(solver.solve(mean_bearing));
    const double variance = sigma_r * sigma_r / k + line_variance;
    return difference * difference <= noise_sigmas * noise_sigmas * variance;
  };
  return predicts(before.last(std::min(before.size(), kJoinFitReturns)),
                  after.first(std::min(after.size(), kJoinTestReturns))) &&
         predicts(after.first(std::min(after.size(), kJoinFitReturns)),
                  before.last(std::min(before.size(), kJoinTestReturns)));
}

}  // namespace

std::vector<ScanCluster> ClusterScan(const LidarScan& scan, std::span<const HitClass> classes,
                                     const SegmentationOptions& options, double min_range_m,
                                     SegmentationStats* stats,
                                     std::span<const std::uint8_t> on_moving_trace) {
  // One standing (static, and not on a mover's trace) and one not (dynamic; unknown: a walker's
  // edge return in cells the map has not settled; static on a mover's trace: the mover's own):
  // the map tells the two apart.
  const auto classes_differ = [&](std::size_t a, std::size_t b) {
    if (classes.empty()) return false;
    const auto returned = [&](std::size_t i) { return classes[i] != HitClass::kNoReturn; };
    return returned(a) && returned(b) &&
           IsStanding(classes, on_moving_trace, a) != IsStanding(classes, on_moving_trace, b);
  };
  // Every return (sensor frame) and what lies between it and the one before: a hard break
  // (not bridged, a class break, or a step no noise could make: beyond the breakpoint distance
  // with twice its noise term, 6 sigma_r, 4.2 sigmas of two returns' difference), a soft one
  // (beyond the breakpoint distance alone), or none.
  enum class Break : std::uint8_t { kNone, kSoft, kHard };
  const double wide_noise_m = 2.0 * options.breakpoint_noise_sigmas * options.range_noise_m;
  std::vector<std::size_t> beams;
  std::vector<Vector2d> points;
  std::vector<Break> breaks;
  beams.reserve(scan.ranges_m.size());
  points.reserve(scan.ranges_m.size());
  breaks.reserve(scan.ranges_m.size());
  SegmentationStats local;
  const double dphi = std::abs(scan.angle_increment_rad);
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    if (!IsReturn(scan, i, min_range_m)) {
      ++local.no_returns;
      continue;
    }
    const double r = static_cast<double>(scan.ranges_m[i]);
    const double a = scan.BeamAngle(i);
    const Vector2d p(r * std::cos(a), r * std::sin(a));  // sensor frame
    Break kind = Break::kHard;
    if (!beams.empty()) {
      const std::size_t last = beams.back();
      const double r_prev = points.back().norm();
      const std::size_t gap = i - last;
      const double dphi_gap = static_cast<double>(gap) * dphi;
      const double step = (p - points.back()).norm();
      const bool bridged = gap <= static_cast<std::size_t>(options.max_gap_beams) + 1;
      const bool class_break =
          options.class_break_m > 0.0 && step > options.class_break_m && classes_differ(last, i);
      if (bridged && !class_break) {
        if (step <= BreakpointDistance(r_prev, dphi_gap, options)) {
          kind = Break::kNone;
        } else if (step <= lookout::BreakpointDistance(
                               r_prev, dphi_gap, options.breakpoint_incidence_rad, wide_noise_m)) {
          kind = Break::kSoft;
        }
      }
    }
    beams.push_back(i);
    points.push_back(p);
    breaks.push_back(kind);
  }

  // A soft break parts the returns unless the cluster so far and the returns after the break,
  // up to the next hard break, lie on one line within the noise (OneSurfaceAcrossTheBreak).
  // The returns after it are taken across further soft breaks: a return the noise threw off
  // the line parts its neighbours on both sides, and the runs between are too short to judge.
  std::vector<ScanCluster> clusters;
  std::size_t start = 0;
  const auto finish = [&](std::size_t end) {
    if (end == start) return;
    if (end - start < static_cast<std::size_t>(options.min_points)) {
      ++local.dropped_small;
    } else {
      clusters.push_back(ScanCluster{{beams.begin() + static_cast<std::ptrdiff_t>(start),
                                      beams.begin() + static_cast<std::ptrdiff_t>(end)}});
      ++local.clusters;
    }
    start = end;
  };
  const std::span<const Vector2d> all(points);
  std::vector<std::size_t> next_hard(points.size() + 1, points.size());
  for (std::size_t j = points.size(); j-- > 0;) {
    next_hard[j] = breaks[j] == Break::kHard ? j : next_hard[j + 1];
  }
  for (std::size_t j = 1; j < points.size(); ++j) {
    if (breaks[j] == Break::kNone) continue;
    if (breaks[j] == Break::kSoft && options.join_noise_breaks) {
      const std::size_t end = next_hard[j + 1];
      if (OneSurfaceAcrossTheBreak(all.subspan(start, j - start), all.subspan(j, end - j),
                                   options.range_noise_m, options.breakpoint_noise_sigmas)) {
        continue;
      }
    }
    finish(j);
  }
  finish(points.size());
  if (stats) *stats = local;
  return clusters;
}

bool HasDynamicBeam(const ScanCluster& cluster, std::span<const HitClass> classes) {
  if (classes.empty()) return false;
  return std::any_of(cluster.beams.begin(), cluster.beams.end(),
                     [&](std::size_t i) { return classes[i] == HitClass::kDynamic; });
}

bool IsUnmapped(const ScanCluster& cluster, std::span<const HitClass> classes) {
  if (classes.empty()) return false;
  return std::all_of(cluster.beams.begin(), cluster.beams.end(),
                     [&](std::size_t i) { return classes[i] == HitClass::kUnknown; });
}

LidarObjectFrame DescribeClusters(const LidarScan& scan, std::span<const ScanCluster> clusters,
                                  std::span<const HitClass> classes, const Pose2& ego_pose,
                                  const SegmentationOptions& options) {
  LidarObjectFrame frame;
  frame.stamp = scan.stamp;
  frame.mount = scan.mount;
  frame.ego_pose = ego_pose;
  std::uint32_t id = 0;
  for (const ScanCluster& cluster : clusters) {
    if (options.dynamic_only && !HasDynamicBeam(cluster, classes) &&
        !(options.report_unmapped && IsUnmapped(cluster, classes))) {
      continue;
    }
    LidarObject o = DescribeCluster(scan, cluster, classes, options);
    o.id = ++id;
    frame.objects.push_back(std::move(o));
  }
  return frame;
}

LidarObjectFrame SegmentScan(const LidarScan& scan, std::span<const HitClass> classes,
                             const Pose2& ego_pose, const SegmentationOptions& options,
                             double min_range_m, SegmentationStats* stats) {
  const std::vector<ScanCluster> clusters = ClusterScan(scan, classes, options, min_range_m, stats);
  return DescribeClusters(scan, clusters, classes, ego_pose, options);
}

}  // namespace lookout::lidar
