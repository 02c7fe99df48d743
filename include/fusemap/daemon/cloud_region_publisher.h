#ifndef FUSEMAP_DAEMON_CLOUD_REGION_PUBLISHER_H_
#define FUSEMAP_DAEMON_CLOUD_REGION_PUBLISHER_H_

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fusemap/cloud/cloud_types.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/io/lcm_output_conversions.h"

namespace lcm {
class LCM;
}  // namespace lcm

namespace fusemap {
namespace daemon {

// One changed region of the coloured map, its points in the submap frame (defined in io,
// which encodes it as fusemap_lcm::cloud_region_t).
using CloudRegionUpdate = io::CloudRegionUpdate;

// `map_points` (map frame) in the submap frame, keeping every k-th point so at most
// `max_points` remain.
CloudRegionUpdate MakeCloudRegionUpdate(double stamp_s, int submap_id,
                                        const common::Rigid3d& T_map_submap,
                                        const cloud::ColorCloud& map_points, size_t max_points);

// Where the engine's cloud-region updates go; called only from the engine's RGB-D thread.
class CloudRegionPublisher {
 public:
  virtual ~CloudRegionPublisher() = default;
  virtual void PublishCloudRegion(const CloudRegionUpdate& update) = 0;
};

// As fusemap_lcm::cloud_region_t on `channel`; a null `lcm` only counts.
class LcmCloudRegionPublisher : public CloudRegionPublisher {
 public:
  LcmCloudRegionPublisher(lcm::LCM* lcm, std::string channel);
  void PublishCloudRegion(const CloudRegionUpdate& update) override;
  int64_t published() const { return published_; }

 private:
  lcm::LCM* const lcm_;
  const std::string channel_;
  std::atomic<int64_t> published_{0};
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_CLOUD_REGION_PUBLISHER_H_
