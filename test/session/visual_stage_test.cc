#include "fusemap/session/visual_stage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "fusemap/common/math.h"
#include "fusemap/pose_graph/pose_graph_2d.h"
#include "fusemap/sensor/range_data_builder.h"
#include "fusemap/sensor/voxel_filter.h"
#include "testing/drifting_arc_drive.h"
#include "testing/synthetic_room.h"
#include "testing/textured_box_camera.h"

namespace fusemap {
namespace session {
namespace {

using visual_loop::LoopDecision;

constexpr double kStepM = 0.15;
const int kLoopNodes =
    static_cast<int>(1.1 * 2.0 * common::kPi * test_world::kArcRadiusM / kStepM);

common::Rigid2d TruePose(int i) { return test_world::ArcPose(i, kStepM); }

io::VisualLoopConfig StageConfig() {
  io::VisualLoopConfig config;
  config.enabled = true;
  std::string error;
  EXPECT_TRUE(io::LoadVisualLoopVocabulary(&config, &error)) << error;
  // A one-lap test drive has few keyframes: fewer excluded as recent, and a revisit is
  // accepted after one consistent query.
  config.checker.detector.recognition.num_recent_excluded = 10;
  config.checker.detector.recognition.temporal_consistency = 1;
  return config;
}

pose_graph::PoseGraphOptions2D GraphOptions() {
  pose_graph::PoseGraphOptions2D options;
  options.optimize_every_n_nodes = 10;
  // No laser search: the laser loops of these tests are given (AddLoopConstraint, kLaser).
  options.constraint_builder.max_constraint_distance_m = 1e-6;
  return options;
}

// A lap and a bit around the synthetic room's island with local SLAM's drift of
// pose_graph_2d_test (1 % too much translation, 0.1 deg too much yaw a step); a camera in a
// textured box around the arc takes a frame at every scan, at the true pose.
class VisualRun {
 public:
  explicit VisualRun(io::VisualLoopConfig config = StageConfig())
      : graph_(GraphOptions(), &executor_),
        camera_(2.0, 0.0, 10.0, 8.0, /*seed=*/7),
        stage_(std::make_unique<VisualStage>(config, CameraOptions(), &graph_)) {}

  // A new stage on the same graph, continuing from `state` (a restart).
  void RestartStage(io::VisualKeyframesState state) {
    stage_ = std::make_unique<VisualStage>(StageConfig(), CameraOptions(), &graph_);
    stage_->RestoreState(std::move(state));
  }

  static cloud::CloudMapperOptions CameraOptions() {
    cloud::CloudMapperOptions options;
    return options;
  }

  // Nodes up to num_nodes - 1 (continuing); with a camera, a frame after each scan.
  void Drive(int num_nodes, bool with_camera = true) {
    while (drive_.next_index() < num_nodes) {
      const test_world::DriftingArcDrive::Step step = drive_.Next();
      const double stamp_s = 0.1 * step.index;
      const int node =
          graph_.AddNode(stamp_s, step.T_local_node, step.filtered_cloud, step.insertion_submaps);
      CloudPoseUpdate update;
      update.stamp_s = stamp_s;
      update.T_local_tracking = step.T_local_node;
      update.submap_id = graph_.SubmapIndex(step.insertion_submaps.front().get());
      update.T_local_submap = step.insertion_submaps.front()->T_local_submap();
      update.node_id = node;
      stage_->Apply(update);
      if (with_camera) stage_->AddFrame(camera_.Render(stamp_s, step.T_true));
    }
  }

