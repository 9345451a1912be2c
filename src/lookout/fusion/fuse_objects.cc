#include "lookout/fusion/fuse_objects.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <optional>

#include "lookout/core/chi_square.h"
#include "lookout/core/planar_geometry.h"
#include "lookout/fusion/association.h"
#include "lookout/fusion/gate.h"
#include "lookout/fusion/gaussian_fusion.h"
#include "lookout/fusion/lidar_point_model.h"
#include "lookout/fusion/shared_heading.h"
#include "lookout/stereo/stereo_validation.h"

namespace lookout::fusion {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;

bool UsableLidarObject(const LidarObject& o) {
  return o.point_m.allFinite() && stereo::IsPositiveDefinite(o.point_covariance) &&
         o.velocity_mps.allFinite() && o.velocity_covariance.allFinite();
}

Gaussian2 FusedVelocity(const LidarObject& lidar, const stereo::StereoPoint& stereo,
                        VelocitySource source) {
  const Gaussian2 from_lidar{lidar.velocity_mps, lidar.velocity_covariance};
  const Gaussian2 from_stereo{stereo.velocity_mps, stereo.velocity_covariance};
  // A lidar velocity without a proper covariance (a cluster born this scan) has no weight.
  const bool lidar_usable = stereo::IsPositiveDefinite(lidar.velocity_covariance);
  switch (source) {
    case VelocitySource::kLidar: return from_lidar;
    case VelocitySource::kStereo: return from_stereo;
    case VelocitySource::kInformationWeighted:
      return lidar_usable ? FuseGaussians(from_lidar, from_stereo) : from_stereo;
  }
  return from_stereo;
}

// The point of `box` nearest to `p` (p itself inside it).
Vector2d NearestPointOnBox(const stereo::OrientedBox& box, const Vector2d& p) {
  const Eigen::Rotation2Dd to_world(box.yaw_rad);
  const Vector2d local = to_world.inverse() * (p - box.center_m);
  const Vector2d half(0.5 * box.length_m, 0.5 * box.width_m);
  return box.center_m + to_world * local.cwiseMax(-half).cwiseMin(half);
}

}  // namespace

double FrontSegmentDistance(const LidarObject& a, const LidarObject& b) {
  const Vector2d& a0 = a.front_start_m;
  const Vector2d& a1 = a.front_end_m;
  const Vector2d& b0 = b.front_start_m;
  const Vector2d& b1 = b.front_end_m;
  // Crossing: each segment's ends on opposite sides of the other's line.
  if (Cross(a1 - a0, b0 - a0) * Cross(a1 - a0, b1 - a0) < 0.0 &&
      Cross(b1 - b0, a0 - b0) * Cross(b1 - b0, a1 - b0) < 0.0) {
    return 0.0;
  }
  // Otherwise they are nearest at an end of one of them.
  return std::min({PointToSegment(a0, b0, b1), PointToSegment(a1, b0, b1),
                   PointToSegment(b0, a0, a1), PointToSegment(b1, a0, a1)});
}

bool HasFragments(ObjectClass c) {
  return c == ObjectClass::kCyclist || c == ObjectClass::kCar || c == ObjectClass::kTruck;
}

bool IsFragmentOf(const LidarObject& fragment, const stereo::StereoPoint& stereo,
                  const Matrix2d& stereo_covariance, const AssociationGate& gate) {
  if (!HasFragments(stereo.object_class)) return false;
  for (const Vector2d& end : {fragment.front_start_m, fragment.front_end_m}) {
    const Vector2d on_box = NearestPointOnBox(stereo.footprint, end);
    const double d2 =
        gate.DistanceSquared(on_box, stereo_covariance, end, fragment.point_covariance);
    if (!gate.Accepts(d2)) return false;
  }
  return true;
}

std::array<double, kAllObjectClasses.size()> StereoClassPmf(ObjectClass reported,
                                                            double confidence) {
  std::array<double, kAllObjectClasses.size()> pmf{};
  const double other = (1.0 - confidence) / static_cast<double>(kAllObjectClasses.size() - 1);
  for (std::size_t i = 0; i < pmf.size(); ++i) {
    pmf[i] = kAllObjectClasses[i] == reported ? confidence : other;
  }
  return pmf;
}

