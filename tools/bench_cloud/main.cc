// Benchmarks the cloud binder: builds synthetic maps of 1, 5 and 20 million points over 200
// submaps, moves 1, 10 and 50 submaps and prints the re-pose time, to show that an update costs
// the moved regions' points, not the map size. Also prints the per-frame carving cost of dynamic
// removal and the peak resident memory. Timings, not assertions: run it by hand.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "fusemap/cloud/cloud_binder.h"
#include "fusemap/common/command_line.h"

namespace {

using fusemap::cloud::CameraCloud;
using fusemap::cloud::CloudBinder;
using fusemap::cloud::CloudBinderOptions;
using fusemap::cloud::ColorCloud;
using fusemap::cloud::ColorPoint;
using fusemap::common::Rigid3d;

constexpr int kNumSubmaps = 200;
constexpr int kPointsPerFrame = 20000;

const std::string kUsage =
    "usage: fusemap_bench_cloud [--sizes 1,5,20]\n"
    "Builds synthetic cloud maps of the given sizes (millions of points) over " +
    std::to_string(kNumSubmaps) +
    " submaps,\n"
    "moves 1, 10 and 50 submaps and prints one line per case:\n"
    "  points=... moved_regions=... moved_points=... update_ms=...\n"
    "then the per-frame dynamic-removal cost and peak RSS.\n";

double PeakRssMb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;
  }
  return -1.0;
}

Rigid3d Pose(double x, double y, double yaw_rad) {
  return Rigid3d(Eigen::Vector3d(x, y, 0.0),
                 Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ())));
}

double Ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// Fills a submap's region with `num_points` distinct voxels: a 2.5 m high wall, 3 cm spacing,
// fed as camera-sized frames whose camera sits at the submap origin.
void FillRegion(CloudBinder* binder, int submap, size_t num_points) {
  const int rows = 83;
  CameraCloud frame;
  frame.points_camera.reset(new ColorCloud);
  for (size_t i = 0; i < num_points; ++i) {
    ColorPoint p;
    p.x = 0.015f + 0.03f * static_cast<float>(i / rows);
    p.y = 2.0f;
    p.z = 0.015f + 0.03f * static_cast<float>(i % rows);
    p.r = static_cast<uint8_t>(submap);
    p.g = 128;
    p.b = static_cast<uint8_t>(i);
    frame.points_camera->push_back(p);
    if (frame.points_camera->size() == kPointsPerFrame || i + 1 == num_points) {
      binder->AddCloud(submap, Rigid3d::Identity(), frame);
      frame.points_camera.reset(new ColorCloud);
    }
  }
}

bool RunSize(double million_points) {
  const size_t total = static_cast<size_t>(million_points * 1e6);
  CloudBinderOptions options;
  // Building the map is not what is measured: one ray per huge stride keeps it quick while
  // the map-frame index that dynamic removal needs is still maintained on every update.
  options.dynamic_ray_stride = 1 << 30;
  options.dynamic_max_ray_length_m = 1e-3;  // and that ray carves nothing
  CloudBinder binder(options);
  const auto build_start = std::chrono::steady_clock::now();
  for (int id = 0; id < kNumSubmaps; ++id) {
    // Submaps 0.5 m apart along a corridor-like strip, each region its own wall: neighbours
    // share few index blocks, as in a real run (heavy overlap adds the shared blocks' cost).
    binder.SetSubmapPose(id, Pose(0.0, 0.5 * id, 0.002 * id));
    FillRegion(&binder, id, total / kNumSubmaps);
  }
  // A few points go as dynamic even so: the origin voxel of a ray is carved, and the long
  // synthetic walls of rotated submaps pass through other submaps' origins.
  std::printf("build points=%zu removed=%lld regions=%zu build_ms=%.0f memory_mb=%.0f\n",
              binder.stats().points_stored,
              static_cast<long long>(binder.stats().points_removed_dynamic),
              binder.stats().regions, Ms(build_start), binder.MemoryBytes() / 1048576.0);
  for (const int moved : {1, 10, 50}) {
    std::vector<std::pair<int, Rigid3d>> poses;
    for (int i = 0; i < moved; ++i) {
      const int id = (i * 37) % kNumSubmaps;  // spread over the map
      poses.emplace_back(id, Pose(0.01, 0.5 * id + 0.02, 0.002 * id + 0.001));
    }
    binder.OnSubmapsMoved(poses);
    std::printf("points=%zu moved_regions=%zu moved_points=%zu update_ms=%.2f\n",
                binder.stats().points_stored, binder.stats().last_update_regions,
                binder.stats().last_update_points, binder.stats().last_update_ms);
  }
  const auto union_start = std::chrono::steady_clock::now();
  const size_t global_size = binder.GlobalCloud()->size();
  std::printf("global_cloud points=%zu union_ms=%.1f\n", global_size, Ms(union_start));
  if (global_size != binder.stats().points_stored) {
    std::fprintf(stderr, "error: global cloud has %zu points, stats say %zu\n", global_size,
                 binder.stats().points_stored);
    return false;
  }
  return true;
}

// Per-frame cost of dynamic removal with the default options: frames of 20k points, 3 m in
// front of the camera, in a room already holding a 1M-point map.
void RunCarving() {
  CloudBinder binder{CloudBinderOptions()};
  binder.SetSubmapPose(0, Rigid3d::Identity());
  FillRegion(&binder, 0, 1000000);
  Eigen::Matrix3d R_base_optical;
  R_base_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  double carve_ms = 0.0;
  const int kFrames = 10;
  for (int f = 0; f < kFrames; ++f) {
    CameraCloud frame;
    frame.points_camera.reset(new ColorCloud);
    for (int i = 0; i < kPointsPerFrame; ++i) {
      ColorPoint p;
      p.x = -2.0f + 4.0f * static_cast<float>(i % 160) / 160.f;
      p.y = -1.0f + 2.0f * static_cast<float>(i / 160) / 125.f;
      p.z = 3.0f;
      frame.points_camera->push_back(p);
    }
    const Rigid3d T_submap_camera(
        Eigen::Vector3d(1.0 + 0.1 * f, -1.0, 1.2),
        Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()) * R_base_optical));
    binder.AddCloud(0, T_submap_camera, frame);
    carve_ms += binder.stats().last_carve_ms;
  }
  std::printf("dynamic_removal frame_points=%d ray_stride=%d mean_carve_ms=%.1f\n", kPointsPerFrame,
              binder.options().dynamic_ray_stride, carve_ms / kFrames);
}

// Every size, then the carving cost and peak memory: 0, or 1 if a size failed.
int RunBenchmarks(const std::vector<double>& sizes_million) {
  for (const double size : sizes_million) {
    if (!RunSize(size)) return 1;
  }
  RunCarving();
  std::printf("peak_rss_mb=%.0f\n", PeakRssMb());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> sizes_million = {1, 5, 20};
  fusemap::common::CommandLine command_line("fusemap_bench_cloud", kUsage);
  command_line.AddDoubleList("--sizes", &sizes_million, {0.0, 100.0, true});
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv)) return *exit_code;
  return RunBenchmarks(sizes_million);
}