  // The true pose of `node` in submap 0 (local SLAM barely drifted while it was built).
  common::Rigid2d TrueSubmap0Node(int node) const { return drive_.TrueInFirstSubmap(node); }
  // A laser loop as the search would have found it; held across a corridor only when
  // unmeasured_direction is not zero.
  int AddLaserLoop(int node, int submap, const common::Rigid2d& T_submap_node,
                   const Eigen::Vector2d& unmeasured_direction = Eigen::Vector2d::Zero()) {
    pose_graph::ExternalLoopConstraint2D c;
    c.unmeasured_direction = unmeasured_direction;
    c.node = node;
    c.submap = submap;
    c.T_submap_node = T_submap_node;
    c.translation_weight = 1.1e4;
    c.rotation_weight = 1e5;
    c.source = pose_graph::Constraint2D::kLaser;
    c.laser_score = 0.7;
    return graph_.AddLoopConstraint(c);
  }
  const visual_loop::ArbitrationRecord* RecordOf(int node) const {
    const visual_loop::ArbitrationRecord* found = nullptr;
    for (const auto& r : stage_->records()) {
      if (r.node == node && r.laser) found = &r;
    }
    return found;
  }
  std::optional<pose_graph::Constraint2D> LoopOf(int node, int submap) const {
    for (const auto& c : graph_.LoopConstraints()) {
      if (c.node == node && c.submap == submap) return c;
    }
    return std::nullopt;
  }
  std::optional<pose_graph::Constraint2D> LoopById(int id) const {
    for (const auto& c : graph_.LoopConstraints()) {
      if (c.loop_id == id) return c;
    }
    return std::nullopt;
  }

  pose_graph::PoseGraph2D& graph() { return graph_; }
  VisualStage& stage() { return *stage_; }

 private:
  common::InlineExecutor executor_;
  pose_graph::PoseGraph2D graph_;
  test_world::TexturedBoxCamera camera_;
  std::unique_ptr<VisualStage> stage_;
  test_world::DriftingArcDrive drive_{kStepM};
};

double DistanceM(const common::Rigid2d& a, const common::Rigid2d& b) {
  return (a.translation() - b.translation()).norm();
}

TEST(VisualStageTest, ToCameraFrameDecodesGreyDepthIntrinsicsAndMount) {
  const test_world::TexturedBoxCamera camera(2.0, 0.0, 10.0, 8.0, 7);
  const sensor::RgbdFrame frame = camera.Render(1.5, TruePose(0));
  cloud::CloudMapperOptions options;
  const visual_loop::CameraFrame out = ToCameraFrame(frame, options, visual_loop::KeyframeOptions());
  ASSERT_EQ(out.image.type(), CV_8UC1);
  ASSERT_EQ(out.depth_m.type(), CV_32FC1);
  EXPECT_EQ(out.image.cols, 640);
  EXPECT_EQ(out.stamp_s, 1.5);
  EXPECT_EQ(out.image.at<uint8_t>(240, 320), frame.color_rgb[3 * (240 * 640 + 320)]);
  EXPECT_NEAR(out.depth_m.at<float>(240, 320), 1e-3 * frame.depth_mm[240 * 640 + 320], 1e-6);
  EXPECT_EQ(out.intrinsics.fx, 500.0);
  EXPECT_TRUE(out.T_base_camera.translation().isApprox(frame.T_base_color.translation()));
  // The cloud's configured mount wins over the frame's, as in the cloud stage.
  options.override_extrinsic = true;
  options.T_base_camera_xyz_m = {0.1, 0.0, 0.3};
  EXPECT_NEAR(ToCameraFrame(frame, options, visual_loop::KeyframeOptions())
                  .T_base_camera.translation()
                  .z(),
              0.3, 1e-12);
  EXPECT_TRUE(ToCameraFrame(sensor::RgbdFrame(), options, visual_loop::KeyframeOptions())
                  .image.empty());
}

// One drive covers the four paths: revisits found by appearance alone are forced; laser loops
// given afterwards are confirmed, overridden or rejected by the camera.
TEST(VisualStageTest, ForcedConfirmedOverriddenAndRejectedThroughThePoseGraph) {
  VisualRun run;
  run.Drive(kLoopNodes);
  const VisualStageStats during = run.stage().stats();
  std::printf("%s\n", VisualSummaryLine(during).c_str());
  EXPECT_GT(during.checker.keyframes, 20);
  EXPECT_GT(during.forced, 0);
  for (const auto& r : run.stage().records()) {
    EXPECT_EQ(r.decision, LoopDecision::kVisualForced);
    EXPECT_EQ(r.submap, 0);
    const auto loop = run.LoopOf(r.node, r.submap);
    ASSERT_TRUE(loop) << "node " << r.node;
    EXPECT_EQ(loop->source, pose_graph::Constraint2D::kVisual);
    // The forced measurement is near the truth, not at the graph's estimate (still well off);
    // what is left is the drift of the matched keyframe within submap 0, which the measurement
    // is anchored to.
    const common::Rigid2d T_submap_node_estimate = *run.graph().T_submap_node(0, r.node);
    EXPECT_GT(DistanceM(T_submap_node_estimate, run.TrueSubmap0Node(r.node)), 0.15) << r.node;
    EXPECT_LT(DistanceM(loop->T_submap_node, run.TrueSubmap0Node(r.node)), 0.12) << r.node;
  }

  const int last = kLoopNodes - 1;
  // Right: confirmed. Turned 0.2 rad: overridden by the camera's measurement. A place on the
  // far side of the lap (node 57, submap 4): the camera sees other walls there, so it is
  // rejected.
  const int confirmed = run.AddLaserLoop(last, 0, run.TrueSubmap0Node(last));
  const common::Rigid2d off = run.TrueSubmap0Node(last - 2) * common::Rigid2d({0.0, 0.0}, 0.2);
  const int overridden = run.AddLaserLoop(last - 2, 0, off);
  const int rejected = run.AddLaserLoop(last - 4, 4, *run.graph().T_submap_node(4, 57));
  ASSERT_GE(confirmed, 0);
  ASSERT_GE(overridden, 0);
  ASSERT_GE(rejected, 0);
  run.stage().Finish();
  const VisualStageStats after = run.stage().stats();
  std::printf("%s\n", VisualSummaryLine(after).c_str());
  EXPECT_EQ(after.laser_loops_checked, 3);

  const auto* r = run.RecordOf(last);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->decision, LoopDecision::kLaserConfirmed) << r->reason;
  EXPECT_EQ(run.LoopById(confirmed)->source, pose_graph::Constraint2D::kBoth);

