#include "lookout/fusion/fusion_options.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lookout::fusion {
namespace {

void Require(bool ok, const char* field, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("FusionOptions.") + field + ": " + what);
}

}  // namespace

void FusionOptions::Validate() const {
  stereo.Validate();
  lidar_point.Validate();
  Require(gate_probability > 0.0 && gate_probability < 1.0, "gate_probability",
          "must be in (0, 1)");
  Require(point_definition_sigma_m >= 0.0, "point_definition_sigma_m", "must be >= 0");
  Require(disagreement_probability > 0.0 && disagreement_probability <= 1.0,
          "disagreement_probability", "must be in (0, 1]");
  Require(piece_gap_m >= 0.0 && std::isfinite(piece_gap_m), "piece_gap_m",
          "must be finite and >= 0");
  Require(max_stereo_age_s >= 0.0, "max_stereo_age_s", "must be >= 0");
  Require(acceleration_sigma_mps2 >= 0.0, "acceleration_sigma_mps2", "must be >= 0");
  Require(pair_memory_s >= 0.0, "pair_memory_s", "must be >= 0");
  Require(two_bodies_probability > 0.0 && two_bodies_probability <= 1.0, "two_bodies_probability",
          "must be in (0, 1]");
  Require(history_disagreement_probability > 0.0 && history_disagreement_probability <= 1.0,
          "history_disagreement_probability", "must be in (0, 1]");
  Require(stereo_class_confidence > 0.0 && stereo_class_confidence <= 1.0,
          "stereo_class_confidence", "must be in (0, 1]");
  Require(dynamic_speed_mps >= 0.0, "dynamic_speed_mps", "must be >= 0");
  Require(dynamic_probability > 0.0 && dynamic_probability < 1.0, "dynamic_probability",
          "must be in (0, 1)");
}

}  // namespace lookout::fusion
