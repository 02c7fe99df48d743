#include "fusemap/cloud/cloud_mapper.h"

#include <gtest/gtest.h>

#include <cmath>

#include "testing/wall_frame.h"

namespace fusemap {
namespace cloud {
namespace {

constexpr double kWallDepthM = test_world::kWallFrameDepthM;
using test_world::WallFrame;

CloudMapperOptions TestOptions() {
  CloudMapperOptions options;
  options.frame.outlier_mean_k = 0;
  options.binder.remove_dynamic = false;
  return options;
}

Eigen::Vector3d Centroid(const ColorCloud& cloud) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : cloud) sum += Eigen::Vector3d(p.x, p.y, p.z);
  return sum / std::max<size_t>(1, cloud.size());
}

TEST(CloudMapperTest, FrameWaitsForLaterPoseAndUsesInterpolatedPose) {
  CloudMapper mapper(TestOptions());
  mapper.AddLocalPose(0.0, common::Rigid2d(0.0, 0.0, 0.0), 0, common::Rigid2d::Identity());
  mapper.AddFrame(WallFrame(0.2));
  EXPECT_EQ(mapper.pending_frames(), 1);  // No pose at or after 0.2 s yet.
  mapper.AddLocalPose(0.4, common::Rigid2d(0.4, 0.0, 0.0), 0, common::Rigid2d::Identity());
  EXPECT_EQ(mapper.pending_frames(), 0);
  EXPECT_EQ(mapper.stats().frames_bound, 1);
  const auto cloud = mapper.binder().GlobalCloud();
  ASSERT_GT(cloud->size(), 100u);
  // Interpolated base x = 0.2 (the nearest sample would give 0 or 0.4).
  EXPECT_NEAR(Centroid(*cloud).x(), 0.2 + kWallDepthM, 0.02);
  EXPECT_NEAR(Centroid(*cloud).y(), 0.0, 0.02);
}

TEST(CloudMapperTest, CloudFollowsItsSubmapWhenGlobalSlamMovesIt) {
  CloudMapper mapper(TestOptions());
  const common::Rigid2d T_local_submap(1.0, 0.0, 0.0);
  mapper.AddLocalPose(0.0, common::Rigid2d(1.0, 0.0, 0.0), 0, T_local_submap);
  mapper.AddFrame(WallFrame(0.1));
  mapper.AddLocalPose(0.2, common::Rigid2d(1.0, 0.0, 0.0), 0, T_local_submap);
  ASSERT_EQ(mapper.stats().frames_bound, 1);
  EXPECT_NEAR(Centroid(*mapper.binder().GlobalCloud()).x(), 1.0 + kWallDepthM, 0.02);
  // Global SLAM turns the submap by 90 degrees about the map origin and lifts it 3 m in y.
  mapper.PlaceSubmaps({{0, common::Rigid2d(0.0, 4.0, M_PI / 2.0)}});
  const Eigen::Vector3d c = Centroid(*mapper.binder().GlobalCloud());
  EXPECT_NEAR(c.x(), 0.0, 0.02);
  EXPECT_NEAR(c.y(), 4.0 + kWallDepthM, 0.02);
  EXPECT_EQ(mapper.binder().stats().last_update_regions, 1u);
}

TEST(CloudMapperTest, FramesBindToTheSubmapActiveWhenTaken) {
  CloudMapper mapper(TestOptions());
  mapper.AddLocalPose(0.0, common::Rigid2d::Identity(), 0, common::Rigid2d::Identity());
  mapper.AddFrame(WallFrame(0.2));
  mapper.AddLocalPose(0.4, common::Rigid2d::Identity(), 1, common::Rigid2d(5.0, 0.0, 0.0));
  mapper.AddFrame(WallFrame(0.6));
  mapper.AddLocalPose(0.8, common::Rigid2d::Identity(), 1, common::Rigid2d(5.0, 0.0, 0.0));
  ASSERT_EQ(mapper.stats().frames_bound, 2);
  EXPECT_GT(mapper.binder().RegionCloud(0)->size(), 100u);
  EXPECT_GT(mapper.binder().RegionCloud(1)->size(), 100u);
}

TEST(CloudMapperTest, FinishDropsFramesThatCanNeverGetAPose) {
  CloudMapper mapper(TestOptions());
  mapper.AddLocalPose(0.0, common::Rigid2d::Identity(), 0, common::Rigid2d::Identity());
  mapper.AddFrame(WallFrame(0.2));
  EXPECT_EQ(mapper.pending_frames(), 1);
  mapper.Finish();
  EXPECT_EQ(mapper.pending_frames(), 0);
  EXPECT_EQ(mapper.stats().frames_dropped_no_pose, 1);
  EXPECT_EQ(mapper.stats().frames_bound, 0);
}

TEST(CloudMapperTest, RateLimitAndQueueBoundAreCounted) {
  CloudMapperOptions options = TestOptions();
  options.min_frame_interval_s = 0.125;
  options.max_pending_frames = 2;
  CloudMapper mapper(options);
  mapper.AddLocalPose(0.0, common::Rigid2d::Identity(), 0, common::Rigid2d::Identity());
  for (int i = 1; i <= 8; ++i) mapper.AddFrame(WallFrame(0.05 * i));  // 0.05 .. 0.4 s
  // Accepted: 0.05, 0.2, 0.35 (0.125 s apart at least); the queue keeps the newest two.
  EXPECT_EQ(mapper.stats().frames_skipped_rate, 5);
  EXPECT_EQ(mapper.stats().frames_dropped_queue, 1);
  EXPECT_EQ(mapper.pending_frames(), 2);
  mapper.AddLocalPose(0.45, common::Rigid2d::Identity(), 0, common::Rigid2d::Identity());
  EXPECT_EQ(mapper.stats().frames_bound, 2);
  EXPECT_EQ(mapper.stats().frames_in, 8);
}

TEST(CloudMapperTest, RateSkippedFramesStillCarve) {
  CloudMapperOptions options = TestOptions();
  options.binder.remove_dynamic = true;  // projective carving (ray_carving defaults to false)
  options.min_frame_interval_s = 0.125;
  CloudMapper mapper(options);
  mapper.AddLocalPose(0.0, common::Rigid2d::Identity(), 0, common::Rigid2d::Identity());
  for (int i = 1; i <= 8; ++i) mapper.AddFrame(WallFrame(0.05 * i));
  mapper.AddLocalPose(0.45, common::Rigid2d::Identity(), 0, common::Rigid2d::Identity());
  // Three frames are bound (0.05, 0.2, 0.35 s) but all eight carve free space.
  EXPECT_EQ(mapper.stats().frames_bound, 3);
  EXPECT_EQ(mapper.stats().frames_carved, 8);
  EXPECT_EQ(mapper.binder().stats().carve_frames, 8);
  // A static wall seen by every frame is never carved away.
  EXPECT_EQ(mapper.binder().stats().points_removed_dynamic, 0);
  EXPECT_GT(mapper.binder().stats().points_stored, 0u);
}

TEST(CloudMapperTest, ConfiguredExtrinsicOverridesTheFramesOwn) {
  CloudMapperOptions options = TestOptions();
  options.override_extrinsic = true;
  options.T_base_camera_xyz_m = {0.0, 0.0, 1.0};
  options.T_base_camera_rpy_deg = {-90.0, 0.0, -90.0};  // Optical z along base x.
  CloudMapper mapper(options);
  mapper.AddLocalPose(0.0, common::Rigid2d::Identity(), 0, common::Rigid2d::Identity());
  sensor::RgbdFrame frame = WallFrame(0.1);
  frame.T_base_color = common::Rigid3d();  // Would look straight up if used.
  mapper.AddFrame(frame);
  mapper.AddLocalPose(0.2, common::Rigid2d::Identity(), 0, common::Rigid2d::Identity());
  const Eigen::Vector3d c = Centroid(*mapper.binder().GlobalCloud());
  EXPECT_NEAR(c.x(), kWallDepthM, 0.02);
  EXPECT_NEAR(c.z(), 1.0, 0.02);
}

TEST(CloudMapperTest, InvalidOptionsNameTheKey) {
  CloudMapperOptions options;
  std::string error;
  options.max_pending_frames = 0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("max_pending_frames"), std::string::npos);
  options = CloudMapperOptions();
  options.T_base_camera_xyz_m = {1.0};
  EXPECT_FALSE(options.IsValid(&error));
}

}  // namespace
}  // namespace cloud
}  // namespace fusemap