  r = run.RecordOf(last - 2);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->decision, LoopDecision::kVisualOverride) << r->reason;
  const auto replaced = run.LoopById(overridden);
  ASSERT_TRUE(replaced);
  EXPECT_EQ(replaced->source, pose_graph::Constraint2D::kVisual);
  EXPECT_LT(DistanceM(replaced->T_submap_node, run.TrueSubmap0Node(last - 2)), 0.12);
  EXPECT_LT(std::abs(common::NormalizeAngle(
                replaced->T_submap_node.angle_rad() - run.TrueSubmap0Node(last - 2).angle_rad())),
            0.1);  // the laser one was 0.2 rad off

  r = run.RecordOf(last - 4);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->decision, LoopDecision::kLaserRejected) << r->reason;
  EXPECT_FALSE(run.LoopById(rejected));
  EXPECT_EQ(after.confirmed, 1);
  EXPECT_EQ(after.overridden, 1);
  EXPECT_EQ(after.rejected, 1);
}

// A laser loop held across a corridor only keeps the graph's estimate along it; once the camera
// confirms it, its measurement of the same place joins the graph and says where along it is.
TEST(VisualStageTest, AConfirmedLoopHeldAcrossOnlyGetsTheCamerasMeasurementAlongIt) {
  VisualRun run;
  run.Drive(kLoopNodes);
  const int last = kLoopNodes - 1;
  // Visual loops the drive forced by appearance alone.
  std::set<int> forced_before;
  for (const auto& c : run.graph().LoopConstraints()) forced_before.insert(c.loop_id);
  // 0.2 m off along the node's x axis, which the laser did not measure.
  const common::Rigid2d slid = run.TrueSubmap0Node(last) * common::Rigid2d({0.2, 0.0}, 0.0);
  const int held = run.AddLaserLoop(last, 0, slid, Eigen::Vector2d::UnitX());
  const int full = run.AddLaserLoop(last - 2, 0, run.TrueSubmap0Node(last - 2));
  ASSERT_GE(held, 0);
  ASSERT_GE(full, 0);
  run.stage().Finish();
  const VisualStageStats stats = run.stage().stats();
  std::printf("%s\n", VisualSummaryLine(stats).c_str());
  ASSERT_NE(run.RecordOf(last), nullptr);
  ASSERT_NE(run.RecordOf(last - 2), nullptr);
  EXPECT_EQ(run.RecordOf(last)->decision, LoopDecision::kLaserConfirmed)
      << run.RecordOf(last)->reason;
  EXPECT_EQ(run.RecordOf(last - 2)->decision, LoopDecision::kLaserConfirmed);
  EXPECT_EQ(stats.confirmed_along, 1);  // the one measured every way needs nothing more
  std::vector<pose_graph::Constraint2D> added;
  for (const auto& c : run.graph().LoopConstraints()) {
    if (c.node == last && c.submap == 0 && forced_before.count(c.loop_id) == 0) added.push_back(c);
  }
  ASSERT_EQ(added.size(), 2u);
  for (const pose_graph::Constraint2D& c : added) {
    if (c.loop_id == held) {
      EXPECT_EQ(c.source, pose_graph::Constraint2D::kBoth);
      EXPECT_EQ(c.unmeasured_direction, Eigen::Vector2d::UnitX());
    } else {
      EXPECT_EQ(c.source, pose_graph::Constraint2D::kVisual);
      EXPECT_TRUE(c.unmeasured_direction.isZero());
      EXPECT_LT(DistanceM(c.T_submap_node, run.TrueSubmap0Node(last)), 0.12);
    }
  }
}

