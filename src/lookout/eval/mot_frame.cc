#include "lookout/eval/mot_frame.h"

#include <algorithm>
#include <cassert>

#include "lookout/assignment/linear_assignment.h"

namespace lookout::eval {
namespace {

template <typename Object, typename Distance>
MotFrame MakeFrame(const std::vector<Object>& truths, const std::vector<Object>& hypotheses,
                   double max_distance, const Distance& distance) {
  MotFrame frame;
  frame.truth_ids.reserve(truths.size());
  frame.hypothesis_ids.reserve(hypotheses.size());
  for (const Object& t : truths) frame.truth_ids.push_back(t.id);
  for (const Object& h : hypotheses) frame.hypothesis_ids.push_back(h.id);
  frame.distance.resize(static_cast<Eigen::Index>(truths.size()),
                        static_cast<Eigen::Index>(hypotheses.size()));
  for (std::size_t i = 0; i < truths.size(); ++i) {
    for (std::size_t j = 0; j < hypotheses.size(); ++j) {
      const double d = distance(truths[i], hypotheses[j]);
      // "<=": a pair exactly at the threshold matches (py-motmetrics and TrackEval agree).
      frame.distance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          d <= max_distance ? d : assignment::kForbidden;
    }
  }
  return frame;
}

}  // namespace

double BoxIou(const Box& a, const Box& b) {
  const double overlap_x =
      std::max(0.0, std::min(a.left + a.width, b.left + b.width) - std::max(a.left, b.left));
  const double overlap_y =
      std::max(0.0, std::min(a.top + a.height, b.top + b.height) - std::max(a.top, b.top));
  const double intersection = overlap_x * overlap_y;
  if (intersection <= 0.0) return 0.0;
  const double union_area = a.width * a.height + b.width * b.height - intersection;
  return intersection / union_area;
}

MotFrame DistanceFrame(const std::vector<PointObject>& truths,
                       const std::vector<PointObject>& hypotheses, double max_distance_m) {
  assert(max_distance_m >= 0.0);
  return MakeFrame(truths, hypotheses, max_distance_m,
                   [](const PointObject& t, const PointObject& h) {
                     return (t.position_m - h.position_m).norm();
                   });
}

MotFrame IouFrame(const std::vector<BoxObject>& truths, const std::vector<BoxObject>& hypotheses,
                  double max_one_minus_iou) {
  assert(max_one_minus_iou >= 0.0 && max_one_minus_iou <= 1.0);
  return MakeFrame(
      truths, hypotheses, max_one_minus_iou,
      [](const BoxObject& t, const BoxObject& h) { return 1.0 - BoxIou(t.box, h.box); });
}

}  // namespace lookout::eval
