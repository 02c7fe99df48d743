// fusemapd: the mapping daemon. Subscribes to laser/odometry/IMU/RGB-D channels on an LCM bus
// (or replays a log with file://), runs 2D SLAM and publishes poses, submaps and health.
#include <signal.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "fusemap/common/command_line.h"
#include "fusemap/daemon/cloud_region_publisher.h"
#include "fusemap/daemon/daemon_options.h"
#include "fusemap/daemon/engine.h"
#include "fusemap/daemon/file_checkpointer.h"
#include "fusemap/daemon/lcm_input.h"
#include "fusemap/daemon/lcm_publisher.h"
#include "fusemap/daemon/resume.h"
#include "fusemap/daemon/this_thread.h"
#include "fusemap/io/visual_keyframes_file.h"

namespace fusemap {
namespace {

constexpr int kExitOk = common::kExitSuccess;
constexpr int kExitRuntime = common::kExitFailure;
constexpr int kExitUsage = common::kExitUsage;
constexpr int kExitCheckpoint = 3;  // a checkpoint that cannot be restored (fusemapd only)

constexpr char kUsage[] =
    "usage: fusemapd --config FILE --lcm-url URL --out DIR [--resume] [--threads N] [--quiet]\n"
    "\n"
    "Runs 2D SLAM on the configured LCM channels (the SLAM profile's channels:) and publishes\n"
    "the pose per scan (channels.pose, fusemap_lcm.pose_t), the submap list (~5 Hz and after\n"
    "each optimisation), loop-closure events and health at 1 Hz (daemon: key of the profile,\n"
    "see config/daemon.yaml). On SIGINT/SIGTERM, or at the end of a file:// log, it processes\n"
    "everything queued, runs the final optimisation and writes DIR/trajectory.tum, DIR/nodes.tum,\n"
    "DIR/map.pgm, DIR/map.yaml and DIR/map.png (as fusemap_offline; with RGB-D frames and\n"
    "cloud.enabled also DIR/cloud.ply/.pcd, DIR/cloud_removed.ply, DIR/octomap.bt/.ot and\n"
    "DIR/cloud.png, while changed cloud regions go out on daemon.cloud_region_channel as\n"
    "fusemap_lcm.cloud_region_t, at most every 0.5 s). Its state goes to\n"
    "DIR/checkpoint.fmck every daemon.checkpoint_period_s and at shutdown (the one before is\n"
    "kept as DIR/checkpoint.fmck.prev). Each checkpoint first moves the odometry record and\n"
    "the nodes submap trimming let go (global_slam.overlapping_submaps_trimmer) out of memory\n"
    "into DIR/archive/ (nodes.bin, odometry.bin), so memory stays flat in a mapped place; the\n"
    "output files still cover the whole run. With visual_loop.enabled the ORB visual loop\n"
    "checker runs on its own thread on the RGB-D frames: its decisions go to DIR/loops.tsv at\n"
    "shutdown, its keyframes to DIR/visual_keyframes.fmvk (restored by --resume); as they\n"
    "depend on its timing, a file:// replay then no longer equals fusemap_offline bit for bit.\n"
    "With daemon.realtime_priority (config/daemon.yaml: 20) the LCM handler and the SLAM thread\n"
    "(which publishes the poses) run under SCHED_FIFO (root, CAP_SYS_NICE or RLIMIT_RTPRIO;\n"
    "else logged, normal priority; not for a speed=0 replay). Threads are named fusemap-*\n"
    "(top -H).\n"
    "\n"
    "  --config FILE   SLAM profile (config/*.yaml) with an optional daemon: section\n"
    "  --lcm-url URL   e.g. udpm://239.255.76.67:7667?ttl=0, or file:///path/log.lcm?speed=0 to\n"
    "                  replay a log as fast as possible (same result as fusemap_offline with\n"
    "                  --threads 1; replay never drops: the reader waits for SLAM)\n"
    "  --out DIR       output folder (created)\n"
    "  --resume        continue from DIR/checkpoint.fmck (or, if that is missing or corrupt,\n"
    "                  DIR/checkpoint.fmck.prev; the reason is printed). A checkpoint of another\n"
    "                  fusemap version is refused (exit 3); one mapped with a different config\n"
    "                  text is used with the current config and a warning. Input stamped at\n"
    "                  or before what the checkpoint holds (per channel) is skipped, so a\n"
    "                  file:// replay restarted from its start is not mapped twice\n"
    "  --threads N     workers for loop closure and optimisation (default 1: deterministic)\n"
    "  --quiet         no health lines on stderr\n"
    "  --help          this text\n"
    "\n"
    "exit codes: 0 clean shutdown (signal or end of log, outputs written), 1 runtime failure\n"
    "(LCM error, outputs not writable, no scans), 2 usage or configuration error, 3 checkpoint\n"
    "cannot be restored (--resume).\n";

bool ReadFileText(const std::string& path, std::string* text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream buffer;
  buffer << in.rdbuf();
  *text = buffer.str();
  return static_cast<bool>(in);
}

struct Args {
  std::string config, lcm_url, out;
  bool resume = false;
  int threads = 1;
  bool quiet = false;
};

int Run(const Args& args) {
  io::SlamConfig slam;
  daemon::DaemonOptions options;
  std::string error;
  if (!daemon::LoadDaemonConfig(args.config, &slam, &options, &error)) {
    std::fprintf(stderr, "fusemapd: %s\n", error.c_str());
    return kExitUsage;
  }
  std::string config_text;
  if (!ReadFileText(args.config, &config_text)) {
    std::fprintf(stderr, "fusemapd: cannot read %s\n", args.config.c_str());
    return kExitUsage;
  }
  const std::string checkpoint_path = daemon::CheckpointPath(args.out);
  daemon::ResumeCheckpoint resume;
  if (args.resume) {
    const auto status =
        daemon::LoadResumeCheckpoint(checkpoint_path, config_text, &resume, &error);
    if (status != daemon::ResumeStatus::kOk) {
      std::fprintf(stderr, "fusemapd: --resume: %s\n", error.c_str());
      return kExitCheckpoint;
    }
    for (const auto& warning : resume.warnings) {
      std::fprintf(stderr, "fusemapd: --resume: %s\n", warning.c_str());
    }
  }
  // Signals are taken synchronously by this thread (sigtimedwait below); every thread created
  // from here on inherits the blocked mask, so no handler runs inside LCM or SLAM code.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  if (options.realtime_priority > 0 && !daemon::ArrivesPaced(args.lcm_url)) {
    // Read as fast as SLAM takes it, the SLAM thread never sleeps: under SCHED_FIFO it would
    // hold a CPU and starve the workers (on one core, everything else).
    if (!args.quiet) {
      std::fprintf(stderr,
                   "fusemapd: daemon.realtime_priority not applied: a speed=0 replay is not "
                   "real time\n");
    }
    options.realtime_priority = 0;
  }
  daemon::RateLimitedLog log(options.bad_message_log_interval_s);
  const daemon::OverflowPolicy policy = daemon::PolicyForUrl(args.lcm_url);
  daemon::LcmInput input;
  if (!input.Open(args.lcm_url, &error)) {
    std::fprintf(stderr, "fusemapd: %s\n", error.c_str());
    return kExitUsage;
  }
  daemon::LcmPublisher publisher(
      input.publish_handle(),
      {slam.channels.pose, options.submap_list_channel, options.loop_closure_channel,
       options.health_channel},
      !args.quiet);
  // Changed regions of the coloured map (cloud.enabled), for a viewer to follow.
  daemon::LcmCloudRegionPublisher cloud_publisher(input.publish_handle(),
                                                  options.cloud_region_channel);
  auto engine = std::make_unique<daemon::Engine>(slam, options, args.threads, policy, &publisher,
                                                 &log);
  engine->SetCloudRegionPublisher(&cloud_publisher);
  daemon::FileCheckpointer checkpointer(checkpoint_path, config_text, [&args](const std::string& line) {
    if (!args.quiet) std::fprintf(stderr, "fusemapd: %s\n", line.c_str());
  });
  engine->SetCheckpointer(&checkpointer);
  std::string warning;
  auto archive = io::TrajectoryArchive::Open(args.out + "/archive",
                                             args.resume ? &resume.contents.archive : nullptr,
                                             &warning, &error);
  if (!archive) {
    std::fprintf(stderr, "fusemapd: trajectory archive: %s\n", error.c_str());
    return kExitRuntime;
  }
  if (!warning.empty()) std::fprintf(stderr, "fusemapd: --resume: %s\n", warning.c_str());
  engine->SetTrajectoryArchive(std::move(archive));
  if (args.resume) {
    engine->Restore(resume.contents.state, std::move(resume.contents.odometry));
    std::fprintf(stderr, "fusemapd: resumed from %s (%zu nodes, %zu submaps)\n",
                 resume.used_path.c_str(), resume.contents.state.pose_graph.nodes.size(),
                 resume.contents.state.submaps.size());
    resume = daemon::ResumeCheckpoint();  // the engine has its own copy now
  }
  if (slam.visual_loop.enabled) {
    // The visual loop checker's keyframes live beside the checkpoint (its own thread writes
    // them); a missing or damaged file costs the keyframes, not the resume.
    const std::string keyframes_path = args.out + "/visual_keyframes.fmvk";
    if (args.resume) {
      io::VisualKeyframesState keyframes;
      if (io::ReadVisualKeyframesFile(keyframes_path, &keyframes, &error)) {
        const size_t saved = keyframes.keyframes.size();
        const int kept = engine->RestoreVisualKeyframes(std::move(keyframes));
        std::fprintf(stderr, "fusemapd: resumed %d of %zu visual keyframes from %s\n", kept, saved,
                     keyframes_path.c_str());
      } else {
        std::fprintf(stderr, "fusemapd: --resume: visual keyframes not restored: %s\n",
                     error.c_str());
      }
    }
    engine->SetVisualKeyframesFile(keyframes_path);
  }
  input.Subscribe(&engine->intake());
  engine->Start();

