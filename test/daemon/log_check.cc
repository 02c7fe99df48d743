// Test helper for netns_integration.sh: reads an lcm-logger recording of fusemapd's outputs and
// checks that poses and health messages were published and decode. Prints one summary line.
#include <cstdio>
#include <string>

#include "fusemap/io/lcm_log.h"
#include "fusemap/io/lcm_output_conversions.h"

int main(int argc, char** argv) {
  if (argc != 2 || std::string(argv[1]) == "--help") {
    std::fprintf(stderr, "usage: daemon_log_check RECORDED.lcm\n");
    return 2;
  }
  fusemap::io::LcmLogReader reader;
  std::string error;
  if (!reader.Open(argv[1], &error)) {
    std::fprintf(stderr, "daemon_log_check: %s\n", error.c_str());
    return 2;
  }
  int poses = 0, health = 0, submap_lists = 0, bad = 0;
  int64_t last_nodes = 0, last_lidar_received = 0;
  fusemap::io::LogEvent event;
  while (reader.Next(&event)) {
    const int size = static_cast<int>(event.data.size());
    double stamp_s = 0.0;
    if (event.channel == "FUSEMAP_POSE") {
      fusemap::io::PoseMessage pose;
      fusemap::io::DecodePose(event.data.data(), size, &pose, &error) ? ++poses : ++bad;
    } else if (event.channel == "FUSEMAP_HEALTH") {
      fusemap::io::HealthReport report;
      if (!fusemap::io::DecodeHealth(event.data.data(), size, &stamp_s, &report, &error)) {
        ++bad;
        continue;
      }
      ++health;
      last_nodes = report.nodes;
      for (const auto& channel : report.channels) {
        if (channel.name == "LIDAR") last_lidar_received = channel.received;
      }
    } else if (event.channel == "FUSEMAP_SUBMAPS") {
      fusemap::pose_graph::PoseGraphSnapshot snapshot;
      fusemap::io::DecodeSubmapList(event.data.data(), size, &stamp_s, &snapshot, &error)
          ? ++submap_lists
          : ++bad;
    }
  }
  std::printf("poses=%d health=%d submap_lists=%d undecodable=%d last_health_nodes=%lld "
              "last_health_lidar_received=%lld\n",
              poses, health, submap_lists, bad, static_cast<long long>(last_nodes),
              static_cast<long long>(last_lidar_received));
  return poses > 0 && health > 0 && submap_lists > 0 && bad == 0 && last_nodes > 0 ? 0 : 1;
}
