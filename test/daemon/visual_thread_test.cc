// The engine's visual thread (visual_loop.enabled): the ORB visual loop checker on its own
// thread, fed by the SLAM thread's pose updates and the RGB-D thread's frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fusemap/daemon/engine.h"
#include "fusemap/io/loops_file.h"
#include "fusemap/io/rgbd_conversions.h"
#include "fusemap/io/visual_keyframes_file.h"
#include "fusemap/common/math.h"
#include "testing/room_drive_log.h"
#include "testing/room_slam_config.h"
#include "testing/textured_box_camera.h"

namespace fusemap {
namespace daemon {
namespace {

constexpr double kStepM = 0.15;
constexpr double kStartS = 1700000000.0;

class LoopRecorder : public Publisher {
 public:
  void PublishPose(double, const common::Rigid2d&) override { ++poses; }
  void PublishSubmapList(double, const pose_graph::PoseGraphSnapshot&) override {}
  void PublishLoopClosure(double, int, const pose_graph::PoseGraph2D::Stats&, int,
                          const io::LoopNote& note) override {
    notes.push_back(note);
  }
  void PublishHealth(double, const HealthReport& r) override { last_health = r; }
  // The engine's SLAM thread writes `poses`, its report thread the rest; the test reads after
  // Finish() joined both.
  int poses = 0;
  std::vector<io::LoopNote> notes;
  HealthReport last_health;
};

io::SlamConfig VisualConfig() {
  io::SlamConfig config = test_world::RoomSlamConfig();
  config.cloud.enabled = false;
  config.visual_loop.enabled = true;
  std::string error;
  EXPECT_TRUE(io::LoadVisualLoopVocabulary(&config.visual_loop, &error)) << error;
  config.visual_loop.checker.detector.recognition.num_recent_excluded = 10;
  config.visual_loop.checker.detector.recognition.temporal_consistency = 1;
  // The test feeds faster than real time: a queue that holds the whole drive keeps the run
  // deterministic (live, the oldest frames would go).
  config.visual_loop.max_queue_frames = 512;
  return config;
}

// Feeds the room drive's messages from `first` (scan index) to `last` (exclusive), each scan
// followed by a camera frame at its true pose.
void Feed(Engine* engine, int first, int last) {
  const test_world::TexturedBoxCamera camera(2.0, 0.0, 10.0, 8.0, 7);
  io::RgbdEncodeOptions raw;
  raw.color_encoding = "rgb8";
  raw.depth_encoding = "mono16";
  int scan = -1;
  for (const auto& message : test_world::RoomDriveMessages(kStepM, kStartS, 42)) {
    if (message.channel == "LIDAR") ++scan;
    if (scan < first || scan >= last) continue;
    engine->intake().OnMessage(message.channel, message.data.data(),
                               static_cast<int>(message.data.size()));
    if (message.channel != "LIDAR") continue;
    std::vector<uint8_t> bytes;
    std::string error;
    ASSERT_TRUE(io::EncodeRgbdFrame(camera.Render(message.stamp_s, test_world::ArcPose(scan, kStepM)),
                                    raw, &bytes, &error))
        << error;
    engine->intake().OnMessage("RGBD", bytes.data(), static_cast<int>(bytes.size()));
  }
}

// A restart between the laps (the daemon's --resume: graph from the checkpoint, keyframes
// from the file the visual thread wrote): the second lap still finds its way back.
TEST(VisualThreadTest, KeyframesSurviveARestart) {
  RateLimitedLog quiet(1e9, [] { return 0.0; }, [](const std::string&) {});
  const std::string path = ::testing::TempDir() + "/visual_thread_keyframes.fmvk";
  std::remove(path.c_str());
  const int num_scans = static_cast<int>(1.1 * 2.0 * common::kPi * test_world::kArcRadiusM / kStepM);
  const int restart = num_scans - 20;
  pose_graph::MapBuilderState2D state;
  std::vector<sensor::OdometryData> odometry;
  {
    LoopRecorder publisher;
    Engine first(VisualConfig(), DaemonOptions(), 1, OverflowPolicy::kBlock, &publisher, &quiet);
    first.SetVisualKeyframesFile(path);
    first.Start();
    Feed(&first, 0, restart);
    first.Finish();
    state = first.finished_builder().ExportState();
    odometry = first.odometry();
  }
  io::VisualKeyframesState keyframes;
  std::string error;
  ASSERT_TRUE(io::ReadVisualKeyframesFile(path, &keyframes, &error)) << error;
  const size_t saved = keyframes.keyframes.size();
  EXPECT_GT(saved, 20u);

  LoopRecorder publisher;
  Engine second(VisualConfig(), DaemonOptions(), 1, OverflowPolicy::kBlock, &publisher, &quiet);
  second.Restore(state, std::move(odometry));
  EXPECT_EQ(second.RestoreVisualKeyframes(std::move(keyframes)), static_cast<int>(saved));
  second.Start();
  Feed(&second, restart, num_scans);
  second.Finish();
  const io::HealthReport::Visual& v = publisher.last_health.visual;
  std::printf("after the restart: keyframes=%d verified=%d\n", v.keyframes, v.verified);
  EXPECT_GT(v.keyframes, static_cast<int>(saved));
  // Only restored keyframes are old enough to be loop candidates for the second lap's end.
  EXPECT_GT(v.verified, 0);
}

TEST(VisualThreadTest, ChecksLoopsOnItsOwnThreadAndReportsThem) {
  RateLimitedLog quiet(1e9, [] { return 0.0; }, [](const std::string&) {});
  LoopRecorder publisher;
  Engine engine(VisualConfig(), DaemonOptions(), 1, OverflowPolicy::kBlock, &publisher, &quiet);
  engine.Start();
  // The room drive, with a camera frame (raw images: no codec cost) after every scan, taken
  // at the true pose in a textured box around the arc.
  const test_world::TexturedBoxCamera camera(2.0, 0.0, 10.0, 8.0, 7);
  io::RgbdEncodeOptions raw;
  raw.color_encoding = "rgb8";
  raw.depth_encoding = "mono16";
  int scans = 0;
  for (const auto& message : test_world::RoomDriveMessages(kStepM, kStartS, 42)) {
    engine.intake().OnMessage(message.channel, message.data.data(),
                              static_cast<int>(message.data.size()));
    if (message.channel != "LIDAR") continue;
    std::vector<uint8_t> bytes;
    std::string error;
    ASSERT_TRUE(io::EncodeRgbdFrame(
        camera.Render(message.stamp_s, test_world::ArcPose(scans++, kStepM)), raw, &bytes,
        &error))
        << error;
    engine.intake().OnMessage("RGBD", bytes.data(), static_cast<int>(bytes.size()));
  }
  engine.Finish();
  EXPECT_EQ(engine.scans_processed(), scans);
  EXPECT_EQ(publisher.poses, scans);  // every pose published, whatever the checker did

  const io::HealthReport::Visual& v = publisher.last_health.visual;
  std::printf("visual health: keyframes=%d candidates=%d verified=%d forced=%d overridden=%d "
              "rejected=%d queue=%d dropped=%lld\n",
              v.keyframes, v.candidates, v.verified, v.forced, v.overridden, v.rejected,
              v.queue_depth, static_cast<long long>(v.dropped_frames));
  EXPECT_GT(v.keyframes, 30);
  EXPECT_EQ(v.queue_depth, 0);
  EXPECT_EQ(v.dropped_frames, 0);
  // The lap's end revisits its start: found by the camera, forced (no laser search is as
  // quick... whichever came first, some decision was published with its source).
  ASSERT_FALSE(publisher.notes.empty());
  EXPECT_FALSE(publisher.notes.back().decision.empty());
  EXPECT_GT(v.forced + v.verified, 0);

  const std::string dir = ::testing::TempDir() + "/visual_thread_out";
  std::string error;
  ASSERT_TRUE(engine.WriteOutputs(dir, &error)) << error;
  std::ifstream loops(dir + "/loops.tsv");
  std::string header;
  ASSERT_TRUE(std::getline(loops, header));
  EXPECT_EQ(header, io::kLoopsTsvHeader);
  int lines = 0;
  for (std::string line; std::getline(loops, line);) ++lines;
  EXPECT_GT(lines, 0);
}

// Decoding a frame's images is the costly part of the RGB-D thread's work; with only the
// checker to feed, a frame it would skip (closer than selector.min_interval_s to the last one
// it took) is not decoded. Shown by frames whose depth PNG cannot be decoded: not counted
// malformed where the checker would skip them anyway.
TEST(VisualThreadTest, FramesTheCheckerSkipsAreNotDecoded) {
  RateLimitedLog quiet(1e9, [] { return 0.0; }, [](const std::string&) {});
  io::SlamConfig config = VisualConfig();
  config.visual_loop.checker.selector.min_interval_s = 1e6;  // one frame, then none
  LoopRecorder publisher;
  Engine engine(config, DaemonOptions(), 1, OverflowPolicy::kBlock, &publisher, &quiet);
  engine.Start();
  const test_world::TexturedBoxCamera camera(2.0, 0.0, 10.0, 8.0, 7);
  // The drive's first scans, each followed by a frame; from the 10th on, each frame has its
  // depth PNG's compressed data broken (its header, which the intake reads, is intact).
  constexpr int kScans = 40, kDecodable = 10;
  int scan = -1;
  for (const auto& message : test_world::RoomDriveMessages(kStepM, kStartS, 42)) {
    if (message.channel == "LIDAR" && ++scan == kScans) break;
    engine.intake().OnMessage(message.channel, message.data.data(),
                              static_cast<int>(message.data.size()));
    if (message.channel != "LIDAR") continue;
    std::vector<uint8_t> bytes;
    std::string error;
    ASSERT_TRUE(
        io::EncodeRgbdFrame(camera.Render(message.stamp_s, test_world::ArcPose(scan, kStepM)),
                            io::RgbdEncodeOptions(), &bytes, &error))
        << error;
    if (scan >= kDecodable) {
      const std::string idat = "IDAT";
      const auto at = std::search(bytes.begin(), bytes.end(), idat.begin(), idat.end());
      ASSERT_LT(at + 8, bytes.end());
      std::fill(at + 4, at + 8, 0xFF);
    }
    engine.intake().OnMessage("RGBD", bytes.data(), static_cast<int>(bytes.size()));
  }
  engine.Finish();
  EXPECT_EQ(engine.intake().counters(kRgbdChannel).received, kScans);
  EXPECT_EQ(engine.intake().counters(kRgbdChannel).malformed, 0);
  EXPECT_EQ(publisher.last_health.visual.keyframes, 1);
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
