#include "lookout/app/lidar_object_scoring.h"

#include <vector>

namespace lookout::app {
namespace {

Eigen::Vector2d FootprintCentre(const sim::Shape& shape) {
  if (shape.kind == sim::Shape::Kind::kCircle) return shape.center;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& v : shape.vertices) sum += v;
  return sum / static_cast<double>(shape.vertices.size());
}

}  // namespace

LidarObjectScorer::LidarObjectScorer(const Pose2& world_from_odom,
                                     const eval::DetectionMatchOptions& options)
    : world_from_odom_(world_from_odom), options_(options) {}

void LidarObjectScorer::Observe(const LidarObjectFrame& objects,
                                const sim::TruthFrame& truth_world,
                                const GridGeometry& window_odom) {
  const Pose2 world_from_vehicle = world_from_odom_ * objects.ego_pose;
  std::vector<Eigen::Vector2d> points;
  for (const LidarObject& o : objects.objects) {
    if (o.dynamic) points.push_back(world_from_vehicle * o.centroid_m);
  }
  const Pose2 odom_from_world = world_from_odom_.Inverse();
  std::vector<bool> countable;
  countable.reserve(truth_world.actors.size());
  for (const sim::ActorTruth& a : truth_world.actors) {
    const bool in_window = window_odom.CellAt(odom_from_world * FootprintCentre(a.footprint))
                               .has_value();
    countable.push_back(a.visible_fraction_lidar > 0.0 && in_window);
  }
  accumulator_.AddFrame(
      eval::MatchObjectsToMovingActors(points, truth_world.actors, countable, options_));
  ++frames_;
}

void LidarObjectScorer::Report(std::map<std::string, double>& metrics) const {
  if (const auto p = accumulator_.Precision()) metrics["lidar_objects.precision"] = *p;
  if (const auto r = accumulator_.Recall()) metrics["lidar_objects.recall"] = *r;
  if (frames_ > 0) {
    metrics["lidar_objects.dynamic_per_frame"] =
        static_cast<double>(accumulator_.counts().objects) / static_cast<double>(frames_);
  }
}

}  // namespace lookout::app