  std::atomic<bool> stop{false};
  std::atomic<bool> input_done{false};
  daemon::LcmInput::End end = daemon::LcmInput::End::kStopped;
  std::thread handler([&] {
    daemon::SetThisThreadName("fusemap-lcm");
    // The handler takes each scan off the wire: it is on the pose path with the SLAM thread
    // (daemon.realtime_priority).
    if (engine->EnterPosePath("LCM handler") && !args.quiet) {
      std::fprintf(stderr, "fusemapd: pose path at SCHED_FIFO priority %d\n",
                   options.realtime_priority);
    }
    end = input.Run(stop);
    input_done = true;
  });
  const timespec poll{0, 100 * 1000 * 1000};
  int signal_number = 0;
  while (!input_done) {
    const int s = sigtimedwait(&signals, nullptr, &poll);
    if (s > 0) {
      signal_number = s;
      break;
    }
  }
  stop = true;
  // A kBlock intake may be waiting for room in a queue: closing it releases the handler.
  engine->intake().Close();
  handler.join();
  if (!args.quiet) {
    std::fprintf(stderr, "fusemapd: %s; finishing\n",
                 signal_number != 0 ? strsignal(signal_number)
                 : end == daemon::LcmInput::End::kEndOfLog ? "end of log"
                                                           : "LCM error");
  }
  engine->Finish();
  if (engine->scans_processed() == 0 && !args.resume) {  // a resumed map is still worth writing
    std::fprintf(stderr, "fusemapd: no usable scans on channel %s; no outputs written\n",
                 slam.channels.lidar.c_str());
    return kExitRuntime;
  }
  session::RunOutputsReport written;
  if (!engine->WriteOutputs(args.out, &error, &written)) {
    std::fprintf(stderr, "fusemapd: %s\n", error.c_str());
    return kExitRuntime;
  }
  const auto health = engine->Health();
  std::printf("%s\n", daemon::FormatHealth(health).c_str());
  const auto saved = checkpointer.stats();
  std::printf("checkpoints: %d written, %d failed; last %s: %d nodes, %.2f MB in %.3f s\n",
              saved.saved, saved.failed, checkpoint_path.c_str(), saved.last_nodes,
              saved.last_bytes / 1048576.0, saved.last_seconds);
  std::printf("wrote %s/trajectory.tum %s/map.pgm %s/map.yaml %s/map.png\n", args.out.c_str(),
              args.out.c_str(), args.out.c_str(), args.out.c_str());
  if (written.wrote_cloud) {
    std::printf("%s cloud_regions_published=%lld\n", written.cloud_summary.c_str(),
                static_cast<long long>(cloud_publisher.published()));
  }
  if (end == daemon::LcmInput::End::kError && signal_number == 0) return kExitRuntime;
  return kExitOk;
}

}  // namespace
}  // namespace fusemap

int main(int argc, char** argv) {
  fusemap::Args args;
  fusemap::common::CommandLine command_line("fusemapd", fusemap::kUsage);
  using Required = fusemap::common::CommandLine::Required;
  command_line.AddString("--config", &args.config, Required::kYes);
  command_line.AddString("--lcm-url", &args.lcm_url, Required::kYes);
  command_line.AddString("--out", &args.out, Required::kYes);
  command_line.AddFlag("--resume", &args.resume);
  command_line.AddInt("--threads", &args.threads, 1, 64);
  command_line.AddFlag("--quiet", &args.quiet);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv)) return *exit_code;
  return fusemap::Run(args);
}
