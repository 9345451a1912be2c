#pragma once

// One frame of multi-object tracking evaluation, as every tracking metric here consumes it:
// the ids of the true objects and of the hypotheses (tracks) present in the frame, and the
// distance of each pair, kForbidden where the pair may not be matched. Distance matching of
// points (the simulator, in metres) and IoU matching of image boxes (MOTChallenge) both
// produce it, so the metrics do not know which one was used.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace lookout::eval {

struct MotFrame {
  std::vector<std::int64_t> truth_ids;       // distinct within the frame
  std::vector<std::int64_t> hypothesis_ids;  // distinct within the frame
  // truth_ids.size() x hypothesis_ids.size(); kForbidden (any non-finite value) = no match.
  Eigen::MatrixXd distance;
};

struct PointObject {
  std::int64_t id = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
};

// An axis-aligned image box, MOTChallenge style: top-left corner and size, in pixels.
struct Box {
  double left = 0.0;
  double top = 0.0;
  double width = 0.0;
  double height = 0.0;
};

struct BoxObject {
  std::int64_t id = 0;
  Box box;
};

// Intersection over union; 0 when the boxes do not overlap or both are empty.
double BoxIou(const Box& a, const Box& b);

// Euclidean distance matching: a pair may match when its distance is at most max_distance_m.
// The distance is the MOTP term (metres).
MotFrame DistanceFrame(const std::vector<PointObject>& truths,
                       const std::vector<PointObject>& hypotheses, double max_distance_m);

// IoU matching (py-motmetrics' iou_matrix): the distance is 1 - IoU, and a pair may match
// when 1 - IoU <= max_one_minus_iou (0.5 in MOTChallenge: IoU >= 0.5). MOTP is then the
// mean of 1 - IoU over matches.
MotFrame IouFrame(const std::vector<BoxObject>& truths, const std::vector<BoxObject>& hypotheses,
                  double max_one_minus_iou = 0.5);

}  // namespace lookout::eval
