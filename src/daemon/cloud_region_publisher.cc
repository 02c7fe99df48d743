#include "fusemap/daemon/cloud_region_publisher.h"

#include <algorithm>
#include <lcm/lcm-cpp.hpp>
#include <utility>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap_lcm/cloud_region_t.hpp"

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
  fusemap_lcm::cloud_region_t msg;
  msg.utime = io::StampToUtime(update.stamp_s);
  msg.submap_id = update.submap_id;
  const Eigen::Vector3d t = update.T_map_submap.translation();
  const Eigen::Quaterniond q = update.T_map_submap.rotation();
  msg.T_map_submap.translation[0] = t.x();
  msg.T_map_submap.translation[1] = t.y();
  msg.T_map_submap.translation[2] = t.z();
  msg.T_map_submap.rotation[0] = q.w();
  msg.T_map_submap.rotation[1] = q.x();
  msg.T_map_submap.rotation[2] = q.y();
  msg.T_map_submap.rotation[3] = q.z();
  msg.total_points = static_cast<int32_t>(update.total_points);
  const cloud::ColorCloud& points = *update.points_submap;
  msg.npoints = static_cast<int32_t>(points.size());
  msg.xyz.reserve(points.size());
  msg.rgb.reserve(points.size());
  for (const cloud::ColorPoint& p : points) {
    msg.xyz.push_back({p.x, p.y, p.z});
    msg.rgb.push_back({p.r, p.g, p.b});
  }
  ++published_;
  if (lcm_ != nullptr) lcm_->publish(channel_, &msg);
}

}  // namespace daemon
}  // namespace fusemap
