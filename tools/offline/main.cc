// fusemap_offline: runs 2D SLAM over a recorded LCM log as fast as the CPU allows and writes
// the trajectory, node poses, occupancy map and, with RGB-D frames, the coloured cloud.
#include "fusemap/common/command_line.h"
#include "offline_run.h"

namespace {

constexpr char kUsage[] =
    "usage: fusemap_offline --log LOG.lcm --config CONFIG.yaml --out DIR [options]\n"
    "\n"
    "Runs laser SLAM over an LCM log as fast as the CPU allows and writes DIR/trajectory.tum\n"
    "(a pose per odometry sample: the odometry between the two neighbouring nodes,\n"
    "blended by time), DIR/nodes.tum,\n"
    "DIR/odometry.tum (the odometry input as received),\n"
    "DIR/map.pgm + DIR/map.yaml (map_server) and DIR/map.png (map with trajectory).\n"
    "With RGB-D frames on the config's rgbd channel (and cloud.enabled) also the coloured map:\n"
    "DIR/cloud.ply, DIR/cloud.pcd, DIR/cloud_removed.ply (points removed as dynamic),\n"
    "DIR/octomap.bt, DIR/octomap.ot and DIR/cloud.png (an oblique rendering).\n"
    "\n"
    "options:\n"
    "  --no-loop-closure   local SLAM only (no loop-closure search, no optimisation)\n"
    "  --no-cloud          ignore RGB-D frames (as cloud.enabled: false)\n"
    "  --visual-loop       run the ORB visual loop checker on the RGB-D frames (as\n"
    "                      visual_loop.enabled: true); writes DIR/loops.tsv\n"
    "  --no-visual-loop    as visual_loop.enabled: false\n"
    "  --threads N         worker threads for loop-closure search and optimisation (default 1:\n"
    "                      reproducible; more is faster but no longer bit-for-bit repeatable)\n"
    "  --quiet             no progress line\n"
    "  --relations FILE    also print the Kuemmerle et al. (2009) relation error of\n"
    "                      DIR/trajectory.tum against FILE (as fusemap_eval relations)\n"
    "  --relations-time-offset S  seconds subtracted from the relation stamps\n"
    "  --relations-stamp-map FILE  relation stamps are on the raw log's clock: look them up\n"
    "                      at the records that printed them (fusemap_carmen2lcm --stamp-map)\n"
    "  --calibrate-odometry  fit the wheel odometry's systematic errors (distance scale,\n"
    "                      rotation scale, heading drift per metre) to the optimised node-to-node\n"
    "                      motion and densify DIR/trajectory.tum with the corrected odometry;\n"
    "                      falls back to the raw odometry when the fit is not determined\n"
    "  --help              this text\n"
    "\n"
    "The last line printed is `scans=N wall_s=W realtime_factor=R cpu_s=C cpu_realtime_factor=F`\n"
    "(R: log seconds per wall second; F: log seconds per CPU second, all threads).\n"
    "Exit codes: 0 outputs written, 1 bad input (unreadable log or relations, no usable scans)\n"
    "or outputs not written, 2 command-line usage or configuration error.\n";

}  // namespace

int main(int argc, char** argv) {
  fusemap::offline_tool::Args args;
  fusemap::common::CommandLine command_line("fusemap_offline", kUsage);
  using Required = fusemap::common::CommandLine::Required;
  command_line.AddString("--log", &args.log, Required::kYes);
  command_line.AddString("--config", &args.config, Required::kYes);
  command_line.AddString("--out", &args.out, Required::kYes);
  command_line.AddFlag("--no-loop-closure", &args.loop_closure, false);
  command_line.AddFlag("--no-cloud", &args.cloud, false);
  bool visual_loop_on = false, visual_loop_off = false;
  command_line.AddFlag("--visual-loop", &visual_loop_on);
  command_line.AddFlag("--no-visual-loop", &visual_loop_off);
  command_line.AddInt("--threads", &args.threads, 1, 64);
  command_line.AddFlag("--quiet", &args.quiet);
  command_line.AddString("--relations", &args.relations);
  command_line.AddDouble("--relations-time-offset", &args.relations_time_offset_s);
  command_line.AddString("--relations-stamp-map", &args.relations_stamp_map);
  command_line.AddFlag("--calibrate-odometry", &args.calibrate_odometry);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv)) return *exit_code;
  if (visual_loop_on && visual_loop_off) {
    return command_line.UsageError("--visual-loop and --no-visual-loop exclude each other");
  }
  if (visual_loop_on || visual_loop_off) args.visual_loop = visual_loop_on;
  if (args.relations.empty() && !args.relations_stamp_map.empty()) {
    return command_line.UsageError("--relations-stamp-map needs --relations");
  }
  return fusemap::offline_tool::Run(args);
}