bool IsSignificantlyMoving(const Vector2d& velocity_mps, const Matrix2d& covariance,
                           double min_speed_mps, double probability) {
  if (velocity_mps.norm() < min_speed_mps) return false;
  if (!stereo::IsPositiveDefinite(covariance)) return true;  // exact: the speed test decides
  return MahalanobisSquared(velocity_mps, covariance) >= ChiSquareQuantile(probability, 2.0);
}

namespace {

// Which stereo object each lidar object pairs with, and how.
struct Pairing {
  Pairing(std::size_t lidar_count, std::size_t stereo_count)
      : stereo_of_lidar(lidar_count),
        footprint_pair(lidar_count, false),
        stereo_taken(stereo_count, false) {}
  std::vector<std::optional<std::size_t>> stereo_of_lidar;
  std::vector<bool> footprint_pair;  // paired on the footprint, not by the point gate
  std::vector<bool> stereo_taken;
};

// Footprint pairs (fuse_objects.h): each unpaired camera body, in the camera's order, with the
// nearest unpaired lidar object on its footprint.
void AddFootprintPairs(std::span<const LidarObject* const> lidar,
                       std::span<const stereo::StereoPoint> stereo,
                       std::span<const stereo::CartesianPoint> stereo_points,
                       const AssociationGate& gate, Pairing& pairing) {
  for (std::size_t i = 0; i < stereo.size(); ++i) {
    if (pairing.stereo_taken[i]) continue;
    std::optional<std::size_t> nearest;
    double nearest_m = 0.0;
    for (std::size_t j = 0; j < lidar.size(); ++j) {
      if (pairing.stereo_of_lidar[j]) continue;
      if (!IsFragmentOf(*lidar[j], stereo[i], stereo_points[i].covariance, gate)) continue;
      const double d = (lidar[j]->point_m - stereo_points[i].point_m).norm();
      if (!nearest || d < nearest_m) {
        nearest = j;
        nearest_m = d;
      }
    }
    if (!nearest) continue;
    pairing.stereo_of_lidar[*nearest] = i;
    pairing.footprint_pair[*nearest] = true;
    pairing.stereo_taken[i] = true;
  }
}

// Fragments (fuse_objects.h): the unpaired lidar objects on the footprint of a stereo object
// that paired another.
std::vector<bool> Fragments(std::span<const LidarObject* const> lidar,
                            std::span<const stereo::StereoPoint> stereo,
                            std::span<const stereo::CartesianPoint> stereo_points,
                            const AssociationGate& gate, const Pairing& pairing) {
  std::vector<bool> fragment(lidar.size(), false);
  for (std::size_t j = 0; j < lidar.size(); ++j) {
    if (pairing.stereo_of_lidar[j]) continue;
    for (std::size_t i = 0; i < stereo.size() && !fragment[j]; ++i) {
      fragment[j] = pairing.stereo_taken[i] &&
                    IsFragmentOf(*lidar[j], stereo[i], stereo_points[i].covariance, gate);
    }
  }
  return fragment;
}

// Pieces (fuse_objects.h): the unpaired dynamic lidar objects within gap_m of a longer or
// camera-paired dynamic one, judged against the objects as they stand after the camera's rules.
std::vector<bool> Pieces(std::span<const LidarObject* const> lidar, const Pairing& pairing,
                         const std::vector<bool>& fragment, double gap_m) {
  std::vector<bool> piece(lidar.size(), false);
  if (!(gap_m > 0.0)) return piece;
  const auto length = [](const LidarObject& o) { return (o.front_end_m - o.front_start_m).norm(); };
  for (std::size_t j = 0; j < lidar.size(); ++j) {
    const LidarObject& a = *lidar[j];
    if (pairing.stereo_of_lidar[j] || fragment[j] || !a.dynamic) continue;
    for (std::size_t k = 0; k < lidar.size() && !piece[j]; ++k) {
      const LidarObject& b = *lidar[k];
      if (k == j || fragment[k] || !b.dynamic) continue;
      const bool b_wins =
          pairing.stereo_of_lidar[k] || length(b) > length(a) || (length(b) == length(a) && k < j);
      piece[j] = b_wins && FrontSegmentDistance(a, b) <= gap_m;
    }
  }
  return piece;
}

}  // namespace

