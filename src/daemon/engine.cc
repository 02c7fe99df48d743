#include "fusemap/daemon/engine.h"

#include <algorithm>
#include <cassert>
#include <limits>
#include <utility>
#include <variant>

#include "fusemap/common/process_memory.h"
#include "fusemap/daemon/resume.h"
#include "fusemap/daemon/this_thread.h"
#include "fusemap/io/visual_keyframes_file.h"

namespace fusemap {
namespace daemon {
namespace {

// Scan poses for the cloud mapper (~25 Hz); the RGB-D thread drains them between frames, so
// this only fills if it stalls for seconds, and then the SLAM thread waits rather than the
// cloud losing poses.
constexpr size_t kCloudPoseQueueSize = 1024;
// The RGB-D thread wakes at least this often to take poses and publish changed regions.
constexpr std::chrono::milliseconds kRgbdPoll{50};
// Scan poses for the visual thread: minutes of them at 25 Hz; if it lags further the oldest go
// (counted), never the SLAM thread's time.
constexpr size_t kVisualPoseQueueSize = 4096;
// Nice values (Linux: per thread) of the threads that may lag: global SLAM's workers
// (loop-closure searches, optimisation) and, behind them, the visual loop checker. On a busy
// machine the SLAM thread, which publishes poses, gets the CPU first (issue 15: scan->pose p99).
constexpr int kWorkerThreadNice = 5;
constexpr int kVisualThreadNice = 10;

// Seconds as the engine clock's duration (int64 ns); DaemonOptions bounds every period and rate
// so that the conversion fits.
std::chrono::steady_clock::duration Seconds(double seconds) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(seconds));
}

std::chrono::steady_clock::duration Period(double rate_hz) { return Seconds(1.0 / rate_hz); }

}  // namespace

Engine::Engine(const io::SlamConfig& slam, const DaemonOptions& options, int num_threads,
               OverflowPolicy policy, Publisher* publisher, RateLimitedLog* log)
    : slam_(slam),
      options_(options),
      publisher_(publisher),
      log_(log),
      start_(std::chrono::steady_clock::now()),
      intake_(slam, options, policy, log),
      // One pending wake-up says all there is to say: the report thread reads the graph's newest.
      submaps_moved_(1, OverflowPolicy::kDropOldest),
      cloud_poses_(kCloudPoseQueueSize, OverflowPolicy::kBlock),
      visual_poses_(kVisualPoseQueueSize, OverflowPolicy::kDropOldest,
                    [this](const session::CloudPoseUpdate&) { ++visual_poses_dropped_; }),
      visual_frames_(static_cast<size_t>(std::max(1, slam.visual_loop.max_queue_frames)),
                     OverflowPolicy::kDropOldest,
                     [this](const sensor::RgbdFrame&) { ++visual_frames_dropped_; }),
      release_memory_(common::ReleaseFreeMemory) {
  if (num_threads > 1) {
    executor_ = std::make_unique<common::ThreadPool>(num_threads, [] {
      SetThisThreadName("fusemap-worker");
      LowerThisThreadPriority(kWorkerThreadNice);
    });
  } else {
    executor_ = std::make_unique<common::InlineExecutor>();
  }
  session_ = std::make_unique<session::SlamSession>(slam_, executor_.get());
  session_->SetCloudSink(
      [this](session::CloudPoseUpdate&& update) { cloud_poses_.Push(std::move(update)); });
  if (session_->visual_stage() != nullptr) {
    auto done = std::make_shared<std::shared_future<void>>(visual_done_.get_future().share());
    session_->SetVisualSink(
        {[this](const session::CloudPoseUpdate& update) { visual_poses_.Push(update); },
         [this, done] {
           // The end of the poses; the frames end when the RGB-D thread has drained its queue.
           visual_poses_.Close();
           scan_gap_.Close();  // no more scans: the rest of the checker's work runs at once
           done->wait();
         }});
    session_->visual_stage()->SetPacer([this] { scan_gap_.WaitForGap(); });
  }
  ConnectSession();
  intake_.set_decode_rgbd(DecodesRgbd());
}

bool Engine::DecodesRgbd() const {
  return static_cast<bool>(rgbd_consumer_) || slam_.cloud.enabled || slam_.visual_loop.enabled;
}

