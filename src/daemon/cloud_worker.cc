#include "fusemap/daemon/cloud_worker.h"

#include <iterator>

namespace fusemap {
namespace daemon {

constexpr std::chrono::milliseconds CloudWorker::kPublishPeriod;
constexpr int CloudWorker::kRegionsPerTick;
constexpr size_t CloudWorker::kMaxPointsPerRegion;

CloudWorker::CloudWorker(session::CloudStage* stage, CloudRegionPublisher* publisher)
    : stage_(stage), publisher_(publisher) {}

void CloudWorker::AddPoseUpdate(const session::CloudPoseUpdate& update) {
  // The session sends only submaps that are new or moved (PoseGraph2D::TakeSubmapPlacements).
  for (const cloud::SubmapPose2d& placement : update.placements) {
    changed_.insert(placement.submap);
  }
  if (update.submap_id >= 0) {
    current_submap_id_ = update.submap_id;
    last_stamp_s_ = update.stamp_s;
  }
  const int64_t bound = mapper().stats().frames_bound;
  stage_->Apply(update);
  MarkIfBound(bound);
}

void CloudWorker::AddFrame(const sensor::RgbdFrame& frame) {
  const int64_t bound = mapper().stats().frames_bound;
  stage_->AddFrame(frame);
  MarkIfBound(bound);
}

void CloudWorker::Finish() {
  const int64_t bound = mapper().stats().frames_bound;
  stage_->Finish();
  MarkIfBound(bound);
  Publish(static_cast<int>(changed_.size()));
}

void CloudWorker::MarkIfBound(int64_t frames_bound_before) {
  // Frames bind to the submap active at their stamp: the current one, or at a submap switch
  // the one before it.
  if (mapper().stats().frames_bound > frames_bound_before && current_submap_id_ >= 0) {
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
    const cloud::ColorCloud::Ptr points = mapper().binder().RegionCloud(id);
    if (!points || points->empty()) continue;
    // Where the mapper placed the region's submap (a submap global SLAM has not placed yet
    // sits at its local pose).
    const auto it = mapper().T_map_submaps().find(id);
    if (it == mapper().T_map_submaps().end()) continue;
    publisher_->PublishCloudRegion(MakeCloudRegionUpdate(
        last_stamp_s_, id, common::Rigid3d::FromRigid2d(it->second), *points,
        kMaxPointsPerRegion));
    ++published;
  }
}

}  // namespace daemon
}  // namespace fusemap
