#pragma once

// Seed 004 section VI as one pure function: association (VI.A), position fusion (VI.B) and
// the fused list (VI.C) of one lidar frame and the stereo objects brought to its stamp.
//
// Space of fusion: Cartesian, the vehicle frame. The paper fuses (range, bearing) from the
// lidar origin; Lookout takes the stereo point as the paper hands it over (range and bearing
// from the lidar origin with their covariance, stereo/stereo_point.h), carries it to Cartesian
// with the Jacobian (stereo/range_bearing.h), and fuses there, because (1) a bearing is an
// angle and an information-weighted mean of angles breaks at the +-pi seam; (2) the lidar
// object's covariance comes in Cartesian form (LidarObject::point_covariance) and the tracker
// wants Cartesian, so fusing in polar would need two more conversions, each a linearisation;
// (3) in Cartesian form the product of the two Gaussians is exact, whereas in polar form it
// is exact only when both sensors share the origin. The linearisation costs under 2 mm here.

#include <cstdint>
#include <span>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/fusion/association.h"
#include "lookout/fusion/fused_object.h"
#include "lookout/fusion/fusion_options.h"
#include "lookout/fusion/gate.h"
#include "lookout/stereo/stereo_point.h"

namespace lookout::fusion {

struct FuseObjectsResult {
  FusedObjectFrame frame;
  std::size_t pairs = 0;            // objects seen by both sensors, their points fused
  std::size_t footprint_pairs = 0;  // ... on different sides (the camera's point kept)
  // Lidar objects left out for a non-finite point or velocity or a covariance that is not
  // positive definite (counted; the lidar stage should never make one).
  std::vector<std::uint32_t> dropped_lidar_ids;
  // Lidar objects left out as fragments of a body the camera paired with another of them
  // (IsFragmentOf), in the lidar frame's order.
  std::vector<std::uint32_t> fragment_lidar_ids;
  // Unpaired lidar objects left out as pieces of a body beside them (FusionOptions::piece_gap_m).
  std::vector<std::uint32_t> piece_lidar_ids;
  // The lidar objects as fused: the usable ones, in their order, each with the point
  // covariance fusion gave it (LidarPointCovariance: with the camera's class where paired).
  LidarObjectFrame lidar;
};

// `stereo` must already be in the vehicle frame at lidar.stamp (FusionEngine predicts it).
//
// Beyond the paper, fragments: a long body can break into several lidar objects where its
// outline has gaps at the scan's height (a bicycle between its wheels; a car's wheel arches;
// close up, returns lost on dark paint), while the camera sees one object. The camera pairs one
// fragment; left alone, each other one would be a lidar-only object of its own, on which the
// tracker starts a second track beside the first (cyclist-crossing: a split cyclist's two
// tracks, docs/fusion.md). An unpaired lidar object whose front segment lies on the footprint of
// a stereo object that paired another lidar object (IsFragmentOf) is left out of the fused
// list and counted. Only the camera's cyclists, cars and trucks: a walker is one arc, and two
// walkers side by side would otherwise be one.
//
// By the same test, footprint pairs: a camera body the point gate paired with nothing, and the
// nearest unpaired lidar object on its footprint. The two points are the middles of two sides
// (near-miss: the lidar sees a car's nose past a corner block, the camera its box and the side
// the ray from its centre leaves through, 2.4 m apart, so the point gate refuses them): both
// sensors saw the object, so it is one fused object (sensor_count 2, both ids, the camera's
// class, dynamic if either says so), but its point, covariance and front are the camera's, not
// a fusion of two different points (FusedObject::footprint_pair; the fusion metrics leave it
// out). Its other pieces are then its fragments.
//
// Without the camera, pieces: the segmentation also splits bodies no camera pairs (fig8's
// cyclist out of the camera's view, as its side and its front face 0.46 m apart; the crowd's
// walkers, whose arcs break), and each piece would be a lidar-only object with a track of its
// own. An unpaired dynamic lidar object whose front segment comes within
// FusionOptions::piece_gap_m of another dynamic lidar object's that is longer (ties: the
// earlier) or that the camera paired is a piece of that body: left out and counted. Static
// objects are not judged (the tracking stage takes no static lidar-only object), and a paired
// object is never a piece.
//
// `priors`: where the camera tracks' previous pairs put their bodies now (FusionEngine,
// PredictPairPrior), for the point gate (AssociateStereoToLidar), and for the fused covariance
// of a point pair that disagrees with its own camera track's prior
// (FusionOptions::history_disagreement_probability).
FuseObjectsResult FuseObjects(const LidarObjectFrame& lidar,
                              std::span<const stereo::StereoPoint> stereo,
                              const FusionOptions& options, std::span<const PairPrior> priors = {});

// The distance between two lidar objects' front segments (0 where they cross). Pure.
double FrontSegmentDistance(const LidarObject& a, const LidarObject& b);

// Whether the stereo class is a body long enough to break into several lidar objects.
bool HasFragments(ObjectClass c);

// Whether `fragment` is a piece of the body the camera sees as `stereo` (its point's
// covariance `stereo_covariance`, vehicle frame): a body with fragments whose footprint each end
// of the fragment's front segment lies on, within `gate` (the association gate's d^2 from the
// end to the footprint's nearest point, under the stereo point's covariance, the fragment's and
// the points' definition sigma). Pure.
bool IsFragmentOf(const LidarObject& fragment, const stereo::StereoPoint& stereo,
                  const Eigen::Matrix2d& stereo_covariance, const AssociationGate& gate);

// The camera's class as a pmf: `reported` with probability `confidence`, the rest evenly
// over the other classes.
std::array<double, kAllObjectClasses.size()> StereoClassPmf(ObjectClass reported,
                                                            double confidence);

// Whether a velocity with covariance says "moving": speed >= min_speed_mps and
// v^T C^-1 v >= the chi-square (2 dof) quantile of `probability`.
bool IsSignificantlyMoving(const Eigen::Vector2d& velocity_mps,
                           const Eigen::Matrix2d& covariance, double min_speed_mps,
                           double probability);

}  // namespace lookout::fusion