// Each keyframe's motion from the one before, as the camera measured it, joins the graph.
TEST(VisualStageTest, MotionLinksMeasureTheTrueMotionBetweenKeyframes) {
  VisualRun run;
  run.Drive(40);
  const VisualStageStats stats = run.stage().stats();
  const std::vector<pose_graph::NodeLink2D> links = run.graph().NodeLinks();
  EXPECT_GE(stats.motion_links, stats.checker.keyframes - 3);
  EXPECT_EQ(static_cast<int>(links.size()), stats.motion_links);
  int previous_to = 0;
  std::vector<double> errors_m;
  for (const pose_graph::NodeLink2D& link : links) {
    // Between consecutive keyframes: each link starts at or after the end of the one before.
    EXPECT_GE(link.from, previous_to);
    EXPECT_LT(link.from, link.to);
    previous_to = link.to;
    // The camera sees the true motion (local SLAM's is 1 % long and 0.1 deg a step off).
    const common::Rigid2d truth = TruePose(link.from).inverse() * TruePose(link.to);
    errors_m.push_back(DistanceM(link.T_from_to, truth));
    EXPECT_LT(errors_m.back(), 0.03) << link.from << " -> " << link.to;
    EXPECT_LT(std::abs(common::NormalizeAngle(link.T_from_to.angle_rad() - truth.angle_rad())),
              common::DegToRad(1.0));
    EXPECT_GT(link.translation_weight, 0.0);
  }
  ASSERT_FALSE(errors_m.empty());
  std::sort(errors_m.begin(), errors_m.end());
  EXPECT_LT(errors_m[errors_m.size() / 2], 0.006);

  io::VisualLoopConfig off = StageConfig();
  off.motion_links.enabled = false;
  VisualRun without(off);
  without.Drive(40);
  EXPECT_EQ(without.stage().stats().motion_links, 0);
  EXPECT_TRUE(without.graph().NodeLinks().empty());
}

// fusemapd holds each piece of the checker's work until the gap after a scan: the pacer is
// asked before every keyframe's processing and every motion link's verification, and holding
// the work there changes nothing of its result.
TEST(VisualStageTest, ThePacerIsAskedBeforeEachPieceOfWork) {
  VisualRun paced;
  int paces = 0;
  paced.stage().SetPacer([&paces] { ++paces; });
  paced.Drive(40);
  const VisualStageStats stats = paced.stage().stats();
  ASSERT_GT(stats.motion_links, 0);
  EXPECT_EQ(paces, stats.frames_offered + stats.motion_links + stats.motion_links_refused);

  VisualRun unpaced;
  unpaced.Drive(40);
  EXPECT_EQ(unpaced.stage().stats().checker.keyframes, stats.checker.keyframes);
  EXPECT_EQ(unpaced.graph().NodeLinks().size(), paced.graph().NodeLinks().size());
}