void Engine::ConnectSession() {
  // Only a wake-up for the report thread: the cloud learns what moved from the session.
  session_->builder().pose_graph().AddSubmapsMovedCallback(
      [this](const std::vector<pose_graph::SubmapMove>&) { submaps_moved_.Push({}); });
}

void Engine::Restore(const pose_graph::MapBuilderState2D& state,
                     std::vector<sensor::OdometryData> odometry) {
  std::lock_guard<std::mutex> lock(finish_mutex_);
  assert(!started_);
  session_->Restore(state, std::move(odometry));
  ConnectSession();
  // A replay restarted from its beginning must not be mapped again: each channel skips what
  // the checkpoint already holds (odometry: its record; the rest: up to the last node).
  const double state_s = LastStateStamp(state);
  double odometry_s = session_->last_odometry_stamp_s();
  if (!(odometry_s > -std::numeric_limits<double>::infinity())) odometry_s = state_s;
  if (state_s > -std::numeric_limits<double>::infinity()) {
    for (InputChannel channel : {kLidarChannel, kImuChannel, kRgbdChannel}) {
      intake_.SetResumePoint(channel, state_s);
    }
    intake_.SetResumePoint(kOdometryChannel, odometry_s);
  }
  last_stamp_s_ = std::max(0.0, state_s);
}

Engine::~Engine() { Finish(); }

void Engine::SetRgbdConsumer(RgbdConsumer consumer) {
  rgbd_consumer_ = std::move(consumer);
  intake_.set_decode_rgbd(DecodesRgbd());
}

void Engine::Start() {
  std::lock_guard<std::mutex> lock(finish_mutex_);
  if (started_) return;
  started_ = true;
  last_checkpoint_ = std::chrono::steady_clock::now();
  next_release_ = (last_checkpoint_ + ReleasePeriod()).time_since_epoch().count();
  if (session_->cloud_stage() != nullptr) {
    cloud_worker_ = std::make_unique<CloudWorker>(session_->cloud_stage(), cloud_publisher_);
  }
  slam_thread_ = std::thread([this] { RunLocalSlam(); });
  report_thread_ = std::thread([this] { RunReporter(); });
  rgbd_thread_ = std::thread([this] { RunRgbd(); });
  if (session_->visual_stage() != nullptr) visual_thread_ = std::thread([this] { RunVisual(); });
}

void Engine::Finish() {
  std::lock_guard<std::mutex> lock(finish_mutex_);
  if (finished_) return;
  finished_ = true;
  intake_.Close();
  if (!started_) {
    // Never started: nothing queued was processed; still leave a consistent builder behind.
    session_->builder().Finish();
    return;
  }
  slam_thread_.join();
  rgbd_thread_.join();
  if (visual_thread_.joinable()) visual_thread_.join();
  submaps_moved_.Close();
  report_thread_.join();
}

void Engine::Process(SensorMessage& message) {
  if (message.after_time_reset) session_->OnTimeReset();
  if (auto* scan = std::get_if<sensor::LaserScan>(&message.data)) {
    const auto pose = session_->AddScan(*scan);
    ++scans_processed_;
    last_stamp_s_ = scan->stamp_s;
    if (pose) {
      // Here, not on a thread of its own: handing the pose over cost its wake-up, 1.5-3 ms in
      // the slowest scans on an idle core of a virtual machine (issue 17), for a send of
      // microseconds.
      publisher_->PublishPose(scan->stamp_s, pose->T_map_tracking);
      const auto published = Clock::now();
      latency_.Add(std::chrono::duration<double, std::milli>(published - message.received).count());
      MaybeReleaseMemory(published, Clock::duration::zero());
    }
    // After the pose: the checker's work this releases starts after the publication.
    // Only the checker waits on the gate: without it, no lock on this thread's path.
    if (session_->visual_stage() != nullptr) scan_gap_.ScanDone(std::chrono::steady_clock::now());
  } else if (auto* odometry = std::get_if<sensor::OdometryData>(&message.data)) {
    session_->AddOdometry(*odometry);
  } else if (auto* imu = std::get_if<sensor::ImuData>(&message.data)) {
    session_->AddImu(*imu);
  }
}

