#ifndef FUSEMAP_DAEMON_ENGINE_H_
#define FUSEMAP_DAEMON_ENGINE_H_

#include <atomic>
#include <chrono>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "fusemap/common/thread_pool.h"
#include "fusemap/daemon/bounded_queue.h"
#include "fusemap/daemon/cloud_worker.h"
#include "fusemap/daemon/daemon_options.h"
#include "fusemap/daemon/health.h"
#include "fusemap/daemon/intake.h"
#include "fusemap/daemon/publisher.h"
#include "fusemap/daemon/rate_limited_log.h"
#include "fusemap/daemon/scan_gap_gate.h"
#include "fusemap/io/slam_config.h"
#include "fusemap/io/trajectory_archive.h"
#include "fusemap/pose_graph/map_builder_2d.h"
#include "fusemap/session/slam_session.h"

namespace fusemap {
namespace daemon {

// The daemon without the network: threads and queues around the session::SlamSession that
// fusemap_offline drives too. Intake queues; the SLAM thread feeding the session; global
// optimisation on the executor (a ThreadPool, or inline on the SLAM thread with one thread:
// then runs are bit-for-bit reproducible), the SLAM thread publishing each scan's pose itself;
// a report thread (submap list at a rate and after every optimisation, loop-closure events,
// health) that may lag without holding back a pose; an RGB-D thread that runs
// the session's cloud stage on the pose updates the SLAM thread queues for it; with
// visual_loop.enabled a visual thread that runs the session's visual stage (the ORB visual loop
// checker, a back-end that may lag) on the same pose updates and the frames the RGB-D thread
// hands it through a bounded queue (oldest frame dropped when full, counted): the SLAM thread
// never waits on it. Whoever owns the LCM handle feeds intake().
// Ownership: the SLAM thread alone calls the session's SLAM half; the RGB-D thread alone its
// cloud stage; the visual thread alone its visual stage (which changes the pose graph only
// through its thread-safe loop API); the other threads only read the pose graph's thread-safe
// snapshots and counters, and the visual thread's published counters.
class Engine {
 public:
  using RgbdConsumer = std::function<void(RgbdMessage&&)>;

  Engine(const io::SlamConfig& slam, const DaemonOptions& options, int num_threads,
         OverflowPolicy policy, Publisher* publisher, RateLimitedLog* log);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  // Before Start(): hooks. Without an RGB-D consumer, frames are not decoded.
  void SetCheckpointer(Checkpointer* checkpointer) { checkpointer_ = checkpointer; }
  void SetRgbdConsumer(RgbdConsumer consumer);
  // Before Start(): where changed cloud regions go (with cloud.enabled; may stay unset).
  void SetCloudRegionPublisher(CloudRegionPublisher* publisher) { cloud_publisher_ = publisher; }
  // Before Start(): continue from a checkpointed state (--resume) and the odometry record
  // saved with it. Replaces the builder and refuses input older than the state's last node.
  void Restore(const pose_graph::MapBuilderState2D& state,
               std::vector<sensor::OdometryData> odometry);
  // Before Start(): at each checkpoint, trimmed nodes and the odometry record move out of
  // memory into `archive` (io/trajectory_archive.h), so that memory does not follow the run's
  // length; WriteOutputs reads them back.
  void SetTrajectoryArchive(std::unique_ptr<io::TrajectoryArchive> archive) {
    session_->SetTrajectoryArchive(std::move(archive));
  }
  // Before Start(), with visual_loop.enabled: the visual thread writes its keyframes to `path`
  // (io::WriteVisualKeyframesFile, atomically) every daemon.checkpoint_period_s when they
  // changed, and at shutdown. Failures count as checkpoint failures.
  void SetVisualKeyframesFile(const std::string& path) { visual_keyframes_path_ = path; }
  // Before Start(): what hands freed heap pages back to the system every
  // daemon.release_memory_period_s (default common::ReleaseFreeMemory). The SLAM thread hands
  // it to the executor right after a pose, the report thread when no pose has come for a
  // period: a worker runs it (with one thread, the thread that handed it, inline).
  void SetMemoryRelease(std::function<void()> release) { release_memory_ = std::move(release); }
  // Before Start(), after Restore(): the visual checker continues with saved keyframes. Those
  // tied to nodes the restored graph does not have (saved after its checkpoint) are left out,
  // as their node indices will be given to new nodes; returns how many were kept.
  int RestoreVisualKeyframes(io::VisualKeyframesState state);

  void Start();
  Intake& intake() { return intake_; }
  // Stops intake, processes everything queued, runs the final optimisation, writes a last
  // checkpoint, publishes the final submap list and health, and joins every thread. Idempotent.
  void Finish();

  // After Finish(): the builder and the odometry the SLAM thread accepted (since the last
  // archiving, with a trajectory archive).
  const pose_graph::MapBuilder2D& finished_builder() const { return session_->builder(); }
  const std::vector<sensor::OdometryData>& odometry() const { return session_->odometry(); }
  // After Finish(): the RGB-D thread's cloud mapper; null without cloud.enabled.
  const cloud::CloudMapper* cloud_mapper() const {
    return session_->cloud_stage() ? &session_->cloud_stage()->mapper() : nullptr;
  }
  // After Finish(): fusemap_offline's output files into `dir`.
  // With RGB-D frames bound also the cloud files; `report` (optional) lists what was written.
  bool WriteOutputs(const std::string& dir, std::string* error,
                    session::RunOutputsReport* report = nullptr) const;

