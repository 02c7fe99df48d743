#include "fusemap/ground_truth/tag_pose.h"

#include <gtest/gtest.h>

#include "tag_render.h"

namespace fusemap {
namespace ground_truth {
namespace {

using common::Rigid3d;

sensor::PinholeIntrinsics Camera() {
  sensor::PinholeIntrinsics k;
  k.width = 640;
  k.height = 480;
  k.fx = 520.0;
  k.fy = 515.0;
  k.cx = 318.7;
  k.cy = 242.3;
  return k;
}

// Camera 0.9 m from the tag, looking at it obliquely (tag tilted 25 deg about x, 15 about y).
Rigid3d TiltedTagPose() {
  const Eigen::Quaterniond q = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(M_PI + 0.44, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(0.26, Eigen::Vector3d::UnitY());
  return Rigid3d(Eigen::Vector3d(0.05, -0.03, 0.9), q);
}

double AngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.angularDistance(b) * 180.0 / M_PI;
}

std::unique_ptr<TagDetector> MakeDetector() {
  std::string error;
  auto detector = TagDetector::Create(TagDetectorOptions(), &error);
  EXPECT_NE(detector, nullptr) << error;
  return detector;
}

// Checks the documented corner order and pixel convention together: every detected corner lies
// where ProjectToPixel puts the matching TagCornersInTagFrame point.
TEST(TagPoseTest, CornersMatchProjectionOfTagFrameCorners) {
  const Rigid3d T_camera_tag = TiltedTagPose();
  const GreyImage image = testing::RenderTags(Camera(), {{7, 0.16, T_camera_tag}});
  const auto detections = MakeDetector()->Detect(image);
  ASSERT_EQ(detections.size(), 1u);
  EXPECT_EQ(detections[0].id, 7);
  const auto corners = TagCornersInTagFrame(0.16);
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d expected = ProjectToPixel(T_camera_tag.inverse(), Camera(), corners[k]);
    EXPECT_LT((detections[0].corners_px[k] - expected).norm(), 0.15)
        << "corner " << k << " detected " << detections[0].corners_px[k].transpose() << " expected "
        << expected.transpose();
  }
}

TEST(TagPoseTest, SingleTagPoseIsRecovered) {
  const Rigid3d T_camera_tag = TiltedTagPose();
  const GreyImage image = testing::RenderTags(Camera(), {{3, 0.16, T_camera_tag}});
  const auto detections = MakeDetector()->Detect(image);
  ASSERT_EQ(detections.size(), 1u);
  Rigid3d estimate;
  ASSERT_TRUE(EstimateTagPose(detections[0], Camera(), 0.16, &estimate));
  EXPECT_LT((estimate.translation() - T_camera_tag.translation()).norm(), 0.003)
      << estimate.DebugString() << " vs " << T_camera_tag.DebugString();
  EXPECT_LT(AngleDeg(estimate.rotation(), T_camera_tag.rotation()), 0.5);
}

// Two floor tags 0.6 m apart seen by a camera looking down and forward; one unknown tag.
TEST(TagPoseTest, MultiTagCameraPoseInMap) {
  TagMap tag_map;
  tag_map[1] = {1, 0.15,
                Rigid3d(Eigen::Vector3d(2.0, 1.0, 0.0),
                        Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())))};
  tag_map[2] = {2, 0.15, Rigid3d(Eigen::Vector3d(2.6, 1.0, 0.0), Eigen::Quaterniond::Identity())};
  // Camera 0.8 m above the floor at (1.6, 1.15), looking along +x and pitched 50 deg down:
  // base axes (x forward, z up) -> optical axes (z forward, x right, y down), then the pitch.
  const Eigen::Matrix3d R_base_optical =
      (Eigen::Matrix3d() << 0, 0, 1, -1, 0, 0, 0, -1, 0).finished();
  const Eigen::Quaterniond pitch(Eigen::AngleAxisd(50.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()));
  const Rigid3d T_map_camera(Eigen::Vector3d(1.6, 1.15, 0.8),
                             pitch * Eigen::Quaterniond(R_base_optical));
  const Rigid3d T_camera_map = T_map_camera.inverse();
  const Rigid3d T_camera_unknown =
      T_camera_map * Rigid3d(Eigen::Vector3d(2.3, 0.6, 0.0), Eigen::Quaterniond::Identity());
  const GreyImage image =
      testing::RenderTags(Camera(), {{1, 0.15, T_camera_map * tag_map[1].T_map_tag},
                                     {2, 0.15, T_camera_map * tag_map[2].T_map_tag},
                                     {9, 0.15, T_camera_unknown}});
  const auto detections = MakeDetector()->Detect(image);
  ASSERT_EQ(detections.size(), 3u);
  CameraPoseEstimate estimate;
  ASSERT_TRUE(EstimateCameraPose(detections, tag_map, Camera(), &estimate));
  EXPECT_EQ(estimate.used_ids, (std::vector<int>{1, 2}));
  EXPECT_EQ(estimate.unknown_ids, (std::vector<int>{9}));
  EXPECT_LT(estimate.rms_reprojection_px, 0.2);
  EXPECT_LT((estimate.T_map_camera.translation() - T_map_camera.translation()).norm(), 0.003)
      << estimate.T_map_camera.DebugString();
  EXPECT_LT(AngleDeg(estimate.T_map_camera.rotation(), T_map_camera.rotation()), 0.3);
}

TEST(TagPoseTest, NoKnownTagGivesNoPose) {
  TagDetection d;
  d.id = 4;
  CameraPoseEstimate estimate;
  EXPECT_FALSE(EstimateCameraPose({d}, TagMap(), Camera(), &estimate));
  EXPECT_EQ(estimate.unknown_ids, (std::vector<int>{4}));
}

}  // namespace
}  // namespace ground_truth
}  // namespace fusemap