bool Engine::EnterPosePath(const char* thread_name) {
  if (options_.realtime_priority == 0) return false;
  std::string error;
  if (SetThisThreadRealtime(options_.realtime_priority, &error)) return true;
  if (log_ != nullptr) {
    log_->Report("daemon.realtime_priority",
                 std::string(thread_name) + " thread: " + error + "; it runs at normal priority");
  }
  return false;
}

void Engine::RunLocalSlam() {
  SetThisThreadName("fusemap-slam");
  EnterPosePath("SLAM");
  while (auto message = intake_.sensor_queue().Pop()) {
    Process(*message);
    MaybeCheckpoint(false);
  }
  session_->Finish();  // the cloud's last update goes through cloud_poses_
  cloud_poses_.Close();
  MaybeCheckpoint(true);
}

void Engine::MaybeCheckpoint(bool force) {
  if (checkpointer_ == nullptr) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && (options_.checkpoint_period_s <= 0.0 ||
                 now - last_checkpoint_ < std::chrono::duration<double>(options_.checkpoint_period_s))) {
    return;
  }
  last_checkpoint_ = now;
  executor_->WaitIdle();
  std::string error;
  if (!session_->ArchiveSettled(&error)) {
    // Health counts it with the checkpoints: both are the run's state not reaching the disk.
    ++checkpoint_failures_;
    if (log_ != nullptr) log_->Report("trajectory archive", error);
  }
  RunRecord record;
  record.odometry = &session_->odometry();
  if (session_->archive() != nullptr) record.archive = &session_->archive()->mark();
  if (!checkpointer_->Save(session_->builder(), record, &error)) {
    ++checkpoint_failures_;
    if (log_ != nullptr) log_->Report("checkpoint", error);
  }
}

void Engine::RunRgbd() {
  using Clock = std::chrono::steady_clock;
  SetThisThreadName("fusemap-rgbd");
  if (!cloud_worker_) {
    // Decoding images is the checker's work here: at the checker's priority, so that it never
    // takes the CPU from the SLAM thread (scan->pose latency, issue 17), and only for frames
    // the checker takes.
    if (!rgbd_consumer_) LowerThisThreadPriority(kVisualThreadNice);
    while (auto frame = intake_.rgbd_queue().Pop()) {
      const bool wanted = rgbd_consumer_ || VisualWantsFrame(frame->frame.stamp_s);
      if (wanted && !rgbd_consumer_) scan_gap_.WaitForGap();
      if (wanted && intake_.DecodeImages(&*frame)) {
        OfferVisualFrame(frame->frame);
        if (rgbd_consumer_) rgbd_consumer_(std::move(*frame));
      }
    }
    visual_frames_.Close();
    return;
  }
  // Poses first, then at most one frame: a frame waits in the mapper for the pose after it.
  const auto take_poses = [this](Clock::time_point deadline) {
    while (auto update = cloud_poses_.PopUntil(deadline)) {
      cloud_worker_->AddPoseUpdate(*update);
      deadline = Clock::now() - kRgbdPoll;  // only what is already queued
    }
  };
  while (!intake_.rgbd_queue().closed_and_drained()) {
    take_poses(Clock::now() - kRgbdPoll);
    auto frame = intake_.rgbd_queue().PopUntil(Clock::now() + kRgbdPoll);
    if (frame && intake_.DecodeImages(&*frame)) {
      cloud_worker_->AddFrame(frame->frame);
      OfferVisualFrame(frame->frame);
      if (rgbd_consumer_) rgbd_consumer_(std::move(*frame));
    }
    cloud_worker_->MaybePublish(Clock::now());
  }
  visual_frames_.Close();
  while (!cloud_poses_.closed_and_drained()) {
    take_poses(Clock::now() + kRgbdPoll);
    cloud_worker_->MaybePublish(Clock::now());
  }
  cloud_worker_->Finish();
}

bool Engine::VisualWantsFrame(double stamp_s) const {
  return session_->visual_stage() != nullptr &&
         !(stamp_s - last_visual_frame_s_ < slam_.visual_loop.checker.selector.min_interval_s);
}

