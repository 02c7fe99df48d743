#include "fusemap/daemon/cloud_worker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "testing/wall_frame.h"

namespace fusemap {
namespace daemon {
namespace {

constexpr double kWallDepthM = test_world::kWallFrameDepthM;
using test_world::WallFrame;

cloud::CloudMapperOptions TestOptions() {
  cloud::CloudMapperOptions options;
  options.frame.outlier_mean_k = 0;
  options.binder.remove_dynamic = false;
  return options;
}

class RecordingPublisher : public CloudRegionPublisher {
 public:
  void PublishCloudRegion(const CloudRegionUpdate& update) override { updates.push_back(update); }
  std::vector<CloudRegionUpdate> updates;
};

session::CloudPoseUpdate Pose(double stamp_s, double x, int submap_id,
                              const common::Rigid2d& T_local_submap) {
  session::CloudPoseUpdate message;
  message.stamp_s = stamp_s;
  message.submap_id = submap_id;
  message.T_local_tracking = common::Rigid2d(x, 0.0, 0.0);
  message.T_local_submap = T_local_submap;
  return message;
}

TEST(CloudWorkerTest, PublishesChangedRegionInSubmapFrameAndAgainWhenMoved) {
  RecordingPublisher publisher;
  session::CloudStage stage(TestOptions(), /*record_cost=*/false);
  CloudWorker worker(&stage, &publisher);
  const common::Rigid2d T_local_submap(1.0, 0.0, 0.0);
  session::CloudPoseUpdate first = Pose(0.0, 1.0, 0, T_local_submap);
  first.placements = {{0, T_local_submap}};
  worker.AddPoseUpdate(first);
  worker.AddFrame(WallFrame(0.1));
  worker.AddPoseUpdate(Pose(0.2, 1.0, 0, T_local_submap));
  ASSERT_EQ(worker.mapper().stats().frames_bound, 1);
  const auto t0 = std::chrono::steady_clock::now();
  worker.MaybePublish(t0);
  ASSERT_EQ(publisher.updates.size(), 1u);
  const CloudRegionUpdate& update = publisher.updates[0];
  EXPECT_EQ(update.submap_id, 0);
  ASSERT_GT(update.points_submap->size(), 100u);
  EXPECT_EQ(update.total_points, update.points_submap->size());
  // Base at the submap origin: the wall is kWallDepthM ahead in the submap frame.
  EXPECT_NEAR(update.points_submap->at(0).x, kWallDepthM, 0.03);
  EXPECT_NEAR(update.T_map_submap.translation().x(), 1.0, 1e-12);
  // Nothing changed: nothing more is published; a move is, but only after the period.
  worker.MaybePublish(t0 + CloudWorker::kPublishPeriod);
  EXPECT_EQ(publisher.updates.size(), 1u);
  session::CloudPoseUpdate moved;
  moved.placements = {{0, common::Rigid2d(0.0, 4.0, M_PI / 2.0)}};
  worker.AddPoseUpdate(moved);
  worker.MaybePublish(t0 + CloudWorker::kPublishPeriod + std::chrono::milliseconds(1));
  EXPECT_EQ(publisher.updates.size(), 1u);
  worker.MaybePublish(t0 + 2 * CloudWorker::kPublishPeriod + std::chrono::milliseconds(1));
  ASSERT_EQ(publisher.updates.size(), 2u);
  EXPECT_NEAR(publisher.updates[1].T_map_submap.translation().y(), 4.0, 1e-12);
  EXPECT_NEAR(publisher.updates[1].points_submap->at(0).x, kWallDepthM, 0.03);
}

TEST(CloudWorkerTest, DecimatesLargeRegions) {
  cloud::ColorCloud points;
  for (int i = 0; i < 1001; ++i) points.push_back(cloud::ColorPoint(uint8_t{1}, uint8_t{2}, uint8_t{3}));
  const CloudRegionUpdate update =
      MakeCloudRegionUpdate(1.0, 3, common::Rigid3d(), points, 100);
  EXPECT_EQ(update.total_points, 1001u);
  EXPECT_LE(update.points_submap->size(), 100u);
  EXPECT_GE(update.points_submap->size(), 90u);
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
