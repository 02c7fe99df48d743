// The engine's threads as fusemapd runs them: what may and may not hold back a pose.
#include "fusemap/daemon/engine.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <future>
#include <mutex>
#include <vector>

#include "fusemap/daemon/publisher.h"
#include "testing/room_drive_log.h"
#include "testing/room_slam_config.h"

namespace fusemap {
namespace daemon {
namespace {

// Counts poses; the test waits on the count. `on_submap_list`, if set, runs in each
// PublishSubmapList.
class PoseCounter : public Publisher {
 public:
  void PublishPose(double, const common::Rigid2d&) override {
    std::lock_guard<std::mutex> lock(mutex_);
    ++poses_;
    changed_.notify_all();
  }
  void PublishSubmapList(double, const pose_graph::PoseGraphSnapshot&) override {
    if (on_submap_list) on_submap_list();
  }
  void PublishLoopClosure(double, int, const pose_graph::PoseGraph2D::Stats&, int,
                          const io::LoopNote&) override {}
  void PublishHealth(double, const HealthReport&) override {}

  std::function<void()> on_submap_list;  // set before the engine starts

  int poses() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return poses_;
  }
  // True once `count` poses are out; false if that takes longer than `timeout` (a generous
  // bound, only there so that a failing test ends).
  bool WaitForPoses(int count, std::chrono::seconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] { return poses_ >= count; });
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  int poses_ = 0;
};

// Feeds the room drive's messages to an engine's intake, a number of scans at a time.
class RoomFeeder {
 public:
  explicit RoomFeeder(Engine* engine)
      : engine_(engine), messages_(test_world::RoomDriveMessages(0.15, 1700000000.0, 42)) {}
  void FeedScans(int count) {
    const int until = scans_ + count;
    for (; next_ < messages_.size() && scans_ < until; ++next_) {
      const auto& message = messages_[next_];
      engine_->intake().OnMessage(message.channel, message.data.data(),
                                  static_cast<int>(message.data.size()));
      if (message.channel == "LIDAR") ++scans_;
    }
  }

 private:
  Engine* const engine_;
  const std::vector<test_world::EncodedMessage> messages_;
  size_t next_ = 0;
  int scans_ = 0;
};

// A call that blocks its thread until the test lets it go (once; later calls return at once),
// telling the test when it started.
class Gate {
 public:
  void Block() {
    if (!first_.exchange(false)) return;
    started_.set_value();
    may_end_.wait();
  }
  bool WaitUntilBlocked(std::chrono::seconds timeout) {
    return started_future_.wait_for(timeout) == std::future_status::ready;
  }
  // Idempotent.
  void Open() {
    std::call_once(opened_, [this] { may_end_promise_.set_value(); });
  }

 private:
  std::atomic<bool> first_{true};
  std::promise<void> started_;
  std::future<void> started_future_ = started_.get_future();
  std::promise<void> may_end_promise_;
  std::shared_future<void> may_end_ = may_end_promise_.get_future().share();
  std::once_flag opened_;
};

// Opens a gate when the test leaves, a failed assertion too, before the engine declared ahead of
// it joins its threads (one may be blocked in the gate).
class OpenAtExit {
 public:
  explicit OpenAtExit(Gate* gate) : gate_(gate) {}
  ~OpenAtExit() { gate_->Open(); }
  OpenAtExit(const OpenAtExit&) = delete;
  OpenAtExit& operator=(const OpenAtExit&) = delete;

 private:
  Gate* const gate_;
};

// Feeds the room drive to a started engine until `gate` holds a thread, then kScans more while it
// holds; succeeds when all their poses come out meanwhile. Opens the gate and finishes the engine
// unless the gate never closed (then the test's OpenAtExit opens it).
::testing::AssertionResult PosesFlowWhileHeld(Engine* engine, Gate* gate, PoseCounter* publisher,
                                              const char* what) {
  RoomFeeder feeder(engine);
  constexpr int kScans = 40;
  feeder.FeedScans(5);
  if (!gate->WaitUntilBlocked(std::chrono::seconds(60))) {
    return ::testing::AssertionFailure() << "no " << what << " within a minute of the first poses";
  }
  const int poses_before = publisher->poses();
  feeder.FeedScans(kScans);
  const bool published = publisher->WaitForPoses(poses_before + kScans, std::chrono::seconds(60));
  const int published_meanwhile = publisher->poses() - poses_before;
  gate->Open();
  engine->Finish();
  if (published) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "poses while the " << what << " was held: " << published_meanwhile << " of " << kScans;
}

// malloc_trim took 3-18 ms on fusemapd's publisher thread (checker on, corridor world), and
// every pose queued meanwhile waited for it. A release that does not return at all shows it
// plainly: poses must keep coming while it runs.
TEST(EngineTest, ReleasingMemoryHoldsBackNoPose) {
  DaemonOptions options;
  options.release_memory_period_s = 1e-3;  // due after the first pose
  Gate release;  // declared before the engine, which may still run a release while destroyed
  PoseCounter publisher;
  Engine engine(test_world::RoomSlamConfig(), options, 2, OverflowPolicy::kBlock, &publisher,
                nullptr);
  engine.SetMemoryRelease([&release] { release.Block(); });
  const OpenAtExit open_at_exit(&release);
  engine.Start();
  EXPECT_TRUE(PosesFlowWhileHeld(&engine, &release, &publisher, "memory release"));
}

// The submap list, loop-closure events and health go out on a thread that may lag; the poses
// once shared a thread with them, and one that did not return (a slow subscriber, a graph lock
// held by an optimisation) held back every pose behind it.
TEST(EngineTest, AStuckReportHoldsBackNoPose) {
  DaemonOptions options;
  options.submap_list_rate_hz = 1000.0;  // due at once
  Gate report;
  PoseCounter publisher;
  publisher.on_submap_list = [&report] { report.Block(); };
  Engine engine(test_world::RoomSlamConfig(), options, 2, OverflowPolicy::kBlock, &publisher,
                nullptr);
  const OpenAtExit open_at_exit(&report);
  engine.Start();
  EXPECT_TRUE(PosesFlowWhileHeld(&engine, &report, &publisher, "submap list"));
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