void Engine::OfferVisualFrame(const sensor::RgbdFrame& frame) {
  if (!VisualWantsFrame(frame.stamp_s)) return;
  last_visual_frame_s_ = frame.stamp_s;
  visual_frames_.Push(frame);
}

int Engine::RestoreVisualKeyframes(io::VisualKeyframesState state) {
  std::lock_guard<std::mutex> lock(finish_mutex_);
  assert(!started_);
  session::VisualStage* stage = session_->visual_stage();
  if (stage == nullptr) return 0;
  const int nodes = session_->builder().pose_graph().stats().nodes;
  auto& keyframes = state.keyframes;
  keyframes.erase(std::remove_if(keyframes.begin(), keyframes.end(),
                                 [nodes](const io::VisualKeyframesState::Entry& e) {
                                   return e.saved.keyframe.node >= nodes;
                                 }),
                  keyframes.end());
  const int kept = static_cast<int>(keyframes.size());
  stage->RestoreState(std::move(state));
  return kept;
}

void Engine::SaveVisualKeyframes(const session::VisualStage& stage) {
  if (visual_keyframes_path_.empty()) return;
  std::string error;
  if (!io::WriteVisualKeyframesFile(visual_keyframes_path_, stage.ExportState(), &error)) {
    ++checkpoint_failures_;
    if (log_ != nullptr) log_->Report("visual keyframes", error);
  }
}

void Engine::RunVisual() {
  using Clock = std::chrono::steady_clock;
  // A back-end that may lag: on a busy machine the SLAM thread (pose publication) gets the CPU
  // first.
  SetThisThreadName("fusemap-visual");
  LowerThisThreadPriority(kVisualThreadNice);
  session::VisualStage* stage = session_->visual_stage();
  const auto publish = [this, stage] {
    std::lock_guard<std::mutex> lock(visual_mutex_);
    visual_stats_ = stage->stats();
    visual_records_ = stage->records().size();
    if (!stage->records().empty()) {
      const visual_loop::ArbitrationRecord& newest = stage->records().back();
      newest_loop_ = {visual_loop::ToString(newest.source), visual_loop::ToString(newest.decision)};
    }
  };
  // Saved on this thread, which alone owns the keyframes, on the checkpoint period.
  const bool periodic = options_.checkpoint_period_s > 0.0;
  const auto period = Seconds(periodic ? options_.checkpoint_period_s : 1.0);
  auto next_save = Clock::now() + period;
  int saved_keyframes = -1;
  while (true) {
    if (periodic && Clock::now() >= next_save) {
      next_save = Clock::now() + period;
      const int keyframes = stage->stats().checker.keyframes;
      if (keyframes != saved_keyframes) SaveVisualKeyframes(*stage);
      saved_keyframes = keyframes;
    }
    // Poses first (only those already queued), then at most one frame: a frame waits in the
    // stage for the pose after it.
    while (auto update = visual_poses_.PopUntil(Clock::now() - kRgbdPoll)) stage->Apply(*update);
    if (!visual_frames_.closed_and_drained()) {
      if (auto frame = visual_frames_.PopUntil(Clock::now() + kRgbdPoll)) stage->AddFrame(*frame);
    } else if (visual_poses_.closed_and_drained()) {
      break;
    } else if (auto update = visual_poses_.PopUntil(Clock::now() + kRgbdPoll)) {
      stage->Apply(*update);
    }
    publish();
  }
  stage->Finish();
  publish();
  SaveVisualKeyframes(*stage);
  visual_done_.set_value();
}

void Engine::PublishSubmapsAndLoops(double stamp_s) {
  const auto snapshot = session_->builder().pose_graph().Snapshot();
  publisher_->PublishSubmapList(stamp_s, *snapshot);
  const auto stats = session_->builder().pose_graph().stats();
  io::LoopNote note;
  size_t visual_records = 0;
  {
    std::lock_guard<std::mutex> lock(visual_mutex_);
    note = newest_loop_;
    visual_records = visual_records_;
  }
  // New laser loops, or new decisions of the visual loop checker (a forced loop is no laser
  // closure, but an event all the same).
  if (stats.loop_closures_found > published_loop_closures_ ||
      visual_records > published_visual_records_) {
    publisher_->PublishLoopClosure(
        stamp_s, std::max(0, stats.loop_closures_found - published_loop_closures_), stats,
        stats.nodes - 1, note);
    published_loop_closures_ = std::max(published_loop_closures_, stats.loop_closures_found);
    published_visual_records_ = visual_records;
  }
}

