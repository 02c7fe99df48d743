#include "fusemap/daemon/cloud_region_publisher.h"

#include <algorithm>
#include <lcm/lcm-cpp.hpp>
#include <utility>

#include <vector>

#include "fusemap/io/lcm_output_conversions.h"

namespace fusemap {
namespace daemon {

CloudRegionUpdate MakeCloudRegionUpdate(double stamp_s, int submap_id,
                                        const common::Rigid3d& T_map_submap,
                                        const cloud::ColorCloud& map_points, size_t max_points) {
  CloudRegionUpdate update;
  update.stamp_s = stamp_s;
  update.submap_id = submap_id;
  update.T_map_submap = T_map_submap;
  update.total_points = map_points.size();
  update.points_submap.reset(new cloud::ColorCloud);
  const size_t stride =
      max_points == 0 ? map_points.size() + 1 : (map_points.size() + max_points - 1) / max_points;
  const common::Rigid3d T_submap_map = T_map_submap.inverse();
  for (size_t i = 0; i < map_points.size(); i += std::max<size_t>(stride, 1)) {
    cloud::ColorPoint p = map_points[i];
    const Eigen::Vector3d q = T_submap_map * Eigen::Vector3d(p.x, p.y, p.z);
    p.x = static_cast<float>(q.x());
    p.y = static_cast<float>(q.y());
    p.z = static_cast<float>(q.z());
    update.points_submap->push_back(p);
  }
  return update;
}

LcmCloudRegionPublisher::LcmCloudRegionPublisher(lcm::LCM* lcm, std::string channel)
    : lcm_(lcm), channel_(std::move(channel)) {}

void LcmCloudRegionPublisher::PublishCloudRegion(const CloudRegionUpdate& update) {
  ++published_;
  if (lcm_ == nullptr) return;
  const std::vector<uint8_t> bytes = io::EncodeCloudRegion(update);
  lcm_->publish(channel_, bytes.data(), static_cast<unsigned int>(bytes.size()));
}

}  // namespace daemon
}  // namespace fusemap
