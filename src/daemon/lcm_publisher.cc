#include "fusemap/daemon/lcm_publisher.h"

#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <utility>

#include "fusemap/io/lcm_output_conversions.h"

namespace fusemap {
namespace daemon {

LcmPublisher::LcmPublisher(lcm::LCM* lcm, OutputChannels channels, bool health_to_stderr)
    : lcm_(lcm), channels_(std::move(channels)), health_to_stderr_(health_to_stderr) {}

void LcmPublisher::Send(const std::string& channel, const std::vector<uint8_t>& bytes) {
  if (lcm_->publish(channel, bytes.data(), static_cast<unsigned int>(bytes.size())) == 0) {
    ++published_;
  } else {
    ++failed_;
  }
}

void LcmPublisher::PublishPose(double stamp_s, const common::Rigid2d& T_map_tracking) {
  if (lcm_ == nullptr) return;
  Send(channels_.pose, io::EncodePlanarPose(stamp_s, T_map_tracking));
}

void LcmPublisher::PublishSubmapList(double stamp_s,
                                     const pose_graph::PoseGraphSnapshot& snapshot) {
  if (lcm_ == nullptr) return;
  Send(channels_.submap_list, io::EncodeSubmapList(stamp_s, snapshot));
}

void LcmPublisher::PublishLoopClosure(double stamp_s, int new_loop_closures,
                                      const pose_graph::PoseGraph2D::Stats& stats,
                                      int latest_node, const io::LoopNote& note) {
  if (lcm_ == nullptr) return;
  Send(channels_.loop_closure,
       io::EncodeLoopClosure(stamp_s, new_loop_closures, stats, latest_node, note));
}

void LcmPublisher::PublishHealth(double stamp_s, const HealthReport& report) {
  if (lcm_ != nullptr) Send(channels_.health, io::EncodeHealth(stamp_s, report));
  if (health_to_stderr_) {
    std::fprintf(stderr, "fusemapd: t=%.1f %s\n", stamp_s, FormatHealth(report).c_str());
  }
}

}  // namespace daemon
}  // namespace fusemap