Engine::Clock::duration Engine::ReleasePeriod() const {
  return Seconds(options_.release_memory_period_s);
}

void Engine::MaybeReleaseMemory(Clock::time_point now, Clock::duration late) {
  if (options_.release_memory_period_s <= 0.0) return;
  Clock::rep due = next_release_.load();
  if (now.time_since_epoch().count() < due + late.count()) return;
  // One hand-over per period even when both threads find it due at once.
  if (!next_release_.compare_exchange_strong(due,
                                             (now + ReleasePeriod()).time_since_epoch().count())) {
    return;
  }
  executor_->ScheduleFirst(release_memory_);
}

void Engine::RunReporter() {
  SetThisThreadName("fusemap-report");
  const auto submap_period = Period(options_.submap_list_rate_hz);
  const auto health_period = Period(options_.health_rate_hz);
  auto next_submaps = Clock::now() + submap_period;
  auto next_health = Clock::now() + health_period;
  // malloc_trim takes 3-18 ms with the checker's images in the heap (corridor world). The SLAM
  // thread hands it to a worker right after a pose, at the start of the gap before the next
  // scan; without scans this thread does, a period late.
  const auto release_overdue = [&] {
    if (options_.release_memory_period_s <= 0.0) return Clock::time_point::max();
    return Clock::time_point(Clock::duration(next_release_.load())) + ReleasePeriod();
  };
  while (true) {
    const auto moved =
        submaps_moved_.PopUntil(std::min({next_submaps, next_health, release_overdue()}));
    if (!moved && submaps_moved_.closed_and_drained()) break;
    const auto now = Clock::now();
    if (moved || now >= next_submaps) {
      PublishSubmapsAndLoops(last_stamp_s_);
      next_submaps = now + submap_period;
    }
    if (now >= next_health) {
      publisher_->PublishHealth(last_stamp_s_, Health());
      next_health = now + health_period;
    }
    MaybeReleaseMemory(now, ReleasePeriod());
  }
  PublishSubmapsAndLoops(last_stamp_s_);
  publisher_->PublishHealth(last_stamp_s_, Health());
}

HealthReport Engine::Health() const {
  HealthReport report;
  report.uptime_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  report.channels = intake_.ChannelHealth();
  report.latency = latency_.Summarize();
  report.rss_bytes = common::ResidentMemoryBytes();
  const auto stats = session_->builder().pose_graph().stats();
  report.nodes = stats.nodes - stats.trimmed_nodes;
  report.submaps = stats.submaps - stats.trimmed_submaps;
  report.constraints = stats.constraints;
  report.trimmed_nodes = stats.trimmed_nodes;
  report.trimmed_submaps = stats.trimmed_submaps;
  report.loop_closures = stats.loop_closures_found;
  report.optimizations = stats.optimizations;
  report.pending_searches = stats.pending_searches;
  report.checkpoint_failures = checkpoint_failures_;
  report.time_resets = intake_.time_resets();
  if (session_->visual_stage() != nullptr) {
    std::lock_guard<std::mutex> lock(visual_mutex_);
    const session::VisualStageStats& v = visual_stats_;
    report.visual.keyframes = v.checker.keyframes;
    report.visual.candidates = v.checker.candidates;
    report.visual.verified = v.checker.verified;
    report.visual.forced = v.forced;
    report.visual.overridden = v.overridden;
    report.visual.rejected = v.rejected;
    report.visual.queue_depth = static_cast<int>(visual_frames_.size());
    // Every frame the checker lost: its thread's queue, and frames that found no pose.
    report.visual.dropped_frames =
        visual_frames_dropped_ + v.frames_dropped_pending + v.frames_dropped_no_pose;
  }
  return report;
}

bool Engine::WriteOutputs(const std::string& dir, std::string* error,
                          session::RunOutputsReport* report) const {
  session::RunOutputsReport local_report;
  return session_->WriteOutputs(dir, report != nullptr ? report : &local_report, error);
}

}  // namespace daemon
}  // namespace fusemap
