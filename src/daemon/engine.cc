#include "fusemap/daemon/engine.h"

#include <algorithm>
#include <utility>
#include <variant>

#include "fusemap/daemon/map_outputs.h"

namespace fusemap {
namespace daemon {
namespace {

// Pose outputs are small and frequent; if the publisher falls behind, old poses are worthless.
constexpr size_t kOutputQueueSize = 256;

std::chrono::steady_clock::duration Period(double rate_hz) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(1.0 / rate_hz));
}

}  // namespace

Engine::Engine(const io::SlamConfig& slam, const DaemonOptions& options, int num_threads,
               OverflowPolicy policy, Publisher* publisher, RateLimitedLog* log)
    : slam_(slam),
      options_(options),
      publisher_(publisher),
      log_(log),
      start_(std::chrono::steady_clock::now()),
      intake_(slam, options, policy, log),
      outputs_(kOutputQueueSize, OverflowPolicy::kDropOldest) {
  if (num_threads > 1) {
    executor_ = std::make_unique<common::ThreadPool>(num_threads);
  } else {
    executor_ = std::make_unique<common::InlineExecutor>();
  }
  builder_ = std::make_unique<pose_graph::MapBuilder2D>(slam_.map_builder, executor_.get());
  builder_->pose_graph().AddSubmapsMovedCallback([this](const std::vector<pose_graph::SubmapMove>&) {
    OutputEvent event;
    event.kind = OutputEvent::Kind::kSubmapsMoved;
    outputs_.Push(std::move(event));
  });
}

Engine::~Engine() { Finish(); }

void Engine::SetRgbdConsumer(RgbdConsumer consumer) {
  rgbd_consumer_ = std::move(consumer);
  intake_.set_decode_rgbd(static_cast<bool>(rgbd_consumer_));
}

void Engine::Start() {
  std::lock_guard<std::mutex> lock(finish_mutex_);
  if (started_) return;
  started_ = true;
  last_checkpoint_ = std::chrono::steady_clock::now();
  slam_thread_ = std::thread([this] { RunLocalSlam(); });
  publisher_thread_ = std::thread([this] { RunPublisher(); });
  rgbd_thread_ = std::thread([this] { RunRgbd(); });
}

void Engine::Finish() {
  std::lock_guard<std::mutex> lock(finish_mutex_);
  if (finished_) return;
  finished_ = true;
  intake_.Close();
  if (!started_) {
    // Never started: nothing queued was processed; still leave a consistent builder behind.
    builder_->Finish();
    return;
  }
  slam_thread_.join();
  rgbd_thread_.join();
  outputs_.Close();
  publisher_thread_.join();
}

void Engine::Process(SensorMessage& message) {
  if (auto* scan = std::get_if<sensor::LaserScan>(&message.data)) {
    const auto pose = builder_->AddScan(*scan);
    ++scans_processed_;
    last_stamp_s_ = scan->stamp_s;
    if (pose) {
      OutputEvent event;
      event.received = message.received;
      event.stamp_s = scan->stamp_s;
      event.pose = pose->T_map_tracking;
      outputs_.Push(std::move(event));
    }
  } else if (auto* odometry = std::get_if<sensor::OdometryData>(&message.data)) {
    // As fusemap_offline: odometry that goes back in time is skipped, the rest recorded for
    // the densified trajectory. (Intake already rejects those; this keeps the two paths equal.)
    if (!odometry_.empty() && odometry->stamp_s < odometry_.back().stamp_s) return;
    odometry_.push_back(*odometry);
    builder_->AddOdometry(*odometry);
  } else if (auto* imu = std::get_if<sensor::ImuData>(&message.data)) {
    builder_->AddImu(*imu);
  }
}

void Engine::RunLocalSlam() {
  while (auto message = intake_.sensor_queue().Pop()) {
    Process(*message);
    MaybeCheckpoint(false);
  }
  builder_->Finish();
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
  if (!checkpointer_->Save(*builder_, &error)) {
    ++checkpoint_failures_;
    if (log_ != nullptr) log_->Report("checkpoint", error);
  }
}

void Engine::RunRgbd() {
  while (auto frame = intake_.rgbd_queue().Pop()) {
    if (rgbd_consumer_) rgbd_consumer_(std::move(*frame));
  }
}

void Engine::PublishSubmapsAndLoops(double stamp_s) {
  const auto snapshot = builder_->pose_graph().Snapshot();
  publisher_->PublishSubmapList(stamp_s, *snapshot);
  const auto stats = builder_->pose_graph().stats();
  if (stats.loop_closures_found > published_loop_closures_) {
    publisher_->PublishLoopClosure(stamp_s, stats.loop_closures_found - published_loop_closures_,
                                   stats, stats.nodes - 1);
    published_loop_closures_ = stats.loop_closures_found;
  }
}

void Engine::RunPublisher() {
  using Clock = std::chrono::steady_clock;
  const auto submap_period = Period(options_.submap_list_rate_hz);
  const auto health_period = Period(options_.health_rate_hz);
  auto next_submaps = Clock::now() + submap_period;
  auto next_health = Clock::now() + health_period;
  while (true) {
    auto event = outputs_.PopUntil(std::min(next_submaps, next_health));
    if (event) {
      if (event->kind == OutputEvent::Kind::kPose) {
        publisher_->PublishPose(event->stamp_s, event->pose);
        latency_.Add(std::chrono::duration<double, std::milli>(Clock::now() - event->received)
                         .count());
      } else {
        PublishSubmapsAndLoops(last_stamp_s_);
        next_submaps = Clock::now() + submap_period;
      }
    } else if (outputs_.closed_and_drained()) {
      break;
    }
    const auto now = Clock::now();
    if (now >= next_submaps) {
      PublishSubmapsAndLoops(last_stamp_s_);
      next_submaps = now + submap_period;
    }
    if (now >= next_health) {
      publisher_->PublishHealth(last_stamp_s_, Health());
      next_health = now + health_period;
    }
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
  report.rss_bytes = ResidentMemoryBytes();
  const auto stats = builder_->pose_graph().stats();
  report.nodes = stats.nodes;
  report.submaps = stats.submaps;
  report.constraints = stats.intra_constraints + stats.loop_closures_found;
  report.loop_closures = stats.loop_closures_found;
  report.optimizations = stats.optimizations;
  return report;
}

bool Engine::WriteOutputs(const std::string& dir, std::string* error) const {
  return WriteMapOutputs(*builder_, odometry_, slam_.map_builder.local_slam.submaps.resolution_m,
                         dir, error);
}

}  // namespace daemon
}  // namespace fusemap
