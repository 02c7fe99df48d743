#include "cloud_feed.h"

namespace fusemap {
namespace offline_tool {

void CloudFeed::AddScan(const pose_graph::MapBuilder2D& builder, double stamp_s,
                        const pose_graph::MapBuilder2D::ScanResult& result) {
  const auto stats = builder.pose_graph().stats();
  if (stats.submaps != seen_submaps_ || stats.optimizations != seen_optimizations_) {
    seen_submaps_ = stats.submaps;
    seen_optimizations_ = stats.optimizations;
    UpdateSubmapPoses(builder);
  }
  if (result.submap_id < 0) return;
  Timed([&] {
    mapper_.AddLocalPose(stamp_s, result.T_local_tracking, result.submap_id,
                         result.T_local_submap);
  });
}

void CloudFeed::AddFrame(const sensor::RgbdFrame& frame) {
  Timed([&] { mapper_.AddFrame(frame); });
}

void CloudFeed::Finish(const pose_graph::MapBuilder2D& builder) {
  Timed([&] { mapper_.Finish(); });
  UpdateSubmapPoses(builder);
  final_update_ms_ = last_update_ms_;
}

void CloudFeed::UpdateSubmapPoses(const pose_graph::MapBuilder2D& builder) {
  const auto snapshot = builder.pose_graph().Snapshot();
  const auto t0 = std::chrono::steady_clock::now();
  mapper_.UpdateSubmapPoses(snapshot->T_map_submaps);
  last_update_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  total_s_ += 1e-3 * last_update_ms_;
  update_ms_.push_back(last_update_ms_);
  final_update_regions_ = mapper_.binder().stats().last_update_regions;
  final_update_points_ = mapper_.binder().stats().last_update_points;
}

}  // namespace offline_tool
}  // namespace fusemap
