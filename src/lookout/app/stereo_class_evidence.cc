#include "lookout/app/stereo_class_evidence.h"

#include <cmath>

#include "lookout/core/input_error.h"
#include "lookout/fusion/fuse_objects.h"

namespace lookout::app {
namespace {

using Eigen::Vector2d;

}  // namespace

grid::GridClass GridClassOf(ObjectClass c) {
  switch (c) {
    case ObjectClass::kPedestrian: return grid::GridClass::kPedestrian;
    case ObjectClass::kCyclist: return grid::GridClass::kCyclist;
    case ObjectClass::kCar:
    case ObjectClass::kTruck: return grid::GridClass::kVehicle;
    case ObjectClass::kPole: return grid::GridClass::kStatic;
    case ObjectClass::kUnknown: break;
  }
  return grid::GridClass::kUnknown;
}

void StereoClassEvidenceOptions::Validate(const std::string& source) const {
  auto check = [&](bool ok, const char* field, const char* problem) {
    if (!ok) throw InputError(source, 0, std::string("stereo_class.") + field, problem);
  };
  check(class_accuracy > 0.0 && class_accuracy < 1.0, "class_accuracy", "must be in (0, 1)");
  check(std::isfinite(max_stereo_age_s) && max_stereo_age_s >= 0.0, "max_stereo_age_s",
        "must be finite and >= 0");
  check(std::isfinite(region_sigmas) && region_sigmas >= 0.0, "region_sigmas",
        "must be finite and >= 0");
  stereo.Validate();
}

std::optional<grid::ClassPmf> GridClassLikelihood(ObjectClass reported, double class_accuracy) {
  if (reported == ObjectClass::kUnknown) return std::nullopt;
  // P(report | true class t) for each t: the pmf fusion gives the report under a uniform prior
  // is exactly this (it sums to one over t).
  const auto given_true = fusion::StereoClassPmf(reported, class_accuracy);
  std::array<double, grid::kGridClassCount> sum{};
  std::array<int, grid::kGridClassCount> members{};
  for (std::size_t i = 0; i < kAllObjectClasses.size(); ++i) {
    const auto g = static_cast<std::size_t>(GridClassOf(kAllObjectClasses[i]));
    sum[g] += given_true[i];
    ++members[g];
  }
  grid::ClassPmf likelihood{};
  for (std::size_t g = 0; g < likelihood.size(); ++g) {
    likelihood[g] = static_cast<float>(sum[g] / members[g]);
  }
  return likelihood;
}

std::vector<grid::StereoClassRegion> StereoClassRegions(const stereo::ProjectedStereoFrame& frame,
                                                        const Pose2& ego_at_stereo, double dt_s,
                                                        const StereoClassEvidenceOptions& options) {
  // The marginal probability of a report at a cell that is not the object's: 1 / 6 for each
  // of the camera's six classes under a uniform prior.
  const double marginal = 1.0 / static_cast<double>(kAllObjectClasses.size());
  std::vector<grid::StereoClassRegion> regions;
  for (const stereo::StereoPoint& object : frame.objects) {
    const std::optional<grid::ClassPmf> likelihood =
        GridClassLikelihood(object.object_class, options.class_accuracy);
    if (!likelihood) continue;
    const stereo::OrientedBox& box = object.footprint;
    const Vector2d u(std::cos(box.yaw_rad), std::sin(box.yaw_rad));
    const Vector2d w(-u.y(), u.x());
    const Eigen::Matrix2d& p = object.point.covariance;
    const double grow_u = options.region_sigmas * std::sqrt(u.dot(p * u));
    const double grow_w = options.region_sigmas * std::sqrt(w.dot(p * w));
    stereo::OrientedBox region = box;
    region.center_m += dt_s * object.velocity_mps;
    region.length_m += 2.0 * grow_u;
    region.width_m += 2.0 * grow_w;
    const double area = region.length_m * region.width_m;
    if (!(area > 0.0)) continue;
    const double inside = box.length_m * box.width_m / area;

    grid::StereoClassRegion r;
    for (const Vector2d& corner : region.Corners()) r.polygon_m.push_back(ego_at_stereo * corner);
    for (std::size_t g = 0; g < r.likelihood.size(); ++g) {
      r.likelihood[g] = static_cast<float>(inside * static_cast<double>((*likelihood)[g]) +
                                           (1.0 - inside) * marginal);
    }
    regions.push_back(std::move(r));
  }
  return regions;
}

}  // namespace lookout::app
