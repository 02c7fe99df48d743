// fusemap_bench_images: the pictures of tools/bench_logs.sh. A reference map drawn from a log's
// scans at GMapping's poses with our own grid code, a side-by-side of two maps, a contact sheet.
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

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

int Usage(const std::string& error) {
  std::fprintf(stderr, "fusemap_bench_images: %s\n%s", error.c_str(), kUsage);
  return 2;
}

int Fail(const std::string& error) {
  std::fprintf(stderr, "fusemap_bench_images: %s\n", error.c_str());
  return 1;
}

// `--key value` pairs from argv[2..] into *values; other words into *positional.
bool ParseArgs(int argc, char** argv, std::map<std::string, std::string>* values,
               std::vector<std::string>* positional, std::string* error) {
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0) {
      positional->push_back(arg);
    } else if (i + 1 < argc) {
      (*values)[arg] = argv[++i];
    } else {
      *error = "option " + arg + " needs a value";
      return false;
    }
  }
  return true;
}

// All `required` options given, and nothing but them and `optional`.
bool CheckOptions(const std::map<std::string, std::string>& values,
                  const std::vector<std::string>& required, const std::vector<std::string>& optional,
                  std::string* error) {
  for (const std::string& key : required) {
    if (values.count(key) == 0) {
      *error = "missing " + key;
      return false;
    }
  }
  for (const auto& [key, value] : values) {
    bool known = false;
    for (const std::string& k : required) known = known || k == key;
    for (const std::string& k : optional) known = known || k == key;
    if (!known) {
      *error = "unknown option " + key;
      return false;
    }
  }
  return true;
}

int RunReferenceMap(std::map<std::string, std::string>& a) {
  std::string error;
  io::SlamConfig config;
  eval::Trajectory poses, anchor;
  if (!io::LoadSlamConfig(a["--config"], &config, &error) ||
      !io::ReadTumTrajectoryFile(a["--poses"], &poses, &error)) {
    return Fail(error);
  }
  common::Rigid2d T_out_map;
  if (a.count("--anchor") > 0) {
    if (!io::ReadTumTrajectoryFile(a["--anchor"], &anchor, &error)) return Fail(error);
    if (!io::AnchorOnFirstPose(poses, anchor, &T_out_map)) {
      return Fail(a["--poses"] + ": no pose at the first stamp of " + a["--anchor"]);
    }
  }
  io::ReferenceMap map;
  if (!io::RenderLogAtPoses(a["--log"], config, poses, T_out_map, &map, &error) ||
      !io::WriteMapPng(map.map, map.trajectory_xy, a["--out"], &error)) {
    return Fail(error);
  }
  std::printf("reference_map: scans=%d drawn=%d width_px=%d height_px=%d resolution_m=%g wrote=%s\n",
              map.scans_read, map.scans_used, map.map.width, map.map.height,
              map.map.resolution_m, a["--out"].c_str());
  return 0;
}

bool PositiveInt(const std::string& text, int* value) {
  char* end = nullptr;
  const long parsed = std::strtol(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0' || parsed < 1 || parsed > 100000) return false;
  *value = static_cast<int>(parsed);
  return true;
}

}  // namespace
}  // namespace fusemap

int main(int argc, char** argv) {
  using fusemap::Fail;
  using fusemap::Usage;
  if (argc < 2) return Usage("missing command");
  const std::string command = argv[1];
  if (command == "--help" || command == "-h") {
    std::printf("%s", fusemap::kUsage);
    return 0;
  }
  std::map<std::string, std::string> a;
  std::vector<std::string> positional;
  std::string error;
  if (!fusemap::ParseArgs(argc, argv, &a, &positional, &error)) return Usage(error);
  if (command == "reference-map") {
    if (!positional.empty()) return Usage("unexpected argument " + positional[0]);
    if (!fusemap::CheckOptions(a, {"--log", "--poses", "--config", "--out"}, {"--anchor"}, &error)) {
      return Usage(error);
    }
    return fusemap::RunReferenceMap(a);
  }
  if (command == "side-by-side") {
    if (!positional.empty()) return Usage("unexpected argument " + positional[0]);
    if (!fusemap::CheckOptions(
            a, {"--left", "--left-title", "--right", "--right-title", "--title", "--out"}, {},
            &error)) {
      return Usage(error);
    }
    if (!fusemap::io::WriteSideBySideFile(a["--left"], a["--left-title"], a["--right"],
                                          a["--right-title"], a["--title"], a["--out"], &error)) {
      return Fail(error);
    }
    std::printf("wrote %s\n", a["--out"].c_str());
    return 0;
  }
  if (command == "contact-sheet") {
    int columns = 2, width_px = 1200;
    if (!fusemap::CheckOptions(a, {"--out"}, {"--columns", "--width"}, &error)) return Usage(error);
    if ((a.count("--columns") > 0 && !fusemap::PositiveInt(a["--columns"], &columns)) ||
        (a.count("--width") > 0 && !fusemap::PositiveInt(a["--width"], &width_px))) {
      return Usage("--columns and --width take a positive integer");
    }
    if (positional.empty()) return Usage("no images given");
    if (!fusemap::io::WriteContactSheetFile(positional, columns, width_px, a["--out"], &error)) {
      return Fail(error);
    }
    std::printf("wrote %s (%zu images)\n", a["--out"].c_str(), positional.size());
    return 0;
  }
  return Usage("unknown command '" + command + "'");
}
