#include "lookout/fusion/fusion_engine.h"

#include <cmath>
#include <utility>

#include "lookout/fusion/fuse_objects.h"
#include "lookout/fusion/stereo_prediction.h"

namespace lookout::fusion {

FusionEngine::FusionEngine(FusionOptions options) : options_(std::move(options)) {
  options_.Validate();
}

FusedObjectFrame FusionEngine::Fuse(const LidarObjectFrame& lidar,
                                    const StereoFrame& latest_stereo) {
  std::optional<Pose2> ego_at_stereo;
  const bool increasing = !previous_stamp_ || lidar.stamp > *previous_stamp_;
  if (!increasing) ++stats_.lidar_stamps_not_increasing;
  if (latest_stereo.stamp == lidar.stamp) {
    ego_at_stereo = lidar.ego_pose;
  } else if (previous_stamp_ && increasing) {
    ego_at_stereo = InterpolatePose(*previous_stamp_, previous_ego_pose_, lidar.stamp,
                                    lidar.ego_pose, latest_stereo.stamp);
  }
  FusedObjectFrame frame = FuseWith(lidar, latest_stereo, ego_at_stereo);
  if (increasing) {
    previous_stamp_ = lidar.stamp;
    previous_ego_pose_ = lidar.ego_pose;
  } else {
    previous_stamp_.reset();  // start again from this frame's successor
  }
  return frame;
}

FusedObjectFrame FusionEngine::Fuse(const LidarObjectFrame& lidar,
                                    const StereoFrame& latest_stereo,
                                    const Pose2& ego_pose_at_stereo) {
  return FuseWith(lidar, latest_stereo, ego_pose_at_stereo);
}

FusedObjectFrame FusionEngine::FuseWith(const LidarObjectFrame& lidar, const StereoFrame& stereo,
                                        const std::optional<Pose2>& ego_pose_at_stereo) {
  ++stats_.frames;
  stereo_.clear();
  drops_.clear();
  if (!stereo.objects.empty()) {
    const double dt_s = ToSeconds(lidar.stamp - stereo.stamp);
    if (std::abs(dt_s) > options_.max_stereo_age_s) {
      ++stats_.stereo_frames_stale;
    } else if (!ego_pose_at_stereo) {
      ++stats_.stereo_frames_without_ego_pose;
    } else {
      ++stats_.stereo_frames_used;
      stereo::ProjectedStereoFrame projected =
          stereo::ProjectStereoFrame(stereo, lidar.mount, options_.stereo);
      drops_ = std::move(projected.drops);
      for (const stereo::Drop& drop : drops_) stats_.stereo_drops.Add(drop.reason);
      const Pose2 lidar_from_stereo_vehicle = lidar.ego_pose.Inverse() * *ego_pose_at_stereo;
      stereo_.reserve(projected.objects.size());
      for (const stereo::StereoPoint& point : projected.objects) {
        stereo_.push_back(PredictStereoPoint(point, dt_s, lidar_from_stereo_vehicle,
                                             lidar.mount, options_.acceleration_sigma_mps2));
      }
    }
  }
  // Each camera track's last pair where it puts the body now; then this frame's pairs
  // remembered, and memories too old to use forgotten.
  std::vector<PairPrior> priors;
  if (options_.pair_memory_s > 0.0) {
    for (const auto& [id, memory] : pairs_) {
      const std::optional<stereo::CartesianPoint> prior =
          PredictPairPrior(memory, lidar.stamp, lidar.ego_pose, options_.acceleration_sigma_mps2,
                           options_.pair_memory_s);
      if (!prior) continue;
      PairPrior p{std::nullopt, *prior};
      for (std::size_t i = 0; i < stereo_.size(); ++i) {
        if (stereo_[i].id == id) p.stereo = i;
      }
      priors.push_back(p);
    }
  }
  FuseObjectsResult result = FuseObjects(lidar, stereo_, options_, priors);
  if (options_.pair_memory_s > 0.0) {
    for (const FusedObject& f : result.frame.objects) {
      if (f.sensor_count != 2 || !f.stereo_id || f.footprint_pair) continue;
      pairs_[*f.stereo_id] = RememberPair(f, lidar.stamp, lidar.ego_pose);
    }
    std::erase_if(pairs_, [&](const auto& entry) {
      return ToSeconds(lidar.stamp - entry.second.stamp) > options_.pair_memory_s ||
             entry.second.stamp > lidar.stamp;
    });
  }
  stats_.pairs += static_cast<std::int64_t>(result.pairs);
  stats_.lidar_objects_dropped += static_cast<std::int64_t>(result.dropped_lidar_ids.size());
  stats_.lidar_fragments += static_cast<std::int64_t>(result.fragment_lidar_ids.size());
  stats_.lidar_pieces += static_cast<std::int64_t>(result.piece_lidar_ids.size());
  left_out_ = std::move(result.fragment_lidar_ids);
  left_out_.insert(left_out_.end(), result.piece_lidar_ids.begin(), result.piece_lidar_ids.end());
  lidar_ = std::move(result.lidar);
  return std::move(result.frame);
}

}  // namespace lookout::fusion