  HealthReport Health() const;
  int scans_processed() const { return scans_processed_; }
  int checkpoint_failures() const { return checkpoint_failures_; }

  // Called on entry by each thread between a scan's receipt and its pose: the engine's SLAM
  // thread and the LCM handler that feeds intake(). With daemon.realtime_priority >
  // 0, SCHED_FIFO at that priority (true); a refusal is logged once and the thread keeps its
  // normal priority (false).
  bool EnterPosePath(const char* thread_name);

 private:
  using Clock = std::chrono::steady_clock;
  // A wake-up for the report thread: an optimisation moved submaps.
  struct SubmapsMoved {};

  void RunLocalSlam();
  void RunReporter();
  void RunRgbd();
  void RunVisual();
  // RGB-D thread: a decoded frame for the visual thread (those the checker would skip anyway,
  // closer than its min_interval_s, are not copied).
  void OfferVisualFrame(const sensor::RgbdFrame& frame);
  // RGB-D thread: whether OfferVisualFrame would pass on a frame of this stamp.
  bool VisualWantsFrame(double stamp_s) const;
  // Visual thread: its keyframes to visual_keyframes_path_.
  void SaveVisualKeyframes(const session::VisualStage& stage);
  void Process(SensorMessage& message);
  // SLAM thread, right after a pose (`late` zero), or report thread (`late` one period): hands
  // release_memory_ to the executor once daemon.release_memory_period_s + `late` has passed
  // since the last hand-over.
  void MaybeReleaseMemory(Clock::time_point now, Clock::duration late);
  // daemon.release_memory_period_s as a duration.
  Clock::duration ReleasePeriod() const;
  void MaybeCheckpoint(bool force);
  void PublishSubmapsAndLoops(double stamp_s);
  void ConnectSession();
  bool DecodesRgbd() const;

  const io::SlamConfig slam_;
  const DaemonOptions options_;
  Publisher* const publisher_;
  RateLimitedLog* const log_;
  Checkpointer* checkpointer_ = nullptr;
  RgbdConsumer rgbd_consumer_;
  CloudRegionPublisher* cloud_publisher_ = nullptr;
  const std::chrono::steady_clock::time_point start_;

  // Declared before the builder so that they outlive it (its callbacks push into
  // submaps_moved_).
  Intake intake_;
  BoundedQueue<SubmapsMoved> submaps_moved_;
  LatencyWindow latency_;
  // When the next memory release is due (Clock ticks since its epoch; set by Start()): SLAM
  // and report threads.
  std::atomic<Clock::rep> next_release_{0};
  // SLAM thread → RGB-D thread: the session's pose updates for its cloud stage.
  BoundedQueue<session::CloudPoseUpdate> cloud_poses_;
  // SLAM thread → visual thread: pose updates (never blocking the SLAM thread; at 25 Hz this
  // holds minutes); RGB-D thread → visual thread: frames, visual_loop.max_queue_frames.
  BoundedQueue<session::CloudPoseUpdate> visual_poses_;
  BoundedQueue<sensor::RgbdFrame> visual_frames_;
  std::atomic<int64_t> visual_frames_dropped_{0};
  std::atomic<int64_t> visual_poses_dropped_{0};
  double last_visual_frame_s_ = -1e300;  // RGB-D thread only
  // The checker's work (and, checker only, its image decoding) starts in the gap after a scan.
  ScanGapGate scan_gap_;
  // Set by the visual thread once its stage has finished (SlamSession::Finish waits for it).
  std::promise<void> visual_done_;
  std::string visual_keyframes_path_;  // empty: keyframes are not saved
  std::function<void()> release_memory_;
  std::unique_ptr<common::Executor> executor_;
  std::unique_ptr<session::SlamSession> session_;

  // RGB-D thread only (read by others only after Finish joined it); null without a cloud.
  std::unique_ptr<CloudWorker> cloud_worker_;

  // SLAM thread only (read by others only after Finish joined it).
  std::chrono::steady_clock::time_point last_checkpoint_;
  std::atomic<int> scans_processed_{0};
  std::atomic<int> checkpoint_failures_{0};
  std::atomic<double> last_stamp_s_{0.0};
  // Visual thread → report thread: its counters and newest decision, copied after each change.
  mutable std::mutex visual_mutex_;
  session::VisualStageStats visual_stats_;  // guarded by visual_mutex_
  size_t visual_records_ = 0;               // guarded by visual_mutex_
  io::LoopNote newest_loop_;                // guarded by visual_mutex_
  // Report thread only.
  int published_loop_closures_ = 0;
  size_t published_visual_records_ = 0;

  std::mutex finish_mutex_;
  bool started_ = false;   // guarded by finish_mutex_
  bool finished_ = false;  // guarded by finish_mutex_
  std::thread slam_thread_;
  std::thread report_thread_;
  std::thread rgbd_thread_;
  std::thread visual_thread_;  // with visual_loop.enabled
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_ENGINE_H_
