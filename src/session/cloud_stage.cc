#include "fusemap/session/cloud_stage.h"

#include <chrono>

namespace fusemap {
namespace session {
namespace {

double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace

CloudStage::CloudStage(const cloud::CloudMapperOptions& options, bool record_cost)
    : mapper_(options), record_cost_(record_cost) {}

template <typename F>
void CloudStage::TimeFrames(F&& f) {
  if (!record_cost_) {
    f();
    return;
  }
  const int64_t bound = mapper_.stats().frames_bound;
  const auto start = std::chrono::steady_clock::now();
  f();
  const double ms = MillisecondsSince(start);
  cost_.total_s += 1e-3 * ms;
  const int64_t n = mapper_.stats().frames_bound - bound;
  for (int64_t i = 0; i < n; ++i) cost_.frame_ms.push_back(ms / static_cast<double>(n));
}

void CloudStage::Place(const std::vector<cloud::SubmapPose2d>& placements) {
  if (placements.empty()) return;
  const auto start = std::chrono::steady_clock::now();
  mapper_.PlaceSubmaps(placements);
  if (!record_cost_) return;
  const double ms = MillisecondsSince(start);
  cost_.total_s += 1e-3 * ms;
  cost_.update_ms.push_back(ms);
}

void CloudStage::Apply(const CloudPoseUpdate& update) {
  // Placements first: a new submap is placed before frames bind to it.
  Place(update.placements);
  if (update.submap_id < 0) return;
  TimeFrames([&] {
    mapper_.AddLocalPose(update.stamp_s, update.T_local_tracking, update.submap_id,
                         update.T_local_submap);
  });
}

void CloudStage::AddFrame(const sensor::RgbdFrame& frame) {
  TimeFrames([&] { mapper_.AddFrame(frame); });
}

void CloudStage::Finish(const CloudPoseUpdate& last_update) {
  const size_t updates = cost_.update_ms.size();
  Apply(last_update);
  if (record_cost_) {
    cost_.final_update_ms = cost_.update_ms.size() > updates ? cost_.update_ms.back() : 0.0;
    cost_.final_update_regions = mapper_.binder().stats().last_update_regions;
    cost_.final_update_points = mapper_.binder().stats().last_update_points;
  }
  TimeFrames([&] { mapper_.Finish(); });
}

}  // namespace session
}  // namespace fusemap
