// fusemap_bench_images: the pictures of tools/bench_logs.sh. A reference map drawn from a log's
// scans at GMapping's poses with our own grid code, a side-by-side of two maps, a contact sheet.
#include <cstdio>
#include <string>
#include <vector>

#include "fusemap/common/command_line.h"
#include "fusemap/io/image_panels.h"
#include "fusemap/io/reference_map.h"
#include "fusemap/io/slam_config.h"
#include "fusemap/io/tum_trajectory.h"

namespace fusemap {
namespace {

constexpr char kUsage[] =
    "usage: fusemap_bench_images <command> [options]\n"
    "  reference-map --log LOG.lcm --poses REF.tum --config PROFILE.yaml --out MAP.png\n"
    "                [--anchor NODES.tum]\n"
    "      draws the log's scans at the given poses (fusemap_carmen2lcm --reference-poses) as\n"
    "      fusemap_offline draws its map (the profile's range gate, mounting, submap size,\n"
    "      resolution); --anchor moves the drawing so it starts at that trajectory's first pose\n"
    "  side-by-side --left A.png --left-title T --right B.png --right-title T --title T\n"
    "               --out OUT.png\n"
    "      two maps of the same scale side by side (shrunk together to at most 2400 px wide)\n"
    "  contact-sheet --out OUT.png [--columns 2] [--width 1200] IMAGE...\n"
    "      tiles the images, each scaled to --width pixels\n"
    "Exit codes: 0 success, 1 bad input or failed write, 2 usage error.\n";

int Fail(const std::string& error) {
  std::fprintf(stderr, "fusemap_bench_images: %s\n", error.c_str());
  return 1;
}

using common::CommandLine;

struct ReferenceMapArgs {
  std::string log_path, poses_path, config_path, out_path, anchor_path;
};

int ReferenceMap(const ReferenceMapArgs& a) {
  std::string error;
  io::SlamConfig config;
  eval::Trajectory poses, anchor;
  if (!io::LoadSlamConfig(a.config_path, &config, &error) ||
      !io::ReadTumTrajectoryFile(a.poses_path, &poses, &error)) {
    return Fail(error);
  }
  common::Rigid2d T_out_map;
  if (!a.anchor_path.empty()) {
    if (!io::ReadTumTrajectoryFile(a.anchor_path, &anchor, &error)) return Fail(error);
    if (!io::AnchorOnFirstPose(poses, anchor, &T_out_map)) {
      return Fail(a.poses_path + ": no pose at the first stamp of " + a.anchor_path);
    }
  }
  io::ReferenceMap map;
  if (!io::RenderLogAtPoses(a.log_path, config, poses, T_out_map, &map, &error) ||
      !io::WriteMapPng(map.map, map.trajectory_xy, a.out_path, &error)) {
    return Fail(error);
  }
  std::printf("reference_map: scans=%d drawn=%d width_px=%d height_px=%d resolution_m=%g wrote=%s\n",
              map.scans_read, map.scans_used, map.map.width, map.map.height,
              map.map.resolution_m, a.out_path.c_str());
  return 0;
}

int RunReferenceMap(int argc, char** argv) {
  ReferenceMapArgs args;
  CommandLine command_line("fusemap_bench_images reference-map", kUsage);
  command_line.AddString("--log", &args.log_path, CommandLine::Required::kYes);
  command_line.AddString("--poses", &args.poses_path, CommandLine::Required::kYes);
  command_line.AddString("--config", &args.config_path, CommandLine::Required::kYes);
  command_line.AddString("--out", &args.out_path, CommandLine::Required::kYes);
  command_line.AddString("--anchor", &args.anchor_path);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  return ReferenceMap(args);
}

int RunSideBySide(int argc, char** argv) {
  std::string left, left_title, right, right_title, title, out;
  CommandLine command_line("fusemap_bench_images side-by-side", kUsage);
  command_line.AddString("--left", &left, CommandLine::Required::kYes);
  command_line.AddString("--left-title", &left_title, CommandLine::Required::kYes);
  command_line.AddString("--right", &right, CommandLine::Required::kYes);
  command_line.AddString("--right-title", &right_title, CommandLine::Required::kYes);
  command_line.AddString("--title", &title, CommandLine::Required::kYes);
  command_line.AddString("--out", &out, CommandLine::Required::kYes);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  std::string error;
  if (!io::WriteSideBySideFile(left, left_title, right, right_title, title, out, &error)) {
    return Fail(error);
  }
  std::printf("wrote %s\n", out.c_str());
  return 0;
}

int RunContactSheet(int argc, char** argv) {
  std::string out;
  int columns = 2, width_px = 1200;
  std::vector<std::string> images;
  CommandLine command_line("fusemap_bench_images contact-sheet", kUsage);
  command_line.AddString("--out", &out, CommandLine::Required::kYes);
  command_line.AddInt("--columns", &columns, 1, 100000);
  command_line.AddInt("--width", &width_px, 1, 100000);
  command_line.AddPositionalList("IMAGE", &images, 1);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  std::string error;
  if (!io::WriteContactSheetFile(images, columns, width_px, out, &error)) return Fail(error);
  std::printf("wrote %s (%zu images)\n", out.c_str(), images.size());
  return 0;
}

}  // namespace
}  // namespace fusemap

int main(int argc, char** argv) {
  return fusemap::common::RunSubcommand("fusemap_bench_images", fusemap::kUsage,
                                        {{"reference-map", fusemap::RunReferenceMap},
                                         {"side-by-side", fusemap::RunSideBySide},
                                         {"contact-sheet", fusemap::RunContactSheet}},
                                        argc, argv);
}
