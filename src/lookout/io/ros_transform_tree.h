#pragma once

// The tf tree of a ROS log in the plane: which frame is the parent of which, and each edge's
// transforms over time, so that the pose of one frame in another can be looked up at a time
// (a laser's mount on the robot, a frame of annotations in the vehicle frame).
//
// As tf does: each frame has at most one parent; frame names are compared without a leading
// '/' (ROS1 bags mix "/base_link" and "base_link"); a lookup walks from both frames up to their
// common ancestor and composes the edges. Each edge answers at time t with the last transform
// at or before t, interpolated linearly (the heading along the shorter arc) towards the next
// one; before the first and after the last it holds the nearest. An edge that never moves (a
// sensor mount repeated on /tf or latched on /tf_static) therefore answers at any time.
//
// Planar: a transform is taken as its x, y and the yaw of its rotation about z (RosTransform::
// Planar). Frames that are not level (a tilted sensor) are flattened; `max_tilt_rad` says by
// how much the worst edge of a lookup was tilted, so a caller can refuse it.

#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lookout/core/pose2.h"
#include "lookout/core/time.h"
#include "lookout/io/ros_conversions.h"

namespace lookout::io {

// "/base_link" and "base_link" name one frame.
std::string NormaliseFrameId(std::string_view frame_id);

class RosTransformTree {
 public:
  // Transforms in any order. A frame given two different parents keeps the first parent it
  // was given (tf would flip between them); the others are counted in `conflicting`.
  explicit RosTransformTree(std::span<const RosTransform> transforms);

  struct Lookup {
    Pose2 pose;                // of `source` in `target`
    double max_tilt_rad = 0.0;  // the largest roll/pitch of an edge used
  };
  // The pose of frame `source` in frame `target` at t, or nullopt when the two frames are not
  // connected (a frame the tree does not know, or two separate trees).
  std::optional<Lookup> Find(std::string_view target, std::string_view source, TimeNs t) const;

  bool HasFrame(std::string_view frame) const;
  std::size_t conflicting() const { return conflicting_; }

 private:
  struct Sample {
    TimeNs t;
    Pose2 pose;  // child in parent
    double tilt_rad;
  };
  struct Edge {
    std::string parent;
    std::vector<Sample> samples;  // by time
  };
  // The child's pose in its parent at t.
  Sample At(const Edge& edge, TimeNs t) const;

  std::map<std::string, Edge, std::less<>> edges_;  // by child frame
  std::size_t conflicting_ = 0;
};

}  // namespace lookout::io
