// fusemap_cloudeval: scores a coloured cloud map against the simulator's ground-truth world.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <pcl/common/transforms.h>

#include "fusemap/cloud_eval/cloud_eval.h"
#include "fusemap/common/command_line.h"
#include "fusemap/eval/absolute_trajectory_error.h"
#include "fusemap/io/cloud_writer.h"
#include "fusemap/io/tum_trajectory.h"
#include "fusemap/cloud_eval/landmark_eval.h"
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
    "Then `landmark_pair_max_rel_err=… landmark_pairs_found=N/6` and one `landmark_pair …` line\n"
    "per pair: horizontal distances between six landmark pairs (pillar axes by circle fit, top\n"
    "centres of boxes below the camera) against the world's (tools/cloudeval/landmark_eval.h).\n"
    "The map frame is the SLAM frame (the robot's start); with --gt the cloud is first aligned\n"
    "to the world by the rigid fit of the SLAM trajectory to the ground truth (as ATE does).\n"
    "Options:\n"
    "  --cloud FILE              map cloud, .ply or .pcd (required)\n"
    "  --world FILE              world description the log was simulated from (required)\n"
    "  --removed FILE            points removed as dynamic (default: cloud_removed.ply next to\n"
    "                            --cloud; if that is absent the fractions print as nan)\n"
    "  --static-tolerance-m M    (default 0.1)\n"
    "  --gt FILE                 ground-truth base trajectory in the world (TUM; fusemap_sim's\n"
    "                            groundtruth.tum); without it the cloud must be in the world frame\n"
    "  --est FILE                the map's trajectory (default: trajectory.tum next to --cloud)\n"
    "  --camera-height-m H       box tops below H - 0.05 m are landmarks (default 1.0)\n"
    "  --help                    this text\n";

bool ReadCloud(const std::string& path, fusemap::cloud::ColorCloud* cloud, std::string* error) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".pcd") return fusemap::io::ReadCloudPcd(path, cloud, error);
  return fusemap::io::ReadCloudPly(path, cloud, error);
}

struct Args {
  std::string cloud_path, world_path, removed_path, gt_path, est_path;
  double static_tolerance_m = 0.1, camera_height_m = 1.0;
};

// Fills *args; nullopt to go on, else the exit code (--help 0, usage error 2).
std::optional<int> ParseArgs(int argc, char** argv, Args* args) {
  using fusemap::common::CommandLine;
  using fusemap::common::NumberRange;
  CommandLine command_line("fusemap_cloudeval", kUsage);
  command_line.AddString("--cloud", &args->cloud_path, CommandLine::Required::kYes);
  command_line.AddString("--world", &args->world_path, CommandLine::Required::kYes);
  command_line.AddString("--removed", &args->removed_path);
  command_line.AddString("--gt", &args->gt_path);
  command_line.AddString("--est", &args->est_path);
  command_line.AddDouble("--camera-height-m", &args->camera_height_m, NumberRange::Positive());
  command_line.AddDouble("--static-tolerance-m", &args->static_tolerance_m,
                         NumberRange::NonNegative());
  return command_line.ParseOrExitCode(argc, argv);
}

// Scores the cloud and prints the result lines: 0, or 1 for an unreadable cloud or world.
int Evaluate(Args args) {
  const std::string& cloud_path = args.cloud_path;
  const std::string& world_path = args.world_path;
  std::string& removed_path = args.removed_path;
  const std::string& gt_path = args.gt_path;
  std::string& est_path = args.est_path;
  const double static_tolerance_m = args.static_tolerance_m;
  const double camera_height_m = args.camera_height_m;
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

  if (!gt_path.empty()) {
    if (est_path.empty()) {
      est_path = (std::filesystem::path(cloud_path).parent_path() / "trajectory.tum").string();
    }
    fusemap::eval::Trajectory gt, est;
    if (!fusemap::io::ReadTumTrajectoryFile(gt_path, &gt, &error) ||
        !fusemap::io::ReadTumTrajectoryFile(est_path, &est, &error)) {
      std::fprintf(stderr, "fusemap_cloudeval: %s\n", error.c_str());
      return 1;
    }
    const fusemap::eval::AteResult ate =
        fusemap::eval::ComputeAte(gt, est, fusemap::eval::AteOptions());
    if (ate.trans_m.count == 0) {
      std::fprintf(stderr, "fusemap_cloudeval: no common stamps in %s and %s\n", gt_path.c_str(),
                   est_path.c_str());
      return 1;
    }
    const Eigen::Affine3f T_world_map =
        (Eigen::Translation3d(ate.T_gt_est.translation()) * ate.T_gt_est.rotation()).cast<float>();
    pcl::transformPointCloud(kept, kept, T_world_map);
    pcl::transformPointCloud(removed, removed, T_world_map);
    std::fprintf(stderr, "fusemap_cloudeval: aligned to the world with ATE rmse %.4f m\n",
                 ate.trans_m.rmse);
  }
  const fusemap::cloud_eval::CloudEvalResult result = fusemap::cloud_eval::EvaluateCloud(
      world, kept, have_removed ? &removed : nullptr, static_tolerance_m);
  std::fprintf(stderr,
               "fusemap_cloudeval: map %zu points (%lld static, %lld dynamic); removed %zu points "
               "(%lld static, %lld dynamic)\n",
               kept.size(), static_cast<long long>(result.kept_static),
               static_cast<long long>(result.kept_dynamic), removed.size(),
               static_cast<long long>(result.removed_static),
               static_cast<long long>(result.removed_dynamic));
  std::printf("%s\n", fusemap::cloud_eval::FormatCloudEvalLine(result).c_str());
  const auto pairs = fusemap::cloud_eval::EvaluateLandmarkPairs(world, kept, camera_height_m);
  std::printf("%s\n", fusemap::cloud_eval::FormatLandmarkSummary(pairs).c_str());
  for (const auto& pair : pairs) {
    std::printf("%s\n", fusemap::cloud_eval::FormatLandmarkPair(pair).c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (const auto exit_code = ParseArgs(argc, argv, &args)) return *exit_code;
  return Evaluate(args);
}
