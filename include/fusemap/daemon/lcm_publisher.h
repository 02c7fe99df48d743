#ifndef FUSEMAP_DAEMON_LCM_PUBLISHER_H_
#define FUSEMAP_DAEMON_LCM_PUBLISHER_H_

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "fusemap/daemon/publisher.h"

namespace lcm {
class LCM;
}  // namespace lcm

namespace fusemap {
namespace daemon {

struct OutputChannels {
  std::string pose = "FUSEMAP_POSE";
  std::string submap_list = "FUSEMAP_SUBMAPS";
  std::string loop_closure = "FUSEMAP_LOOP_CLOSURE";
  std::string health = "FUSEMAP_HEALTH";
};

// Publishes the engine's outputs as fusemap_lcm pose_t, submap_list_t, loop_closure_t and
// health_t, encoded by io/lcm_output_conversions.h. `lcm` may be null (file:// replay with
// nowhere to publish): nothing is then encoded or sent, and published() stays 0. With
// `health_to_stderr`, each health report is also logged as one line.
class LcmPublisher : public Publisher {
 public:
  LcmPublisher(lcm::LCM* lcm, OutputChannels channels, bool health_to_stderr);

  void PublishPose(double stamp_s, const common::Rigid2d& T_map_tracking) override;
  void PublishSubmapList(double stamp_s, const pose_graph::PoseGraphSnapshot& snapshot) override;
  void PublishLoopClosure(double stamp_s, int new_loop_closures,
                          const pose_graph::PoseGraph2D::Stats& stats, int latest_node,
                          const io::LoopNote& note) override;
  void PublishHealth(double stamp_s, const HealthReport& report) override;

  int64_t published() const { return published_; }
  int64_t failed() const { return failed_; }

 private:
  // Publishes encoded bytes; lcm_ must not be null.
  void Send(const std::string& channel, const std::vector<uint8_t>& bytes);

  lcm::LCM* const lcm_;
  const OutputChannels channels_;
  const bool health_to_stderr_;
  std::atomic<int64_t> published_{0};
  std::atomic<int64_t> failed_{0};
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_LCM_PUBLISHER_H_
