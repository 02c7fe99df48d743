#ifndef FUSEMAP_TOOLS_OFFLINE_OFFLINE_RUN_H_
#define FUSEMAP_TOOLS_OFFLINE_OFFLINE_RUN_H_

#include <optional>
#include <string>

namespace fusemap {
namespace offline_tool {

// fusemap_offline's command line (see its usage text in main.cc).
struct Args {
  std::string log, config, out;
  bool loop_closure = true;
  bool cloud = true;
  // Overrides visual_loop.enabled when set (--visual-loop / --no-visual-loop).
  std::optional<bool> visual_loop;
  int threads = 1;
  bool quiet = false;
  std::string relations;
  double relations_time_offset_s = 0.0;
  std::string relations_stamp_map;
  bool calibrate_odometry = false;
};

// Maps the log through a session::SlamSession, writes the outputs and prints the summary.
// Returns the exit code (0 written, 1 bad input or outputs not written, 2 configuration error).
int Run(const Args& args);

}  // namespace offline_tool
}  // namespace fusemap

#endif  // FUSEMAP_TOOLS_OFFLINE_OFFLINE_RUN_H_
