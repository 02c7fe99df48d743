// The engine's threads as fusemapd runs them: what may and may not hold back a pose.
#include "fusemap/daemon/engine.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <future>
#include <mutex>

#include "fusemap/daemon/publisher.h"
#include "testing/room_drive_log.h"
#include "testing/room_slam_config.h"

namespace fusemap {
namespace daemon {
namespace {

// Counts poses; the test waits on the count.
class PoseCounter : public Publisher {
 public:
  void PublishPose(double, const common::Rigid2d&) override {
    std::lock_guard<std::mutex> lock(mutex_);
    ++poses_;
    changed_.notify_all();
  }
  void PublishSubmapList(double, const pose_graph::PoseGraphSnapshot&) override {}
  void PublishLoopClosure(double, int, const pose_graph::PoseGraph2D::Stats&, int,
                          const io::LoopNote&) override {}
  void PublishHealth(double, const HealthReport&) override {}

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

// malloc_trim took 3-18 ms on fusemapd's publisher thread (checker on, corridor world), and
// every pose queued meanwhile waited for it. A release that does not return at all shows it
// plainly: poses must keep coming while it runs.
TEST(EngineTest, ReleasingMemoryHoldsBackNoPose) {
  DaemonOptions options;
  options.release_memory_period_s = 1e-3;  // due after the first pose
  // Declared before the engine, which may still run a release while it is destroyed.
  std::promise<void> release_started;
  std::promise<void> release_may_end;
  std::shared_future<void> may_end = release_may_end.get_future().share();
  std::atomic<bool> first{true};  // only the first release waits (the test's)
  PoseCounter publisher;
  Engine engine(test_world::RoomSlamConfig(), options, 2, OverflowPolicy::kBlock, &publisher,
                nullptr);
  engine.SetMemoryRelease([&, may_end] {
    if (!first.exchange(false)) return;
    release_started.set_value();
    may_end.wait();
  });
  engine.Start();

  const auto messages = test_world::RoomDriveMessages(0.15, 1700000000.0, 42);
  constexpr int kScans = 40;
  int scans = 0;
  size_t next = 0;
  const auto feed_scans = [&](int count) {
    const int until = scans + count;
    for (; next < messages.size() && scans < until; ++next) {
      const auto& message = messages[next];
      engine.intake().OnMessage(message.channel, message.data.data(),
                                static_cast<int>(message.data.size()));
      if (message.channel == "LIDAR") ++scans;
    }
  };
  feed_scans(5);
  ASSERT_EQ(release_started.get_future().wait_for(std::chrono::seconds(60)),
            std::future_status::ready)
      << "no memory release within a minute of the first poses";
  const int poses_before = publisher.poses();
  feed_scans(kScans);
  const bool published = publisher.WaitForPoses(poses_before + kScans, std::chrono::seconds(60));
  const int published_meanwhile = publisher.poses() - poses_before;
  release_may_end.set_value();
  engine.Finish();
  EXPECT_TRUE(published) << "poses while the release ran: " << published_meanwhile << " of "
                         << kScans;
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
