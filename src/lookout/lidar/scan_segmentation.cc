#include "lookout/lidar/scan_segmentation.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "lookout/core/breakpoint_distance.h"
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

// The index of the point furthest from the chord first-last, and its distance.
std::pair<std::size_t, double> FurthestFromChord(std::span<const Vector2d> points) {
  const Vector2d a = points.front();
  const Vector2d chord = points.back() - a;
  const double length = chord.norm();
  std::size_t best = 0;
  double best_distance = 0.0;
  for (std::size_t k = 1; k + 1 < points.size(); ++k) {
    const Vector2d d = points[k] - a;
    const double distance = length > 0.0 ? std::abs(Cross(chord, d)) / length : d.norm();
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
};

FrontSideRange FrontSide(std::span<const Vector2d> points, const Vector2d& lidar,
                         const SegmentationOptions& options) {
  const FrontSideRange whole{0, points.size(), false};
  if (points.size() < 3) return whole;
  const auto [corner, distance] = FurthestFromChord(points);
  const double threshold =
      std::max(options.corner_split_m, options.breakpoint_noise_sigmas * options.range_noise_m);
  if (distance <= threshold) return whole;
  // The corner belongs to both sides.
  const Vector2d side_1 = points.front() - points[corner];
  const Vector2d side_2 = points.back() - points[corner];
  const double l1 = side_1.norm();
  const double l2 = side_2.norm();
  const std::size_t returns_1 = corner + 1;
  const std::size_t returns_2 = points.size() - corner;
  if (std::max(l1, l2) < options.min_box_side_m &&
      std::max(returns_1, returns_2) < 2 * std::min(returns_1, returns_2)) {
    return {0, points.size(), true};
  }
  const Vector2d to_lidar = lidar - (points[corner] + 0.5 * (side_1 + side_2));
  const bool first_is_front =
      std::abs(to_lidar.dot(side_2)) * l1 * l1 >= std::abs(to_lidar.dot(side_1)) * l2 * l2;
  return first_is_front ? FrontSideRange{0, corner + 1, false}
                        : FrontSideRange{corner, points.size(), false};
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

  // Not a structured binding: the lambda below captures both, which clang 14 does not allow of
  // bindings (C++20 does; the sanitizer and fuzz builds use clang).
  const FrontSideRange side = FrontSide(points, scan.mount.translation, options);
  const std::size_t begin = side.begin;
  const std::size_t end = side.end;
  const std::span<const Vector2d> front(points.data() + begin, end - begin);
  const Line line = FitLine(front);
  o.front_start_m = Project(line, front.front());
  o.front_end_m = Project(line, front.back());
  o.point_m = 0.5 * (o.front_start_m + o.front_end_m);
  if (side.round_body) {
    // The point is the middle of the side facing the lidar, which for a round body is its
    // nearest point, r in front of its centre on the ray. The beams sample the arc evenly
    // across the ray, so the line through the returns' mean lies (pi / 4) r in front of the
    // centre: the segment moves (1 - pi / 4) r towards the lidar, r half its chord.
    const Vector2d from_lidar = o.point_m - scan.mount.translation;
    const double range = from_lidar.norm();
    const double radius = 0.5 * (o.front_end_m - o.front_start_m).norm();
    if (range > 0.0) {
      const Vector2d shift = -(1.0 - 0.25 * kPi) * radius / range * from_lidar;
      o.front_start_m += shift;
      o.front_end_m += shift;
      o.point_m += shift;
      o.round_body_shift_m = shift;
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
  // surface (at most sigma_r) at each end.
  const double seen_m = (o.front_end_m - o.front_start_m).norm();
  const double margin = options.breakpoint_noise_sigmas * options.range_noise_m;
  const auto extent = [&](bool at_start) {
    const std::size_t k = at_start ? begin : end - 1;
    const Vector2d& p = points[k];
    const double spacing = BeamSpacingOnSurface(p - lidar, u, dphi);
    const bool outer = at_start ? begin == 0 : end == n;
    if (!outer) return spacing;
    const double cap = std::max(spacing, options.max_side_length_m - seen_m);
    return HiddenExtent(scan, cluster.beams[k], at_start ? -1 : 1, line,
                        at_start ? o.front_start_m : o.front_end_m, at_start ? -u : u, margin, cap);
  };
  // The line runs from the front's first beam to its last (FitLine), so the start's outward
  // is -u, beam index down.
  const double h1 = extent(true);
  const double h2 = extent(false);
  o.hidden_start_m = h1;
  o.hidden_end_m = h2;
  const double var_along =
      (h1 * h1 + h2 * h2) / 48.0 + (h2 - h1) * (h2 - h1) / 16.0 + sigma_r2 / 2.0;
  const double var_across = sigma_r2 / static_cast<double>(front.size());
  Matrix2d axes;
  axes.col(0) = u;
  axes.col(1) = v;
  o.point_covariance =
      axes * Eigen::Vector2d(var_along, var_across).asDiagonal() * axes.transpose();

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
  check(std::isfinite(max_side_length_m) && max_side_length_m > 0.0, "max_side_length_m",
        "must be finite and > 0");
  check(std::isfinite(velocity_unknown_sigma_mps) && velocity_unknown_sigma_mps > 0.0,
        "velocity_unknown_sigma_mps", "must be finite and > 0");
}

double BreakpointDistance(double r_prev_m, double dphi_rad, const SegmentationOptions& options) {
  return lookout::BreakpointDistance(r_prev_m, dphi_rad, options.breakpoint_incidence_rad,
                                     options.breakpoint_noise_sigmas * options.range_noise_m);
}

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
  std::vector<ScanCluster> clusters;
  SegmentationStats local;
  ScanCluster current;
  std::size_t last = 0;
  Vector2d last_point = Vector2d::Zero();
  const double dphi = std::abs(scan.angle_increment_rad);
  auto finish = [&] {
    if (current.beams.empty()) return;
    if (current.beams.size() < static_cast<std::size_t>(options.min_points)) {
      ++local.dropped_small;
    } else {
      clusters.push_back(std::move(current));
      ++local.clusters;
    }
    current = ScanCluster{};
  };
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    if (!IsReturn(scan, i, min_range_m)) {
      ++local.no_returns;
      continue;
    }
    const double r = static_cast<double>(scan.ranges_m[i]);
    const double a = scan.BeamAngle(i);
    const Vector2d p(r * std::cos(a), r * std::sin(a));  // sensor frame
    if (!current.beams.empty()) {
      const std::size_t gap = i - last;
      const double r_prev = last_point.norm();
      const bool bridged = gap <= static_cast<std::size_t>(options.max_gap_beams) + 1;
      const double step = (p - last_point).norm();
      const bool class_break =
          options.class_break_m > 0.0 && step > options.class_break_m && classes_differ(last, i);
      if (!bridged || class_break ||
          step > BreakpointDistance(r_prev, static_cast<double>(gap) * dphi, options)) {
        finish();
      }
    }
    current.beams.push_back(i);
    last = i;
    last_point = p;
  }
  finish();
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