FuseObjectsResult FuseObjects(const LidarObjectFrame& lidar,
                              std::span<const stereo::StereoPoint> stereo,
                              const FusionOptions& options, std::span<const PairPrior> priors) {
  FuseObjectsResult result;
  result.frame.stamp = lidar.stamp;
  result.frame.mount = lidar.mount;
  result.frame.ego_pose = lidar.ego_pose;

  std::vector<const LidarObject*> lidar_objects;
  std::vector<stereo::CartesianPoint> lidar_points;
  for (const LidarObject& o : lidar.objects) {
    if (!UsableLidarObject(o)) {
      result.dropped_lidar_ids.push_back(o.id);
      continue;
    }
    lidar_objects.push_back(&o);
    lidar_points.push_back({o.point_m, o.point_covariance});
  }
  // The stereo points as the paper hands them over, range and bearing from the lidar origin,
  // carried to Cartesian with the Jacobian.
  std::vector<stereo::CartesianPoint> stereo_points;
  stereo_points.reserve(stereo.size());
  for (const stereo::StereoPoint& s : stereo) {
    stereo_points.push_back(stereo::ToCartesian(s.polar, lidar.mount));
  }

  const AssociationGate gate(options);
  // Once per frame: the quantile is an inversion of the incomplete gamma function. Off (1): no
  // disagreement passes an infinite quantile.
  const auto quantile_or_off = [](double probability) {
    return probability < 1.0 ? ChiSquareQuantile(probability, 2.0)
                             : std::numeric_limits<double>::infinity();
  };
  const double disagreement_quantile = quantile_or_off(options.disagreement_probability);
  const double two_bodies_quantile = quantile_or_off(options.two_bodies_probability);
  const double history_quantile = quantile_or_off(options.history_disagreement_probability);
  const std::vector<std::optional<std::size_t>> own_prior = OwnPriors(priors, stereo.size());
  const std::vector<AssociationPair> pairs =
      AssociateStereoToLidar(stereo_points, lidar_points, gate, priors);
  result.pairs = pairs.size();
  Pairing pairing(lidar_objects.size(), stereo.size());
  for (const AssociationPair& pair : pairs) {
    pairing.stereo_of_lidar[pair.lidar] = pair.stereo;
    pairing.stereo_taken[pair.stereo] = true;
  }
  AddFootprintPairs(lidar_objects, stereo, stereo_points, gate, pairing);
  result.footprint_pairs = static_cast<std::size_t>(
      std::count(pairing.footprint_pair.begin(), pairing.footprint_pair.end(), true));
  const std::vector<bool> fragment = Fragments(lidar_objects, stereo, stereo_points, gate, pairing);
  const std::vector<bool> piece = Pieces(lidar_objects, pairing, fragment, options.piece_gap_m);

  result.lidar.stamp = lidar.stamp;
  result.lidar.mount = lidar.mount;
  result.lidar.ego_pose = lidar.ego_pose;
  result.lidar.objects.reserve(lidar_objects.size());
  auto next_id = [&result] { return static_cast<std::uint32_t>(result.frame.objects.size()); };
  for (std::size_t j = 0; j < lidar_objects.size(); ++j) {
    const LidarObject& l = *lidar_objects[j];
    FusedObject f;
    f.id = next_id();
    f.lidar_id = l.id;
    f.front_start_m = l.front_start_m;
    f.front_end_m = l.front_end_m;
    // Where the camera paired the object, the lidar point's covariance is the model's with the
    // camera's class and box (a segmentation object has none of its own). An object the camera did
    // not see keeps its source's (the grid's own class would be the one to use: not measured yet).
    const auto paired = pairing.stereo_of_lidar[j];
    LidarObject& as_fused = result.lidar.objects.emplace_back(l);
    if (fragment[j]) {
      result.fragment_lidar_ids.push_back(l.id);
      continue;
    }
    if (piece[j]) {
      result.piece_lidar_ids.push_back(l.id);
      continue;
    }
    if (const auto i = paired) {
      const stereo::StereoPoint& s = stereo[*i];
      const PairedBody body{s.object_class, s.footprint.length_m, s.footprint.width_m,
                            s.front.end_m - s.front.start_m, s.yaw_variance};
      // What the lidar alone measured, as the camera's body reads the returns. It takes the
      // model's covariance below, once FacingSidePoint has read the segment's own from it.
      as_fused = ReadAsBody(l, body, options.lidar_point);
      const Matrix2d modelled =
          LidarPointCovariance(as_fused, body, lidar.mount.translation, options.lidar_point);
      if (pairing.footprint_pair[j]) {
        // Two sides' middles are not one point: the camera's is kept, with its front.
        f.point_m = stereo_points[*i].point_m;
        f.point_covariance = stereo_points[*i].covariance;
        f.front_start_m = s.front.start_m;
        f.front_end_m = s.front.end_m;
        f.footprint_pair = true;
      } else {
        // The lidar's point for the side the camera's box turns to it, the segment's middle
        // unless a corner view says another side faces (FacingSidePoint). The lidar object
        // itself keeps its own point: what the lidar alone measured.
        const LidarSidePoint side =
            FacingSidePoint(as_fused, modelled, body, lidar.mount.translation, options.lidar_point);
        const Gaussian2 lidar_point{side.point_m, side.covariance};
        const Gaussian2 stereo_point{stereo_points[*i].point_m, stereo_points[*i].covariance};
        // The camera's heading, where it turned the lidar's point too, counted once.
        const Matrix2d cross = SharedHeadingCovariance(side.heading_share, s.heading_share);
        const Gaussian2 position = FuseCorrelated(lidar_point, stereo_point, cross);
        f.front_start_m = side.front_start_m;
        f.front_end_m = side.front_end_m;
        f.point_m = position.mean;
        f.point_covariance = TwoBodiesMixture(
            Gaussian2{position.mean,
                      DisagreementScale(lidar_point, stereo_point, disagreement_quantile, cross) *
                          position.covariance},
            lidar_point, stereo_point, two_bodies_quantile, cross);
        const std::optional<std::size_t> k = own_prior[*i];
        if (k && options.history_disagreement_probability < 1.0) {
          const stereo::CartesianPoint& prior = priors[*k].point;
          const Gaussian2 history{prior.point_m, prior.covariance};
          f.point_covariance *= DisagreementScale(Gaussian2{f.point_m, f.point_covariance}, history,
                                                  history_quantile);
          f.point_covariance = DisagreementMixture(Gaussian2{f.point_m, f.point_covariance},
                                                   history, two_bodies_quantile);
        }
      }
      as_fused.point_covariance = modelled;
      const Gaussian2 velocity = FusedVelocity(l, s, options.velocity_source);
      f.velocity_mps = velocity.mean;
      f.velocity_covariance = velocity.covariance;
      f.class_pmf = StereoClassPmf(s.object_class, options.stereo_class_confidence);
      f.dynamic = l.dynamic ||
                  IsSignificantlyMoving(f.velocity_mps, f.velocity_covariance,
                                        options.dynamic_speed_mps, options.dynamic_probability);
      f.sensor_count = 2;
      f.stereo_id = s.id;
    } else {
      f.point_m = l.point_m;
      f.point_covariance = as_fused.point_covariance;
      f.velocity_mps = l.velocity_mps;
      f.velocity_covariance = l.velocity_covariance;
      f.class_pmf = l.class_pmf;
      f.dynamic = l.dynamic;
      f.sensor_count = 1;
    }
    result.frame.objects.push_back(f);
  }
  // Seed 004 VI.B: unpaired stereo objects are kept, "because they may correspond to dynamic
  // objects which may not have been detected by laser" (occluded, or transparent to it).
  for (std::size_t i = 0; i < stereo.size(); ++i) {
    if (pairing.stereo_taken[i]) continue;
    const stereo::StereoPoint& s = stereo[i];
    FusedObject f;
    f.id = next_id();
    f.stereo_id = s.id;
    f.point_m = stereo_points[i].point_m;
    f.point_covariance = stereo_points[i].covariance;
    f.velocity_mps = s.velocity_mps;
    f.velocity_covariance = s.velocity_covariance;
    f.front_start_m = s.front.start_m;
    f.front_end_m = s.front.end_m;
    f.class_pmf = StereoClassPmf(s.object_class, options.stereo_class_confidence);
    f.dynamic = IsSignificantlyMoving(s.velocity_mps, s.velocity_covariance,
                                      options.dynamic_speed_mps, options.dynamic_probability);
    f.sensor_count = 1;
    result.frame.objects.push_back(f);
  }
  return result;
}

}  // namespace lookout::fusion
