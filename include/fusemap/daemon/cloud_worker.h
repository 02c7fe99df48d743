#ifndef FUSEMAP_DAEMON_CLOUD_WORKER_H_
#define FUSEMAP_DAEMON_CLOUD_WORKER_H_

#include <chrono>
#include <set>
#include <vector>

#include "fusemap/cloud/cloud_mapper.h"
#include "fusemap/session/cloud_stage.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/daemon/cloud_region_publisher.h"
#include "fusemap/sensor/rgbd_frame.h"

namespace fusemap {
namespace daemon {

// The RGB-D thread's state: the session's cloud stage fed from pose updates and frames, and
// the bookkeeping of which regions changed since they were last published. Changed regions are
// published at most every kPublishPeriod, a few per tick, newest submap first; a region
// changes when a frame binds to it or its submap moves (points removed from older regions
// by dynamic carving go out with that region's next change). One owner thread.
class CloudWorker {
 public:
  static constexpr std::chrono::milliseconds kPublishPeriod{500};
  static constexpr int kRegionsPerTick = 4;
  static constexpr size_t kMaxPointsPerRegion = 20000;

  // `stage` (the session's) must outlive the worker; `publisher` may be null (nothing
  // published).
  CloudWorker(session::CloudStage* stage, CloudRegionPublisher* publisher);

  void AddPoseUpdate(const session::CloudPoseUpdate& update);
  void AddFrame(const sensor::RgbdFrame& frame);
  // End of input: binds what can be bound and publishes every changed region.
  void Finish();
  void MaybePublish(std::chrono::steady_clock::time_point now);

  const cloud::CloudMapper& mapper() const { return stage_->mapper(); }

 private:
  void MarkIfBound(int64_t frames_bound_before);
  void Publish(int max_regions);

  session::CloudStage* const stage_;
  CloudRegionPublisher* const publisher_;
  std::set<int> changed_;
  int current_submap_id_ = -1;
  double last_stamp_s_ = 0.0;
  std::chrono::steady_clock::time_point last_publish_;
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_CLOUD_WORKER_H_
