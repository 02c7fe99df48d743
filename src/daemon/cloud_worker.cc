#include "fusemap/daemon/cloud_worker.h"

#include <iterator>

namespace fusemap {
namespace daemon {

constexpr std::chrono::milliseconds CloudWorker::kPublishPeriod;
constexpr int CloudWorker::kRegionsPerTick;
constexpr size_t CloudWorker::kMaxPointsPerRegion;

CloudWorker::CloudWorker(const cloud::CloudMapperOptions& options, CloudRegionPublisher* publisher)
    : mapper_(options), publisher_(publisher) {}

void CloudWorker::AddPoseMessage(const CloudPoseMessage& message) {
  if (!message.T_map_submaps.empty()) {
    for (size_t i = 0; i < message.T_map_submaps.size(); ++i) {
      const int id = static_cast<int>(i);
      const auto it = T_map_submaps_.find(id);
      const common::Rigid2d& T = message.T_map_submaps[i];
      if (it == T_map_submaps_.end() ||
          (it->second.translation() - T.translation()).squaredNorm() > 0.0 ||
          it->second.angle_rad() != T.angle_rad()) {
        T_map_submaps_[id] = T;
        changed_.insert(id);
      }
    }
    mapper_.UpdateSubmapPoses(message.T_map_submaps);
  }
  if (message.submap_id < 0) return;
  // As the mapper: a submap global SLAM has not placed yet sits at its local pose.
  T_map_submaps_.emplace(message.submap_id, message.T_local_submap);
  current_submap_id_ = message.submap_id;
  last_stamp_s_ = message.stamp_s;
  const int64_t bound = mapper_.stats().frames_bound;
  mapper_.AddLocalPose(message.stamp_s, message.T_local_tracking, message.submap_id,
                       message.T_local_submap);
  MarkIfBound(bound);
}

void CloudWorker::AddFrame(const sensor::RgbdFrame& frame) {
  const int64_t bound = mapper_.stats().frames_bound;
  mapper_.AddFrame(frame);
  MarkIfBound(bound);
}

void CloudWorker::Finish() {
  const int64_t bound = mapper_.stats().frames_bound;
  mapper_.Finish();
  MarkIfBound(bound);
  Publish(static_cast<int>(changed_.size()));
}

void CloudWorker::MarkIfBound(int64_t frames_bound_before) {
  // Frames bind to the submap active at their stamp: the current one, or at a submap switch
  // the one before it.
  if (mapper_.stats().frames_bound > frames_bound_before && current_submap_id_ >= 0) {
    changed_.insert(current_submap_id_);
    if (current_submap_id_ > 0) changed_.insert(current_submap_id_ - 1);
  }
}

void CloudWorker::MaybePublish(std::chrono::steady_clock::time_point now) {
  if (now - last_publish_ < kPublishPeriod) return;
  last_publish_ = now;
  Publish(kRegionsPerTick);
}

void CloudWorker::Publish(int max_regions) {
  int published = 0;
  while (!changed_.empty() && published < max_regions) {
    const auto newest = std::prev(changed_.end());
    const int id = *newest;
    changed_.erase(newest);
    if (publisher_ == nullptr) continue;
    const cloud::ColorCloud::Ptr points = mapper_.binder().RegionCloud(id);
    if (!points || points->empty()) continue;
    const auto it = T_map_submaps_.find(id);
    if (it == T_map_submaps_.end()) continue;
    publisher_->PublishCloudRegion(MakeCloudRegionUpdate(
        last_stamp_s_, id, common::Rigid3d::FromRigid2d(it->second), *points,
        kMaxPointsPerRegion));
    ++published;
  }
}

}  // namespace daemon
}  // namespace fusemap