// A restart between the laps: the keyframes of the first lap, through the checkpoint file's
// encoding, still close the loop.
TEST(VisualStageTest, RestoredKeyframesStillCloseTheLoop) {
  VisualRun run;
  run.Drive(kLoopNodes - 12);
  const io::VisualKeyframesState saved = run.stage().ExportState();
  ASSERT_GT(saved.keyframes.size(), 20u);
  io::VisualKeyframesState read;
  std::string error;
  ASSERT_TRUE(io::DecodeVisualKeyframes(io::EncodeVisualKeyframes(saved), "kf", &read, &error))
      << error;
  run.RestartStage(std::move(read));
  EXPECT_EQ(run.stage().stats().checker.keyframes, static_cast<int>(saved.keyframes.size()));
  run.Drive(kLoopNodes);
  std::printf("%s\n", VisualSummaryLine(run.stage().stats()).c_str());
  // The new stage's own counts: its loops matched keyframes it only has from the file.
  EXPECT_GT(run.stage().stats().forced, 0);
  for (const auto& r : run.stage().records()) {
    EXPECT_EQ(r.submap, 0);
    EXPECT_LT(DistanceM(r.chosen->T_submap_node, run.TrueSubmap0Node(r.node)), 0.12) << r.node;
  }
}

// Keyframes are bound to the older of the two active submaps, so the start of submap 1 (node
// 10 on: its first ten nodes also go into submap 0) was seen by keyframes bound to submap 0
// only. A laser loop into that part of submap 1 is still checked by the camera.
TEST(VisualStageTest, LaserLoopIntoTheStartOfASubmapIsChecked) {
  VisualRun run;
  const int lap_nodes =
      static_cast<int>(std::round(2.0 * common::kPi * test_world::kArcRadiusM / kStepM));
  const int first = 10;
  const int node = first + lap_nodes;
  run.Drive(node + 1);
  // Where local SLAM put `first` in submap 1 (exact within a submap) and the true motion from
  // `first` to `node`, a lap later at the same place.
  const common::Rigid2d T_submap_first = *run.graph().T_submap_node(1, first);
  const common::Rigid2d T_first_node = TruePose(first).inverse() * TruePose(node);
  const int id = run.AddLaserLoop(node, 1, T_submap_first * T_first_node);
  ASSERT_GE(id, 0);
  run.stage().Finish();
  const auto* r = run.RecordOf(node);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->decision, LoopDecision::kLaserConfirmed) << r->reason;
  EXPECT_EQ(run.LoopById(id)->source, pose_graph::Constraint2D::kBoth);
}

TEST(VisualStageTest, LaserLoopWhereTheCameraSawNothingIsKept) {
  VisualRun run;
  run.Drive(30, /*with_camera=*/false);
  const int id = run.AddLaserLoop(29, 0, common::Rigid2d({0.2, 0.0}, 0.0));
  ASSERT_GE(id, 0);
  run.stage().Finish();
  ASSERT_EQ(run.stage().records().size(), 1u);
  EXPECT_EQ(run.stage().records()[0].decision, LoopDecision::kLaserKept);
  EXPECT_EQ(run.LoopById(id)->source, pose_graph::Constraint2D::kLaser);
  EXPECT_EQ(run.stage().stats().kept, 1);
}

TEST(VisualStageTest, LaserLoopsWaitForTheFramesOfTheirPlace) {
  VisualRun run;
  run.Drive(25);
  // Node 24's loop is taken, but its place's frames are still to come (24 is the newest).
  ASSERT_GE(run.AddLaserLoop(24, 0, run.TrueSubmap0Node(24) * common::Rigid2d({0.1, 0.0}, 0.0)),
            0);
  run.Drive(0);  // nothing new
  EXPECT_TRUE(run.stage().records().empty());
  run.stage().Finish();
  EXPECT_EQ(run.stage().records().size(), 1u);
}

}  // namespace
}  // namespace session
}  // namespace fusemap
