// fusemap_offline's run: the log decoded and passed through the daemon's stamp policy into a
// session::SlamSession, in file order, on this thread.
#include "offline_run.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "fusemap/common/math.h"
#include "fusemap/common/process_memory.h"
#include "fusemap/common/thread_pool.h"
#include "fusemap/eval/relation_error.h"
#include "fusemap/eval/trajectory.h"
#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/lcm_log.h"
#include "fusemap/io/relations_file.h"
#include "fusemap/io/stamp_map_file.h"
#include "fusemap/io/rgbd_conversions.h"
#include "fusemap/io/slam_config.h"
#include "fusemap/io/tum_trajectory.h"
#include "fusemap/pose_graph/map_builder_2d.h"
#include "fusemap/pose_graph/odometry_calibration.h"
#include "fusemap/sensor/stamp_gate.h"
#include "fusemap/session/slam_session.h"

namespace fusemap {
namespace offline_tool {
namespace {

using common::Percentile;

// Resident memory is sampled every this many scans (`rss_mb_over_time`).
constexpr int kRssSampleScans = 250;

}  // namespace

int Run(const Args& args) {
  io::SlamConfig config;
  std::string error;
  if (!io::LoadSlamConfig(args.config, &config, &error)) {
    std::fprintf(stderr, "fusemap_offline: %s\n", error.c_str());
    return 2;
  }
  if (!args.loop_closure) config.map_builder.global_slam.optimize_every_n_nodes = 0;
  if (!args.cloud) config.cloud.enabled = false;
  if (args.visual_loop) {
    config.visual_loop.enabled = *args.visual_loop;
    if (config.visual_loop.enabled && !config.visual_loop.loaded_vocabulary &&
        !io::LoadVisualLoopVocabulary(&config.visual_loop, &error)) {
      std::fprintf(stderr, "fusemap_offline: --visual-loop: %s\n", error.c_str());
      return 2;
    }
  }
  // Read before the run, so a bad file does not cost one.
  std::vector<eval::Relation> relations;
  std::string stamp_map_summary;
  if (!args.relations.empty() &&
      (!io::ReadRelationsFile(args.relations, args.relations_time_offset_s, &relations,
                              &error) ||
       (!args.relations_stamp_map.empty() &&
        !io::MapRelationsThroughStampMapFile(args.relations_stamp_map, &relations,
                                             &stamp_map_summary, &error)))) {
    std::fprintf(stderr, "fusemap_offline: %s\n", error.c_str());
    return 1;
  }
  io::LcmLogReader reader;
  if (!reader.Open(args.log, &error)) {
    std::fprintf(stderr, "fusemap_offline: %s\n", error.c_str());
    return 1;
  }
  std::error_code ec;
  std::filesystem::create_directories(args.out, ec);
  if (ec) {
    std::fprintf(stderr, "fusemap_offline: cannot create output folder %s: %s\n", args.out.c_str(),
                 ec.message().c_str());
    return 1;
  }

  std::unique_ptr<common::Executor> executor;
  if (args.threads > 1) {
    executor = std::make_unique<common::ThreadPool>(args.threads);
  } else {
    executor = std::make_unique<common::InlineExecutor>();
  }
  session::SlamSession session(config, executor.get(), /*record_cloud_cost=*/true);

  std::vector<double> scan_cost_ms;
  std::vector<double> rss_mb;  // every kRssSampleScans scans
  // Global SLAM's grids and clouds at the same moments: what of the RSS the graph holds.
  std::vector<double> graph_mb, matcher_mb;
  std::vector<double> submaps_held;  // finished submaps held: what the trimmer bounds
  int scans = 0, rgbd_frames = 0, bad_messages = 0, other_messages = 0, odometry_out_of_order = 0;
  double first_stamp_s = 0.0, last_stamp_s = 0.0;
  bool have_stamp = false;
  const auto start = std::chrono::steady_clock::now();
  auto last_progress = start;
  io::LogEvent event;
  // Malformed messages are counted and dropped; the first one is described so the cause shows.
  const auto drop_bad_message = [&] {
    if (bad_messages++ == 0) {
      std::fprintf(stderr, "\nfusemap_offline: dropped %s message: %s\n", event.channel.c_str(),
                   error.c_str());
    }
  };
  // The daemon's stamp policy (sensor::StampGate, as in daemon::Intake): absurd or backwards
  // stamps are dropped, a far jump is held until the channel's next message confirms it, a
  // plausible backwards jump of the laser is a time reset.
  using Message =
      std::variant<sensor::LaserScan, sensor::OdometryData, sensor::ImuData, sensor::RgbdFrame>;
  enum { kLaser = 0, kOdometry, kImu, kRgbd, kChannels };
  sensor::StampGate<Message> gate(
      sensor::StampFilterOptions(), kChannels, kLaser, [](Message& message) -> double& {
        return std::visit([](auto& data) -> double& { return data.stamp_s; }, message);
      });
  int bad_stamps = 0;
  const auto drop_bad_stamp = [&](const std::string& why) {
    if (bad_stamps++ == 0) {
      std::fprintf(stderr, "\nfusemap_offline: dropped %s message: %s\n", event.channel.c_str(),
                   why.c_str());
    }
  };
  const auto apply = [&](const Message& message) {
    if (const auto* scan = std::get_if<sensor::LaserScan>(&message)) {
      const auto t0 = std::chrono::steady_clock::now();
      session.AddScan(*scan);
      scan_cost_ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      ++scans;
      if (scans % kRssSampleScans == 0) {
        // What is held, not also what was freed since the last return to the system (up to a
        // second of a run that plays hundreds of times faster than real time).
        common::ReleaseFreeMemory();
        rss_mb.push_back(static_cast<double>(common::ResidentMemoryBytes()) / 1048576.0);
        const auto graph = session.builder().pose_graph().stats();
        matcher_mb.push_back(graph.matcher_bytes / 1048576.0);
        graph_mb.push_back((graph.submap_bytes + graph.matcher_bytes + graph.node_bytes) /
                           1048576.0);
        submaps_held.push_back(graph.finished_submaps_held);
      }
    } else if (const auto* odometry = std::get_if<sensor::OdometryData>(&message)) {
      session.AddOdometry(*odometry);
    } else if (const auto* imu = std::get_if<sensor::ImuData>(&message)) {
      session.AddImu(*imu);
    } else if (const auto* frame = std::get_if<sensor::RgbdFrame>(&message)) {
      session.AddRgbdFrame(*frame);
      ++rgbd_frames;
    }
  };
  while (reader.Next(&event)) {
    const int size = static_cast<int>(event.data.size());
    Message message;
    int channel = -1;
    bool decoded = false;
    if (event.channel == config.channels.lidar) {
      channel = kLaser;
      decoded = io::DecodeLaserScan(event.data.data(), size, config.lidar,
                                    &message.emplace<sensor::LaserScan>(), &error);
    } else if (event.channel == config.channels.odometry) {
      channel = kOdometry;
      decoded = io::DecodeOdometry(event.data.data(), size,
                                   &message.emplace<sensor::OdometryData>(), &error);
    } else if (event.channel == config.channels.imu) {
      channel = kImu;
      decoded = io::DecodeImu(event.data.data(), size, &message.emplace<sensor::ImuData>(), &error);
    } else if ((session.cloud_stage() != nullptr || session.visual_stage() != nullptr) &&
               event.channel == config.channels.rgbd) {
      channel = kRgbd;
      decoded = io::DecodeRgbdFrame(event.data.data(), size,
                                    &message.emplace<sensor::RgbdFrame>(), &error);
    } else {
      ++other_messages;
      continue;
    }
    if (!decoded) {
      drop_bad_message();
      continue;
    }
    auto passed = gate.Offer(channel, message);
    const sensor::StampFilter::Decision& decision = passed.decision;
    if (decision.time_reset) session.OnTimeReset();
    if (passed.released) {
      apply(*passed.released);
    } else if (decision.held == sensor::StampFilter::Held::kDrop) {
      drop_bad_stamp(decision.held_reason);
    }
    if (!passed.pass) {
      if (decision.verdict == sensor::StampFilter::Verdict::kReject) {
        if (channel == kOdometry) ++odometry_out_of_order;
        drop_bad_stamp(decision.kind + ": " + decision.reason);
      }
      continue;
    }
    apply(message);
    const double stamp_s = decision.stamp_s;
    if (!have_stamp) first_stamp_s = stamp_s;
    have_stamp = true;
    last_stamp_s = std::max(last_stamp_s, stamp_s);
    const auto now = std::chrono::steady_clock::now();
    if (now - last_progress > std::chrono::seconds(1)) {
      last_progress = now;
      // As fusemapd does: grids freed in the middle of the heap go back to the system.
      common::ReleaseFreeMemory();
      if (!args.quiet) {
        std::fprintf(stderr, "\r[fusemap_offline] scans=%d log_t=%.1fs wall=%.1fs", scans,
                     last_stamp_s - first_stamp_s,
                     std::chrono::duration<double>(now - start).count());
      }
    }
  }
  session.Finish();
  // The final optimisation released the loop-closure grids; their pages go back before the
  // map is drawn.
  common::ReleaseFreeMemory();
  const double end_of_slam_rss_mb = static_cast<double>(common::ResidentMemoryBytes()) / 1048576.0;
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!args.quiet) std::fprintf(stderr, "\n");
  if (scans == 0) {
    std::fprintf(stderr, "fusemap_offline: %s has no usable scans on channel %s\n",
                 args.log.c_str(), config.channels.lidar.c_str());
    return 1;
  }

