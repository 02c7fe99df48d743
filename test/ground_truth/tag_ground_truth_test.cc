#include "fusemap/ground_truth/tag_ground_truth.h"

#include <gtest/gtest.h>

#include "tag_render.h"

namespace fusemap {
namespace ground_truth {
namespace {

using common::Rigid3d;

// A downward-looking camera 0.7 m above the floor, 0.1 m ahead of the base: optical x is the
// robot's right (-y), optical y its back (-x), optical z down.
Rigid3d DownCamera() {
  Eigen::Matrix3d R;
  R << 0, -1, 0, -1, 0, 0, 0, 0, -1;
  return Rigid3d(Eigen::Vector3d(0.1, 0.0, 0.7), Eigen::Quaterniond(R));
}

TEST(TagGroundTruthTest, RobotPoseFromFloorTagsAndUnknownTagsCounted) {
  const sensor::PinholeIntrinsics k{640, 480, 500.0, 500.0, 319.5, 239.5};
  TagMap tag_map;
  tag_map[3] = {3, 0.16, Rigid3d(Eigen::Vector3d(1.8, 0.6, 0.0), Eigen::Quaterniond::Identity())};
  tag_map[4] = {4, 0.16,
                Rigid3d(Eigen::Vector3d(1.8, 1.2, 0.0),
                        Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())))};
  std::string error;
  auto detector = TagDetector::Create(TagDetectorOptions(), &error);
  ASSERT_NE(detector, nullptr) << error;
  TagGroundTruth builder(TagGroundTruthOptions(), tag_map, std::move(detector));

  const Rigid3d T_map_base = Rigid3d::FromRigid2d(common::Rigid2d(1.75, 0.85, 0.4));
  const Rigid3d T_camera_map = (T_map_base * DownCamera()).inverse();
  const Rigid3d T_map_unknown(Eigen::Vector3d(1.95, 0.9, 0.0), Eigen::Quaterniond::Identity());
  const GreyImage image = testing::RenderTags(k, {{3, 0.16, T_camera_map * tag_map[3].T_map_tag},
                                                  {4, 0.16, T_camera_map * tag_map[4].T_map_tag},
                                                  {11, 0.16, T_camera_map * T_map_unknown}});
  EXPECT_EQ(builder.AddImage(5.0, image, k, DownCamera()), FrameOutcome::kPose);
  ASSERT_EQ(builder.trajectory().size(), 1u);
  const Rigid3d& estimate = builder.trajectory()[0].pose;
  EXPECT_LT((estimate.translation() - T_map_base.translation()).norm(), 0.005)
      << estimate.DebugString();
  EXPECT_NEAR(estimate.ToRigid2d().angle_rad(), 0.4, 0.005);
  ASSERT_EQ(builder.sightings().size(), 2u);
  for (const TagSighting& s : builder.sightings()) {
    EXPECT_LT((s.T_map_base.translation() - T_map_base.translation()).norm(), 0.01) << s.tag_id;
  }
  EXPECT_EQ(builder.unknown_tag_counts().at(11), 1);

  // A frame with only the unknown tag gives no pose; an empty one neither.
  const GreyImage only_unknown = testing::RenderTags(k, {{11, 0.16, T_camera_map * T_map_unknown}});
  EXPECT_EQ(builder.AddImage(5.1, only_unknown, k, DownCamera()), FrameOutcome::kOnlyUnknownTags);
  EXPECT_EQ(builder.AddImage(5.2, testing::RenderTags(k, {}), k, DownCamera()),
            FrameOutcome::kNoTag);
  EXPECT_EQ(builder.trajectory().size(), 1u);
  EXPECT_EQ(builder.unknown_tag_counts().at(11), 2);
}

TEST(TagGroundTruthTest, ParsesExtrinsicOverride) {
  std::string error;
  auto reader = common::ConfigReader::FromString(
      "default_tag_size_m: 0.2\n"
      "detector: {family: tag25h9}\n"
      "T_base_camera: {translation_m: [0.1, 0, 0.5], rotation_wxyz: [0, 1, 0, 0]}\n",
      "test", &error);
  ASSERT_NE(reader, nullptr) << error;
  const TagGroundTruthOptions options = ParseTagGroundTruthOptions(*reader);
  ASSERT_TRUE(reader->Finish(&error)) << error;
  EXPECT_TRUE(options.override_T_base_camera);
  EXPECT_DOUBLE_EQ(options.default_tag_size_m, 0.2);
  EXPECT_EQ(options.detector.family, "tag25h9");
  EXPECT_LT(
      (options.T_base_camera * Eigen::Vector3d::UnitZ() - Eigen::Vector3d(0.1, 0, -0.5)).norm(),
      1e-12);

  auto bad =
      common::ConfigReader::FromString("T_base_camera: {rotation_wxyz: [1, 0]}\n", "bad", &error);
  ASSERT_NE(bad, nullptr);
  ParseTagGroundTruthOptions(*bad);
  EXPECT_FALSE(bad->Finish(&error));
  EXPECT_NE(error.find("rotation_wxyz"), std::string::npos) << error;
}

// Issue 16: the tool's config (config/tagscore.yaml's ground_truth:) names each bad key path.
TEST(TagGroundTruthTest, BadValuesNameTheirKeyPathAndLine) {
  std::string error;
  auto reader = common::ConfigReader::FromString(
      "detector:\n  nthreads: 0\nmin_decision_margin: -1\n", "gt.yaml", &error);
  ASSERT_NE(reader, nullptr) << error;
  ParseTagGroundTruthOptions(*reader);
  EXPECT_FALSE(reader->Finish(&error));
  EXPECT_EQ(error,
            "gt.yaml:2: key 'detector.nthreads': must be >= 1\n"
            "gt.yaml:3: key 'min_decision_margin': must be >= 0");
  TagGroundTruthOptions options;
  options.detector.family = "tag99h1";
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_EQ(error.rfind("detector.family '", 0), 0u) << error;
}

}  // namespace
}  // namespace ground_truth
}  // namespace fusemap
