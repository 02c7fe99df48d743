#ifndef FUSEMAP_DAEMON_CLOUD_WORKER_H_
#define FUSEMAP_DAEMON_CLOUD_WORKER_H_

#include <chrono>
#include <map>
#include <set>
#include <vector>

#include "fusemap/cloud/cloud_mapper.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/daemon/cloud_region_publisher.h"
#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace daemon {

// What the SLAM thread tells the RGB-D thread after a scan (MapBuilder2D::ScanResult) and when
// submaps were added or moved: a message, so the two threads share no mutable state.
struct CloudPoseMessage {
  double stamp_s = 0.0;
  int submap_id = -1;  // -1: no scan pose in this message, only submap poses
  common::Rigid2d T_local_tracking;
  common::Rigid2d T_local_submap;
  std::vector<common::Rigid2d> T_map_submaps;  // every submap's pose by index; empty: unchanged
};

// The RGB-D thread's state: the cloud mapper fed from pose messages and frames, and the
// bookkeeping of which regions changed since they were last published. Changed regions are
// published at most every kPublishPeriod, a few per tick, newest submap first; a region
// changes when a frame binds to it or its submap moves (points removed from older regions
// by dynamic carving go out with that region's next change). One owner thread.
class CloudWorker {
 public:
  static constexpr std::chrono::milliseconds kPublishPeriod{500};
  static constexpr int kRegionsPerTick = 4;
  static constexpr size_t kMaxPointsPerRegion = 20000;

  // `publisher` may be null (nothing published).
  CloudWorker(const cloud::CloudMapperOptions& options, CloudRegionPublisher* publisher);

  void AddPoseMessage(const CloudPoseMessage& message);
  void AddFrame(const sensor::RgbdFrame& frame);
  // End of input: binds what can be bound and publishes every changed region.
  void Finish();
  void MaybePublish(std::chrono::steady_clock::time_point now);

  const cloud::CloudMapper& mapper() const { return mapper_; }

 private:
  void MarkIfBound(int64_t frames_bound_before);
  void Publish(int max_regions);

  cloud::CloudMapper mapper_;
  CloudRegionPublisher* const publisher_;
  std::map<int, common::Rigid2d> T_map_submaps_;
  std::set<int> changed_;
  int current_submap_id_ = -1;
  double last_stamp_s_ = 0.0;
  std::chrono::steady_clock::time_point last_publish_;
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_CLOUD_WORKER_H_
