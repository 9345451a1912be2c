#pragma once

// The fusion stage as the pipeline runs it (not wired yet: src/lookout/app does that): one
// call per lidar frame with the latest stereo frame, in seed 004's order
//   ProjectStereoFrame (V.C) -> PredictStereoPoint to the lidar stamp -> FuseObjects (VI).
//
// The ego pose at the stereo stamp is interpolated between the previous lidar frame's ego pose
// and this one's (LidarObjectFrame::ego_pose, odometry frame). Before there is a previous
// frame, or after the lidar stamps went backwards, there is nothing to interpolate with, and a
// stereo frame at another stamp than the lidar's is not used for that one frame (counted).

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "lookout/core/messages.h"
#include "lookout/fusion/fused_object.h"
#include "lookout/fusion/fusion_options.h"
#include "lookout/fusion/pair_memory.h"
#include "lookout/stereo/stereo_point.h"
#include "lookout/stereo/stereo_validation.h"

namespace lookout::fusion {

struct FusionStats {
  std::int64_t frames = 0;                // Fuse calls
  std::int64_t stereo_frames_used = 0;
  std::int64_t stereo_frames_stale = 0;   // more than max_stereo_age_s from the lidar stamp
  std::int64_t stereo_frames_without_ego_pose = 0;  // no pose to interpolate yet
  std::int64_t lidar_stamps_not_increasing = 0;     // a lidar stamp <= the one before
  std::int64_t pairs = 0;                           // objects seen by both sensors
  std::int64_t lidar_objects_dropped = 0;           // unusable lidar objects
  std::int64_t lidar_fragments = 0;  // lidar objects taken as fragments of a paired body
  std::int64_t lidar_pieces = 0;     // ... as pieces of a body beside them
  stereo::DropCounts stereo_drops;                  // unusable stereo objects, by reason
};

class FusionEngine {
 public:
  // Throws std::invalid_argument for invalid options (FusionOptions::Validate).
  explicit FusionEngine(FusionOptions options = {});

  // Fuses the lidar frame with the latest stereo frame (pass an empty StereoFrame when there
  // is none yet). Lidar frames in time order.
  FusedObjectFrame Fuse(const LidarObjectFrame& lidar, const StereoFrame& latest_stereo);
  // The same with the ego pose at the stereo stamp given (odometry frame), for a caller that
  // has it from odometry.
  FusedObjectFrame Fuse(const LidarObjectFrame& lidar, const StereoFrame& latest_stereo,
                        const Pose2& ego_pose_at_stereo);

  const FusionOptions& options() const { return options_; }
  const FusionStats& stats() const { return stats_; }
  // Of the last Fuse call: the stereo objects used, at the lidar stamp in its vehicle frame
  // (for metrics and display), and the ones dropped, with why (for the log).
  const std::vector<stereo::StereoPoint>& stereo_at_lidar_time() const { return stereo_; }
  const std::vector<stereo::Drop>& last_stereo_drops() const { return drops_; }
  // Of the last Fuse call: the lidar objects as fused, each with the point covariance fusion
  // gave it (FuseObjectsResult::lidar), for metrics of the lidar's own consistency.
  const LidarObjectFrame& lidar_as_fused() const { return lidar_; }
  // Of the last Fuse call: the lidar objects left out as fragments or pieces of a body
  // (fuse_objects.h), fragments first.
  const std::vector<std::uint32_t>& last_left_out_lidar_ids() const { return left_out_; }

 private:
  FusedObjectFrame FuseWith(const LidarObjectFrame& lidar, const StereoFrame& stereo,
                            const std::optional<Pose2>& ego_pose_at_stereo);

  FusionOptions options_;
  FusionStats stats_;
  std::optional<TimeNs> previous_stamp_;
  Pose2 previous_ego_pose_;
  std::vector<stereo::StereoPoint> stereo_;
  std::vector<stereo::Drop> drops_;
  LidarObjectFrame lidar_;
  std::vector<std::uint32_t> left_out_;
  // By camera track id: its last pair (pair_memory.h). A map, for a deterministic order.
  std::map<std::uint32_t, PairMemory> pairs_;
};

}  // namespace lookout::fusion
