#include "lookout/eval/relation_error.h"

#include <cmath>
#include <optional>

#include "lookout/core/input_error.h"

namespace lookout::eval {
namespace {

struct MeanStd {
  double mean = 0.0;
  double std = 0.0;
};

// Two passes: the mean first, then the spread about it, which is exact where the one-pass
// E[x^2] - E[x]^2 cancels.
MeanStd OfValues(const std::vector<double>& values) {
  MeanStd result;
  for (const double v : values) result.mean += v;
  result.mean /= static_cast<double>(values.size());
  double spread = 0.0;
  for (const double v : values) spread += (v - result.mean) * (v - result.mean);
  result.std = std::sqrt(spread / static_cast<double>(values.size()));
  return result;
}

}  // namespace

void RelationGeneratorOptions::Validate() const {
  if (step_poses == 0) throw InputError("options", 0, "step_poses", "must be at least 1");
  if (!(min_travel_m >= 0.0) || !std::isfinite(min_travel_m)) {
    throw InputError("options", 0, "min_travel_m", "must be finite and not negative");
  }
}

RelationError ComputeRelationError(const Trajectory2& estimate,
                                   const std::vector<Relation2>& relations,
                                   const TrajectoryErrorOptions& options) {
  options.Validate();
  CheckTrajectoryTimes(estimate, "estimate trajectory");
  std::vector<double> translation;
  std::vector<double> rotation;
  RelationError result;
  for (const Relation2& relation : relations) {
    const std::optional<Pose2> first =
        InterpolatePose(estimate, relation.t1_s, options.max_interpolation_gap_s);
    const std::optional<Pose2> second =
        InterpolatePose(estimate, relation.t2_s, options.max_interpolation_gap_s);
    if (!first || !second) {
      ++result.unmatched;
      continue;
    }
    const Pose2 estimated_motion = first->Inverse() * *second;
    const Pose2 error = relation.motion.Inverse() * estimated_motion;  // delta_ij (-) delta*_ij
    translation.push_back(error.translation.norm());
    rotation.push_back(std::abs(WrapAngle(error.yaw)));
  }
  result.used = translation.size();
  if (translation.empty()) return result;
  std::vector<double> translation_squared;
  std::vector<double> rotation_squared;
  for (std::size_t i = 0; i < translation.size(); ++i) {
    translation_squared.push_back(translation[i] * translation[i]);
    rotation_squared.push_back(rotation[i] * rotation[i]);
  }
  const MeanStd t = OfValues(translation);
  const MeanStd t2 = OfValues(translation_squared);
  const MeanStd r = OfValues(rotation);
  const MeanStd r2 = OfValues(rotation_squared);
  result.translation_mean_m = t.mean;
  result.translation_std_m = t.std;
  result.translation_squared_mean_m2 = t2.mean;
  result.translation_squared_std_m2 = t2.std;
  result.rotation_mean_rad = r.mean;
  result.rotation_std_rad = r.std;
  result.rotation_squared_mean_rad2 = r2.mean;
  result.rotation_squared_std_rad2 = r2.std;
  return result;
}

std::vector<Relation2> GenerateRelations(const Trajectory2& reference,
                                         const RelationGeneratorOptions& options) {
  options.Validate();
  std::vector<Relation2> relations;
  const auto relate = [&](std::size_t i, std::size_t j) {
    relations.push_back(
        {reference[i].t_s, reference[j].t_s, reference[i].pose.Inverse() * reference[j].pose});
  };
  if (options.min_travel_m <= 0.0) {
    for (std::size_t i = 0; i + options.step_poses < reference.size(); ++i) {
      relate(i, i + options.step_poses);
    }
    return relations;
  }
  // Distance along the path to each pose; two indices walk it once.
  std::vector<double> along(reference.size(), 0.0);
  for (std::size_t i = 1; i < reference.size(); ++i) {
    along[i] =
        along[i - 1] + (reference[i].pose.translation - reference[i - 1].pose.translation).norm();
  }
  std::size_t j = 0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (j <= i) j = i + 1;
    while (j < reference.size() && along[j] - along[i] < options.min_travel_m) ++j;
    if (j == reference.size()) break;
    relate(i, j);
  }
  return relations;
}

}  // namespace lookout::eval
