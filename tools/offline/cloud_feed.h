#ifndef FUSEMAP_TOOLS_OFFLINE_CLOUD_FEED_H_
#define FUSEMAP_TOOLS_OFFLINE_CLOUD_FEED_H_

#include <chrono>
#include <cstdint>
#include <vector>

#include "fusemap/cloud/cloud_mapper.h"
#include "fusemap/pose_graph/map_builder_2d.h"

namespace fusemap {
namespace offline_tool {

// Feeds the cloud mapper from the offline loop and times it. Submap poses are passed on when
// the pose graph's submap or optimisation count changes (a new submap is placed before frames
// bind to it); a final pass after the builder's Finish() picks up the last optimisation.
class CloudFeed {
 public:
  explicit CloudFeed(const cloud::CloudMapperOptions& options) : mapper_(options) {}

  void AddScan(const pose_graph::MapBuilder2D& builder, double stamp_s,
               const pose_graph::MapBuilder2D::ScanResult& result);
  void AddFrame(const sensor::RgbdFrame& frame);
  void Finish(const pose_graph::MapBuilder2D& builder);

  const cloud::CloudMapper& mapper() const { return mapper_; }
  const std::vector<double>& frame_ms() const { return frame_ms_; }
  const std::vector<double>& update_ms() const { return update_ms_; }
  double total_s() const { return total_s_; }
  double final_update_ms() const { return final_update_ms_; }
  size_t final_update_regions() const { return final_update_regions_; }
  size_t final_update_points() const { return final_update_points_; }

 private:
  // Time per bound frame: a call may bind several waiting frames, or none.
  template <typename F>
  void Timed(F&& f) {
    const int64_t bound = mapper_.stats().frames_bound;
    const auto t0 = std::chrono::steady_clock::now();
    f();
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    total_s_ += 1e-3 * ms;
    const int64_t n = mapper_.stats().frames_bound - bound;
    for (int64_t i = 0; i < n; ++i) frame_ms_.push_back(ms / static_cast<double>(n));
  }
  void UpdateSubmapPoses(const pose_graph::MapBuilder2D& builder);

  cloud::CloudMapper mapper_;
  int seen_submaps_ = -1, seen_optimizations_ = -1;
  std::vector<double> frame_ms_, update_ms_;
  double total_s_ = 0.0, last_update_ms_ = 0.0, final_update_ms_ = 0.0;
  size_t final_update_regions_ = 0, final_update_points_ = 0;
};

}  // namespace offline_tool
}  // namespace fusemap

#endif  // FUSEMAP_TOOLS_OFFLINE_CLOUD_FEED_H_
