#include "lookout/io/ros_transform_tree.h"

#include <algorithm>
#include <cmath>

namespace lookout::io {
namespace {

// The angle between the rotated z axis and z: 0 for a rotation about z alone.
double TiltOf(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d z = q.normalized() * Eigen::Vector3d::UnitZ();
  return std::acos(std::clamp(z.z(), -1.0, 1.0));
}

Pose2 Interpolate(const Pose2& a, const Pose2& b, double s) {
  return Pose2(a.translation + s * (b.translation - a.translation),
               WrapAngle(a.yaw + s * WrapAngle(b.yaw - a.yaw)));
}

}  // namespace

std::string NormaliseFrameId(std::string_view frame_id) {
  while (!frame_id.empty() && frame_id.front() == '/') frame_id.remove_prefix(1);
  return std::string(frame_id);
}

RosTransformTree::RosTransformTree(std::span<const RosTransform> transforms) {
  for (const RosTransform& t : transforms) {
    const std::string child = NormaliseFrameId(t.child_frame);
    const std::string parent = NormaliseFrameId(t.parent_frame);
    if (child.empty() || parent.empty() || child == parent) {
      ++conflicting_;
      continue;
    }
    auto [it, inserted] = edges_.try_emplace(child, Edge{parent, {}});
    if (!inserted && it->second.parent != parent) {
      ++conflicting_;
      continue;
    }
    it->second.samples.push_back({t.stamp, t.Planar(), TiltOf(t.rotation)});
  }
  for (auto& [child, edge] : edges_) {
    std::stable_sort(edge.samples.begin(), edge.samples.end(),
                     [](const Sample& a, const Sample& b) { return a.t < b.t; });
  }
}

bool RosTransformTree::HasFrame(std::string_view frame) const {
  const std::string f = NormaliseFrameId(frame);
  if (edges_.contains(f)) return true;
  return std::any_of(edges_.begin(), edges_.end(),
                     [&](const auto& e) { return e.second.parent == f; });
}

RosTransformTree::Sample RosTransformTree::At(const Edge& edge, TimeNs t) const {
  const std::vector<Sample>& s = edge.samples;
  const auto after = std::upper_bound(s.begin(), s.end(), t,
                                      [](TimeNs value, const Sample& x) { return value < x.t; });
  if (after == s.begin()) return s.front();
  if (after == s.end()) return s.back();
  const Sample& a = *std::prev(after);
  const Sample& b = *after;
  const double f = static_cast<double>(t - a.t) / static_cast<double>(b.t - a.t);
  return {t, Interpolate(a.pose, b.pose, f), std::max(a.tilt_rad, b.tilt_rad)};
}

std::optional<RosTransformTree::Lookup> RosTransformTree::Find(std::string_view target,
                                                                std::string_view source,
                                                                TimeNs t) const {
  // The chain of each frame up to its root: the frame's pose in each ancestor.
  struct Link {
    std::string frame;  // an ancestor (the frame itself first)
    Pose2 pose;         // of the starting frame in `frame`
    double tilt_rad;
  };
  const auto chain = [&](const std::string& start) {
    std::vector<Link> links{{start, Pose2(), 0.0}};
    // A cycle in the tree (a bag whose edges loop) ends the walk: at most one step per edge.
    for (std::size_t step = 0; step <= edges_.size(); ++step) {
      const auto it = edges_.find(links.back().frame);
      if (it == edges_.end()) break;
      const Sample s = At(it->second, t);
      links.push_back({it->second.parent, s.pose * links.back().pose,
                       std::max(links.back().tilt_rad, s.tilt_rad)});
    }
    return links;
  };
  const std::string target_frame = NormaliseFrameId(target);
  const std::string source_frame = NormaliseFrameId(source);
  if (target_frame == source_frame) {
    if (!HasFrame(target_frame)) return std::nullopt;
    return Lookup{};
  }
  const std::vector<Link> from_source = chain(source_frame);
  const std::vector<Link> from_target = chain(target_frame);
  for (const Link& s : from_source) {
    for (const Link& g : from_target) {
      if (s.frame != g.frame) continue;
      // source in ancestor, target in ancestor: source in target = target^-1 * source.
      return Lookup{g.pose.Inverse() * s.pose, std::max(s.tilt_rad, g.tilt_rad)};
    }
  }
  return std::nullopt;
}

}  // namespace lookout::io
