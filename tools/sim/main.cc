// fusemap_sim: deterministic simulated sensor log (laser, odometry, IMU, RGB-D, ground truth).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "fusemap/common/thread_pool.h"
#include "fusemap/sim/simulation.h"
#include "fusemap/sim/world_loader.h"
#include "fusemap/sim_log/sim_log.h"

namespace {

constexpr char kUsage[] =
    "Usage: fusemap_sim --world FILE.yaml --out DIR [options]\n"
    "Simulates a robot driving a waypoint loop through a world and writes\n"
    "  DIR/sim.lcm           LCM log: LIDAR (laser_scan_t), ODOMETRY (odometry2d_t), IMU (imu_t),\n"
    "                        RGBD (rgbd_frame_t, JPEG + 16-bit PNG), GROUND_TRUTH (pose_t;\n"
    "                        for evaluation only, SLAM must not read it)\n"
    "  DIR/groundtruth.tum   base trajectory, `t x y z qx qy qz qw`\n"
    "  DIR/tags.yaml         floor AprilTag map (tag36h11): id -> x, y, yaw, size_m\n"
    "Options:\n"
    "  --seconds S       simulated duration (default 60)\n"
    "  --seed N          noise seed; same seed, same bytes (default 1)\n"
    "  --laser-rate HZ   laser scan rate (default 25)\n"
    "  --rgbd-rate HZ    RGB-D frame rate (default 10; 25 works but the log grows ~2.5x)\n"
    "  --no-rgbd         no RGB-D frames\n"
    "  --threads N       RGB-D rendering threads (default 2; output does not depend on it)\n"
    "  --help            this text\n";

bool ParseNumber(const std::string& flag, const char* text, double* value) {
  char* end = nullptr;
  *value = std::strtod(text, &end);
  if (end == text || *end != '\0') {
    std::fprintf(stderr, "fusemap_sim: %s expects a number, got '%s'\n", flag.c_str(), text);
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  std::string world_path, out_dir;
  fusemap::sim::SimulationOptions options;
  int threads = 2;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (flag == "--no-rgbd") {
      options.rgbd_enabled = false;
      continue;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "fusemap_sim: %s needs a value (or unknown flag)\n%s", flag.c_str(), kUsage);
      return 2;
    }
    const char* value = argv[++i];
    double number = 0.0;
    if (flag == "--world") {
      world_path = value;
    } else if (flag == "--out") {
      out_dir = value;
    } else if (flag == "--seconds" || flag == "--seed" || flag == "--laser-rate" ||
               flag == "--rgbd-rate" || flag == "--threads") {
      if (!ParseNumber(flag, value, &number)) return 2;
      if (flag == "--seconds") options.seconds = number;
      if (flag == "--laser-rate") options.laser.rate_hz = number;
      if (flag == "--rgbd-rate") options.rgbd.rate_hz = number;
      if (flag == "--threads") threads = static_cast<int>(number);
      if (flag == "--seed") {
        if (number < 0 || number != static_cast<double>(static_cast<uint64_t>(number))) {
          std::fprintf(stderr, "fusemap_sim: --seed must be a non-negative integer\n");
          return 2;
        }
        options.seed = static_cast<uint64_t>(number);
      }
    } else {
      std::fprintf(stderr, "fusemap_sim: unknown flag '%s'\n%s", flag.c_str(), kUsage);
      return 2;
    }
  }
  if (world_path.empty() || out_dir.empty()) {
    std::fprintf(stderr, "fusemap_sim: --world and --out are required\n%s", kUsage);
    return 2;
  }
  if (threads < 1 || threads > 64) {
    std::fprintf(stderr, "fusemap_sim: --threads must be in [1, 64]\n");
    return 2;
  }

  std::string error;
  fusemap::sim::World world;
  if (!fusemap::sim::LoadWorldFile(world_path, &world, &error)) {
    std::fprintf(stderr, "fusemap_sim: %s\n", error.c_str());
    return 1;
  }
  const std::vector<fusemap::sim::FloorTag> tags = world.tags;
  auto simulation = fusemap::sim::Simulation::Create(std::move(world), options, &error);
  if (simulation == nullptr) {
    std::fprintf(stderr, "fusemap_sim: %s: %s\n", world_path.c_str(), error.c_str());
    return 1;
  }
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) {
    std::fprintf(stderr, "fusemap_sim: cannot create %s: %s\n", out_dir.c_str(), ec.message().c_str());
    return 1;
  }
  if (!fusemap::sim::WriteTagMapFile(out_dir + "/tags.yaml", tags, &error)) {
    std::fprintf(stderr, "fusemap_sim: %s\n", error.c_str());
    return 1;
  }

  fusemap::sim_log::SimLogOptions log_options;
  log_options.log_path = out_dir + "/sim.lcm";
  log_options.groundtruth_tum_path = out_dir + "/groundtruth.tum";
  fusemap::common::ThreadPool render_pool(threads);
  log_options.render_executor = &render_pool;
  log_options.render_batch = 4 * threads;
  const double seconds = options.seconds;
  log_options.progress = [seconds](double t, int64_t messages) {
    std::fprintf(stderr, "\rfusemap_sim: %6.1f / %.1f s simulated, %lld messages", t, seconds,
                 static_cast<long long>(messages));
    std::fflush(stderr);
  };
  const auto start = std::chrono::steady_clock::now();
  fusemap::sim_log::SimLogSummary summary;
  if (!fusemap::sim_log::WriteSimulationLog(*simulation, log_options, &summary, &error)) {
    std::fprintf(stderr, "\nfusemap_sim: %s\n", error.c_str());
    return 1;
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto log_bytes = std::filesystem::file_size(log_options.log_path, ec);
  std::fprintf(stderr, "\n");
  std::string counts;
  for (const auto& [channel, count] : summary.messages_per_channel) {
    counts += " " + channel + "=" + std::to_string(count);
  }
  std::printf("fusemap_sim: %.1f s simulated (path loop %.1f m, drive %.1f s), messages:%s, "
              "wall %.1f s, log %.1f MB (%s)\n",
              summary.sim_seconds, simulation->trajectory().loop_length_m(),
              simulation->trajectory().duration_s(), counts.c_str(), wall_s,
              (ec ? 0.0 : static_cast<double>(log_bytes)) / 1e6, log_options.log_path.c_str());
  return 0;
}
