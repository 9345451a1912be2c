#pragma once

// The camera's classes as evidence for the grid's class layer (the fusion issue's item 3;
// grid/class_update.h, step 8 of docs/extended-grid.md): each validated stereo object becomes
// a footprint in the grid's (odometry) frame at the scan's time, with the likelihood of the
// camera's report under each grid class.
//
// Likelihood: the camera's confusion model (the simulator's, sim/stereo_sensor.h): it reports
// the true class with probability a (class_accuracy) and each of the five others with
// (1 - a) / 5. A grid class stands for the camera classes it holds (pedestrian, cyclist; car
// and truck -> vehicle; pole -> static; unknown -> unknown), so its likelihood is the mean of
// P(report | member) over its members. A report of "unknown" carries no evidence and gives no
// region.
//
// Where: the object's footprint (stereo::ProjectStereoFrame: validated, in the vehicle frame
// at the stereo stamp) moved by its own velocity to the scan's stamp and put in the odometry
// frame by the ego pose at the stereo stamp. The camera's centre is uncertain (sigma 1.3 m in
// depth at 35 m): the region is the footprint grown by one sigma of the object's point on each
// side, along the box's axes, and a cell in it belongs to the object with probability
// p = footprint area / region area. A cell that is not the object's sees the report with its
// marginal probability, 1/6 under a uniform prior whatever the cell's class, so the region's
// likelihood is the mixture
//     L'(g) = p L(g) + (1 - p) / 6,
// strong for a near, well-placed object, close to flat for a far one.

#include <optional>
#include <string>
#include <vector>

#include "lookout/core/object_class.h"
#include "lookout/core/pose2.h"
#include "lookout/grid/class_update.h"
#include "lookout/stereo/stereo_point.h"

namespace lookout::app {

struct StereoClassEvidenceOptions {
  bool enabled = true;
  // The camera's confusion model: the probability that it reports the true class (the
  // simulator's class_accuracy; fusion::FusionOptions::stereo_class_confidence is the same).
  double class_accuracy = 0.9;
  // A stereo frame further than this from the scan is not used (fusion's max_stereo_age_s).
  double max_stereo_age_s = 0.1;
  // Grow the footprint by this many sigmas of the object's point on each side.
  double region_sigmas = 1.0;
  stereo::StereoObjectOptions stereo;

  // Throws lookout::InputError(source, 0, "stereo_class.<field>", ...) for the first field out
  // of range.
  void Validate(const std::string& source = "stereo class evidence options") const;
};

// The grid class that stands for a camera class (see above).
grid::GridClass GridClassOf(ObjectClass c);

// The likelihood of the camera reporting `reported` under each grid class; nullopt for an
// unknown report (no evidence).
std::optional<grid::ClassPmf> GridClassLikelihood(ObjectClass reported, double class_accuracy);

// The regions of `frame` (its objects at frame.stamp, vehicle frame), for a scan dt_s later,
// in the odometry frame where the vehicle was at `ego_at_stereo`. Pure.
std::vector<grid::StereoClassRegion> StereoClassRegions(const stereo::ProjectedStereoFrame& frame,
                                                        const Pose2& ego_at_stereo, double dt_s,
                                                        const StereoClassEvidenceOptions& options);

}  // namespace lookout::app
