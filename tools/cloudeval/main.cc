// fusemap_cloudeval: scores a coloured cloud map against the simulator's ground-truth world.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "cloud_eval.h"
#include "fusemap/io/cloud_writer.h"
#include "fusemap/sim/world_loader.h"

namespace {

constexpr char kUsage[] =
    "Usage: fusemap_cloudeval --cloud DIR/cloud.ply --world WORLD.yaml [options]\n"
    "Compares a map cloud (world frame) with the simulator's world and prints one line:\n"
    "  median_surface_dist_m=... dynamic_removed_frac=... static_kept_frac=...\n"
    "A point is dynamic if it is nearer to the volume swept by a walking person than to any\n"
    "static surface and farther than the tolerance from every static surface; else static.\n"
    "  median_surface_dist_m  median distance of the map's static points to static surfaces\n"
    "  dynamic_removed_frac   removed dynamic / all dynamic points (map + removed)\n"
    "  static_kept_frac       static points in the map / all static points (map + removed)\n"
    "Options:\n"
    "  --cloud FILE              map cloud, .ply or .pcd (required)\n"
    "  --world FILE              world description the log was simulated from (required)\n"
    "  --removed FILE            points removed as dynamic (default: cloud_removed.ply next to\n"
    "                            --cloud; if that is absent the fractions print as nan)\n"
    "  --static-tolerance-m M    (default 0.1)\n"
    "  --help                    this text\n";

bool ReadCloud(const std::string& path, fusemap::cloud::ColorCloud* cloud, std::string* error) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".pcd") return fusemap::io::ReadCloudPcd(path, cloud, error);
  return fusemap::io::ReadCloudPly(path, cloud, error);
}

}  // namespace

int main(int argc, char** argv) {
  std::string cloud_path, world_path, removed_path;
  double static_tolerance_m = 0.1;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "fusemap_cloudeval: %s needs a value (or unknown flag)\n%s",
                   flag.c_str(), kUsage);
      return 2;
    }
    const char* value = argv[++i];
    if (flag == "--cloud") {
      cloud_path = value;
    } else if (flag == "--world") {
      world_path = value;
    } else if (flag == "--removed") {
      removed_path = value;
    } else if (flag == "--static-tolerance-m") {
      char* end = nullptr;
      static_tolerance_m = std::strtod(value, &end);
      if (end == value || *end != '\0' || !(static_tolerance_m >= 0.0)) {
        std::fprintf(stderr, "fusemap_cloudeval: --static-tolerance-m expects a number >= 0, got '%s'\n",
                     value);
        return 2;
      }
    } else {
      std::fprintf(stderr, "fusemap_cloudeval: unknown flag %s\n%s", flag.c_str(), kUsage);
      return 2;
    }
  }
  if (cloud_path.empty() || world_path.empty()) {
    std::fprintf(stderr, "fusemap_cloudeval: --cloud and --world are required\n%s", kUsage);
    return 2;
  }

  std::string error;
  fusemap::sim::World world;
  if (!fusemap::sim::LoadWorldFile(world_path, &world, &error)) {
    std::fprintf(stderr, "fusemap_cloudeval: %s\n", error.c_str());
    return 1;
  }
  fusemap::cloud::ColorCloud kept;
  if (!ReadCloud(cloud_path, &kept, &error)) {
    std::fprintf(stderr, "fusemap_cloudeval: %s\n", error.c_str());
    return 1;
  }
  const bool removed_explicit = !removed_path.empty();
  if (!removed_explicit) {
    removed_path = (std::filesystem::path(cloud_path).parent_path() / "cloud_removed.ply").string();
  }
  fusemap::cloud::ColorCloud removed;
  bool have_removed = true;
  if (!removed_explicit && !std::filesystem::exists(removed_path)) {
    std::fprintf(stderr,
                 "fusemap_cloudeval: %s does not exist, so the removed points are unknown: "
                 "dynamic_removed_frac and static_kept_frac print as nan\n",
                 removed_path.c_str());
    have_removed = false;
  } else if (!ReadCloud(removed_path, &removed, &error)) {
    std::fprintf(stderr, "fusemap_cloudeval: %s\n", error.c_str());
    return 1;
  }

  const fusemap::cloudeval_tool::CloudEvalResult result = fusemap::cloudeval_tool::EvaluateCloud(
      world, kept, have_removed ? &removed : nullptr, static_tolerance_m);
  std::fprintf(stderr,
               "fusemap_cloudeval: map %zu points (%lld static, %lld dynamic); removed %zu points "
               "(%lld static, %lld dynamic)\n",
               kept.size(), static_cast<long long>(result.kept_static),
               static_cast<long long>(result.kept_dynamic), removed.size(),
               static_cast<long long>(result.removed_static),
               static_cast<long long>(result.removed_dynamic));
  std::printf("%s\n", fusemap::cloudeval_tool::FormatCloudEvalLine(result).c_str());
  return 0;
}