  session::RunOutputsReport written;
  if (!session.WriteOutputs(args.out, &written, &error)) {
    std::fprintf(stderr, "fusemap_offline: %s\n", error.c_str());
    return 1;
  }
  const std::vector<sensor::OdometryData>& odometry = session.odometry();
  const pose_graph::MapBuilder2D& builder = session.builder();
  const std::string out = args.out + "/";
  // The trajectory that is written and scored: node poses densified with the odometry,
  // optionally corrected for its systematic errors first.
  const auto nodes = builder.NodePoses();
  pose_graph::OdometryCalibration calibration;
  std::string calibration_note;
  if (args.calibrate_odometry) {
    std::string reason;
    if (pose_graph::FitOdometryCalibration(nodes, odometry,
                                           pose_graph::OdometryCalibrationOptions(), &calibration,
                                           &reason)) {
      char line[160];
      std::snprintf(line, sizeof(line),
                    "odometry_calibration: translation_scale=%.4f rotation_scale=%.4f "
                    "heading_drift_deg_per_m=%.3f",
                    calibration.translation_scale, calibration.rotation_scale,
                    common::RadToDeg(calibration.heading_drift_rad_per_m));
      calibration_note = line;
    } else {
      calibration_note = "odometry_calibration: none (" + reason + ")";
    }
  }
  const auto dense = pose_graph::DensifyWithOdometry(
      nodes, pose_graph::ApplyOdometryCalibration(calibration, odometry),
      session.odometry_breaks_s());
  if (!calibration.IsIdentity() &&
      !io::WriteTumTrajectoryFile(out + "trajectory.tum", session::ToTrajectory(dense), &error)) {
    std::fprintf(stderr, "fusemap_offline: %s\n", error.c_str());
    return 1;
  }
  const auto local = builder.local_slam().stats();
  const auto global = builder.pose_graph().stats();
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  // A message still held at the end was a jump nothing confirmed.
  bad_stamps += gate.num_held();
  std::printf(
      "log=%s odometry=%zu other_messages=%d bad_messages=%d odometry_out_of_order=%d "
      "bad_stamps=%d time_resets=%lld\n",
      args.log.c_str(), odometry.size(), other_messages, bad_messages, odometry_out_of_order,
      bad_stamps, static_cast<long long>(gate.filter().time_resets()));
  std::printf(
      "local_slam: scans=%d inserted=%d too_few_returns=%d out_of_order=%d "
      "initial_match_rejected=%d window_edge_matches=%d wide_matches_taken=%d "
      "absurd_predictions=%d insertions_refused=%d\n",
      local.scans, local.inserted, local.too_few_returns, local.out_of_order,
      local.initial_match_rejected, local.window_edge_matches, local.wide_matches_taken,
      local.absurd_predictions, local.insertions_refused);
  std::printf(
      "global_slam: nodes=%d submaps=%d loop_closure_searches=%d loop_closures_accepted=%d "
      "optimizations=%d search_s=%.3f precomputation_s=%.3f optimization_s=%.3f trimming_s=%.3f "
      "trimmed_submaps=%d trimmed_nodes=%d loop_closures_unverified=%d "
      "loop_closures_degenerate=%d loop_closures_beyond_drift=%d loop_closures_ambiguous=%d "
      "node_links=%d linked_unmeasured_steps=%d\n",
      global.nodes, global.submaps, global.loop_closure_searches, global.loop_closures_found,
      global.optimizations, global.loop_closure_search_s, global.precomputation_s,
      global.optimization_s, global.trimming_s, global.trimmed_submaps, global.trimmed_nodes,
      global.loop_closure_candidates, global.loop_closures_degenerate,
      global.loop_closures_beyond_drift, global.loop_closures_ambiguous, global.node_links,
      global.linked_unmeasured_steps);
  const auto per = [](size_t bytes, int count) {
    return count > 0 ? static_cast<double>(bytes) / count / 1024.0 : 0.0;
  };
  std::printf(
      "global_slam_memory: max_pending_searches=%d searches_skipped=%d submap_grids_mb=%.1f "
      "max_matchers=%d max_matcher_grids_mb=%.1f matcher_builds=%d matcher_evictions=%d node_clouds_mb=%.1f "
      "kb_per_submap=%.1f kb_per_matcher=%.1f kb_per_node=%.2f\n",
      global.max_pending_searches, global.searches_skipped, global.submap_bytes / 1048576.0,
      global.max_matchers, global.max_matcher_bytes / 1048576.0, global.matcher_builds, global.matcher_evictions,
      global.node_bytes / 1048576.0,
      per(global.submap_bytes, global.finished_submaps_held),
      per(global.max_matcher_bytes, global.max_matchers), per(global.node_bytes, global.nodes));
  std::printf("per_scan_ms: median=%.2f p99=%.2f mean=%.2f peak_rss_mb=%.1f\n",
              Percentile(scan_cost_ms, 0.5), Percentile(scan_cost_ms, 0.99),
              1e3 * wall_s / scans, usage.ru_maxrss / 1024.0);
  const auto samples = [](const std::vector<double>& values) {
    std::string line;
    for (double value : values) line += " " + std::to_string(static_cast<int>(value + 0.5));
    return line.empty() ? std::string(" none") : line;
  };
  std::printf("rss_mb_over_time: every_scans=%d end_of_slam=%.0f samples=%s\n", kRssSampleScans,
              end_of_slam_rss_mb, samples(rss_mb).c_str());
  std::printf("graph_mb_over_time: every_scans=%d samples=%s matcher_samples=%s submaps_held=%s\n",
              kRssSampleScans, samples(graph_mb).c_str(), samples(matcher_mb).c_str(),
              samples(submaps_held).c_str());
  // Whether the cost of a scan grows with the map: the first and the last 1,000 scans (the
  // same scans twice on a shorter log).
  const size_t window = std::min<size_t>(1000, scan_cost_ms.size());
  const std::vector<double> first(scan_cost_ms.begin(), scan_cost_ms.begin() + window);
  const std::vector<double> last(scan_cost_ms.end() - window, scan_cost_ms.end());
  std::printf("per_scan_ms_first_last: scans=%zu first_median=%.2f first_p99=%.2f "
              "last_median=%.2f last_p99=%.2f\n",
              window, Percentile(first, 0.5), Percentile(first, 0.99), Percentile(last, 0.5),
              Percentile(last, 0.99));
  std::printf("wrote %strajectory.tum %snodes.tum %smap.pgm %smap.yaml %smap.png\n", out.c_str(),
              out.c_str(), out.c_str(), out.c_str(), out.c_str());
  if (written.wrote_cloud) {
    std::string files;
    for (const std::string& f : written.files) {
      if (f.find("/cloud") != std::string::npos || f.find("/octomap") != std::string::npos) {
        files += " " + f;
      }
    }
    std::printf("wrote%s\n", files.c_str());
    std::printf("%s\n", written.cloud_summary.c_str());
  }
  if (session.cloud_stage() != nullptr && rgbd_frames > 0) {  // Laser-only logs: nothing to report.
    const session::CloudStageCost& cost = session.cloud_stage()->cost();
    const auto& c = session.cloud_stage()->mapper().binder().stats();
    std::printf("cloud_cost: rgbd_frames=%d per_frame_ms_median=%.1f per_frame_ms_p99=%.1f "
                "cloud_s=%.2f submap_updates=%zu update_ms_max=%.2f final_update_ms=%.2f "
                "final_update_regions=%zu final_update_points=%zu rebuilt_points_total=%lld\n",
                rgbd_frames, Percentile(cost.frame_ms, 0.5), Percentile(cost.frame_ms, 0.99),
                cost.total_s, cost.update_ms.size(),
                cost.update_ms.empty()
                    ? 0.0
                    : *std::max_element(cost.update_ms.begin(), cost.update_ms.end()),
                cost.final_update_ms, cost.final_update_regions, cost.final_update_points,
                static_cast<long long>(c.rebuilt_points_total));
  }
  if (session.visual_stage() != nullptr) {
    std::printf("%s\n", session::VisualSummaryLine(session.visual_stage()->stats()).c_str());
    std::printf("wrote %sloops.tsv\n", out.c_str());
  }
  if (!calibration_note.empty()) std::printf("%s\n", calibration_note.c_str());
  if (!args.relations.empty()) {
    if (!stamp_map_summary.empty()) std::printf("%s\n", stamp_map_summary.c_str());
    const eval::RelationError r = eval::EvaluateRelations(
        session::ToTrajectory(dense), relations);
    std::printf("relations: used=%d skipped=%d trans_mean_m=%.4f trans_std_m=%.4f "
                "rot_mean_deg=%.3f rot_std_deg=%.3f\n",
                r.count_used, r.count_skipped, r.trans_m.mean, r.trans_m.std, r.rot_deg.mean,
                r.rot_deg.std);
  }
  const double duration_s = last_stamp_s - first_stamp_s;
  // CPU of every thread (loop-closure search runs beside the scan loop), to the end of the run.
  struct rusage end_usage;
  getrusage(RUSAGE_SELF, &end_usage);
  const double cpu_s = end_usage.ru_utime.tv_sec + 1e-6 * end_usage.ru_utime.tv_usec +
                       end_usage.ru_stime.tv_sec + 1e-6 * end_usage.ru_stime.tv_usec;
  std::printf("scans=%d wall_s=%.3f realtime_factor=%.1f cpu_s=%.2f cpu_realtime_factor=%.1f\n",
              scans, wall_s, wall_s > 0 ? duration_s / wall_s : 0.0, cpu_s,
              cpu_s > 0 ? duration_s / cpu_s : 0.0);
  return 0;
}

}  // namespace offline_tool
}  // namespace fusemap
