#pragma once

// Options of the stereo stage: how a camera object becomes a point for fusion.

#include "lookout/stereo/depth_model.h"

namespace lookout::stereo {

// Where the covariance of an object's centre comes from.
enum class CovarianceSource {
  // The camera's own (StereoObject::center_covariance, seed 004 V.C.4: "variance of the object
  // center coordinates"). The simulator draws its noise from exactly this, so it is the
  // default.
  kReported,
  // The depth model evaluated at the reported centre: for a camera whose own variances are
  // missing or not trusted. Slightly off at long range, where the measured depth differs from
  // the true one (variance ~ z^4: +-7 % in z at 35 m is +-30 % in variance).
  kDepthModel,
};

struct StereoObjectOptions {
  StereoDepthModel depth_model;
  CovarianceSource covariance_source = CovarianceSource::kReported;

  // Throws std::invalid_argument naming the first field out of range.
  void Validate() const { depth_model.Validate(); }
};

}  // namespace lookout::stereo
