// fusemap_sim: deterministic simulated sensor log (laser, odometry, IMU, RGB-D, ground truth).
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include "fusemap/common/command_line.h"
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
    "  --to-end          simulate until the robot stops at the end of its drive (+1 s;\n"
    "                    overrides --seconds)\n"
    "  --seed N          noise seed; same seed, same bytes (default 1)\n"
    "  --laser-rate HZ   laser scan rate (default 25)\n"
    "  --rgbd-rate HZ    RGB-D frame rate (default 10; 25 works but the log grows ~2.5x)\n"
    "  --no-rgbd         no RGB-D frames\n"
    "  --threads N       RGB-D rendering threads (default 2; output does not depend on it)\n"
    "  --help            this text\n";

struct Args {
  std::string world_path, out_dir;
  fusemap::sim::SimulationOptions options;
  int threads = 2;
  bool to_end = false;
};

// Fills *args; nullopt to go on, else the exit code (--help 0, usage error 2).
std::optional<int> ParseArgs(int argc, char** argv, Args* args) {
  int64_t seed = static_cast<int64_t>(args->options.seed);
  fusemap::common::CommandLine command_line("fusemap_sim", kUsage);
  command_line.AddString("--world", &args->world_path,
                         fusemap::common::CommandLine::Required::kYes);
  command_line.AddString("--out", &args->out_dir, fusemap::common::CommandLine::Required::kYes);
  command_line.AddDouble("--seconds", &args->options.seconds);
  command_line.AddInt64("--seed", &seed, 0, std::numeric_limits<int64_t>::max());
  command_line.AddDouble("--laser-rate", &args->options.laser.rate_hz);
  command_line.AddDouble("--rgbd-rate", &args->options.rgbd.rate_hz);
  command_line.AddFlag("--no-rgbd", &args->options.rgbd_enabled, false);
  command_line.AddFlag("--to-end", &args->to_end);
  command_line.AddInt("--threads", &args->threads, 1, 64);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv)) return exit_code;
  args->options.seed = static_cast<uint64_t>(seed);
  // A duration or rate out of the simulation's range came from this command line: usage.
  std::string error;
  if (!args->options.IsValid(&error)) return command_line.UsageError(error);
  return std::nullopt;
}

// Simulates and writes DIR's files: 0, or 1 for an unreadable world or unwritten outputs.
int Simulate(const Args& args) {
  const std::string& world_path = args.world_path;
  const std::string& out_dir = args.out_dir;
  fusemap::sim::SimulationOptions options = args.options;
  const int threads = args.threads;
  std::string error;
  fusemap::sim::World world;
  if (!fusemap::sim::LoadWorldFile(world_path, &world, &error)) {
    std::fprintf(stderr, "fusemap_sim: %s\n", error.c_str());
    return 1;
  }
  const std::vector<fusemap::sim::FloorTag> tags = world.tags;
  if (args.to_end) options.seconds = fusemap::sim::WaypointTrajectory(world.robot).duration_s() + 1.0;
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

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (const auto exit_code = ParseArgs(argc, argv, &args)) return *exit_code;
  return Simulate(args);
}
