// The loop checker on the real and rendered frames in ../shared/data/visual (see its README);
// every test skips with a message when the folder is absent.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "fusemap/visual_loop/geometric_verifier.h"
#include "fusemap/visual_loop/image_sequence.h"
#include "fusemap/visual_loop/keyframe.h"
#include "fusemap/visual_loop/loop_detector.h"
#include "fusemap/visual_loop/patch_alignment.h"
#include "visual_loop/synthetic_views.h"

namespace fusemap {
namespace visual_loop {
namespace {

const std::string kVisual = std::string(FUSEMAP_SHARED_DATA_DIR) + "/visual";

#define SKIP_WITHOUT(path)                                                         \
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << (path)

sensor::PinholeIntrinsics Intrinsics(double fx, double fy, double cx, double cy) {
  sensor::PinholeIntrinsics in;
  in.fx = fx;
  in.fy = fy;
  in.cx = cx;
  in.cy = cy;
  return in;
}

std::optional<Vocabulary> CommittedVocabulary() {
  std::string error;
  return Vocabulary::Load(std::string(FUSEMAP_SOURCE_DIR) + "/data/vocabulary/orb_k10_l4.bin", &error);
}

Keyframe Load(const std::string& image, const std::string& depth, double depth_scale,
              const sensor::PinholeIntrinsics& in, const Vocabulary* vocabulary) {
  const cv::Mat color = cv::imread(image, cv::IMREAD_COLOR);
  EXPECT_FALSE(color.empty()) << image;
  cv::Mat depth_m;
  if (!depth.empty()) depth_m = DepthToMeters(cv::imread(depth, cv::IMREAD_ANYDEPTH), depth_scale);
  return MakeKeyframe(color, depth_m, in, OrbExtractor(OrbOptions{}), vocabulary, KeyframeOptions{});
}

// Open3D/Redwood trajectory.log: a "i i i+1" line, then the 4x4 T_world_cam.
std::vector<common::Rigid3d> ReadTrajectoryLog(const std::string& path) {
  std::ifstream file(path);
  std::vector<common::Rigid3d> poses;
  int a, b, c;
  while (file >> a >> b >> c) {
    Eigen::Matrix4d T;
    for (int r = 0; r < 4; ++r)
      for (int k = 0; k < 4; ++k) file >> T(r, k);
    poses.emplace_back(T.block<3, 1>(0, 3), Eigen::Quaterniond(T.block<3, 3>(0, 0)));
  }
  return poses;
}

TEST(RealImagesTest, IclLivingRoomPnpRecoversTheTrueRelativePose) {
  const std::string dir = kVisual + "/open3d_icl_livingroom";
  SKIP_WITHOUT(dir);
  const std::vector<common::Rigid3d> T_world_cam = ReadTrajectoryLog(dir + "/trajectory.log");
  ASSERT_EQ(T_world_cam.size(), 5u);
  const sensor::PinholeIntrinsics in = Intrinsics(525.0, 525.0, 319.5, 239.5);
  const Keyframe a = Load(dir + "/color/00000.jpg", dir + "/depth/00000.png", 1000.0, in, nullptr);
  for (int j = 1; j < 5; ++j) {
    const Keyframe b = Load(dir + "/color/0000" + std::to_string(j) + ".jpg", "", 1.0, in, nullptr);
    const VerificationResult result = VerifyKeyframes(a, b, VerificationOptions{});
    ASSERT_TRUE(result.verified) << j << ": " << result.reason;
    const common::Rigid3d truth = T_world_cam[0].inverse() * T_world_cam[j];
    const double error_m = (result.T_a_b.translation() - truth.translation()).norm();
    const double error_deg = testing::AngleBetweenDeg(result.T_a_b, truth);
    std::cout << "ICL 0 -> " << j << ": inliers " << result.inliers << ", |t| "
              << truth.translation().norm() << " m, error " << error_m * 1000.0 << " mm, "
              << error_deg << " deg\n";
    EXPECT_LT(error_m, 0.01) << j;
    EXPECT_LT(error_deg, 0.3) << j;
    // The stated uncertainty is not wildly off the actual error (3-sigma on the distance).
    EXPECT_LT(error_m, 3.0 * std::sqrt(result.covariance.topLeftCorner<3, 3>().trace()) + 0.005);
  }
}

// The motion links' refinement on pixels (RefineByPatchAlignment) on real-looking images: it
// must not cost the pose what it gains in the simulator.
TEST(RealImagesTest, IclLivingRoomPatchRefinementKeepsTheTrueRelativePose) {
  const std::string dir = kVisual + "/open3d_icl_livingroom";
  SKIP_WITHOUT(dir);
  const std::vector<common::Rigid3d> T_world_cam = ReadTrajectoryLog(dir + "/trajectory.log");
  ASSERT_EQ(T_world_cam.size(), 5u);
  const sensor::PinholeIntrinsics in = Intrinsics(525.0, 525.0, 319.5, 239.5);
  CameraImage image_a;
  image_a.gray = cv::imread(dir + "/color/00000.jpg", cv::IMREAD_GRAYSCALE);
  image_a.depth_m =
      DepthToMeters(cv::imread(dir + "/depth/00000.png", cv::IMREAD_ANYDEPTH), 1000.0);
  image_a.intrinsics = in;
  const Keyframe a = Load(dir + "/color/00000.jpg", dir + "/depth/00000.png", 1000.0, in, nullptr);
  for (int j = 1; j < 5; ++j) {
    const std::string path_b = dir + "/color/0000" + std::to_string(j) + ".jpg";
    CameraImage image_b;
    image_b.gray = cv::imread(path_b, cv::IMREAD_GRAYSCALE);
    image_b.intrinsics = in;
    const Keyframe b = Load(path_b, "", 1.0, in, nullptr);
    VerificationResult result = VerifyKeyframes(a, b, VerificationOptions{});
    ASSERT_TRUE(result.verified) << j << ": " << result.reason;
    const common::Rigid3d truth = T_world_cam[0].inverse() * T_world_cam[j];
    const double before_m = (result.T_a_b.translation() - truth.translation()).norm();
    const double before_deg = testing::AngleBetweenDeg(result.T_a_b, truth);
    const int aligned =
        RefineByPatchAlignment(a, image_a, b, image_b, PatchAlignmentOptions{}, &result);
    const double error_m = (result.T_a_b.translation() - truth.translation()).norm();
    const double error_deg = testing::AngleBetweenDeg(result.T_a_b, truth);
    std::cout << "ICL 0 -> " << j << " refined on pixels: " << aligned << " of " << result.inliers
              << " aligned, error " << before_m * 1000.0 << " -> " << error_m * 1000.0 << " mm, "
              << before_deg << " -> " << error_deg << " deg\n";
    EXPECT_GE(aligned, 150) << j;  // of 267-477 inliers, at most max_points (300) tried
    EXPECT_LT(error_m, 0.01) << j;
    EXPECT_LT(error_deg, 0.3) << j;
    // Not worse than from the keypoints by more than their own spread here (~1 mm).
    EXPECT_LT(error_m, before_m + 0.002) << j;
  }
}

TEST(RealImagesTest, TumPairGivesAHundredInliersAndAConsistentPose) {
  const std::string dir = kVisual + "/slambook2_tum_fr2/pair_ch7";
  SKIP_WITHOUT(dir);
  const sensor::PinholeIntrinsics in = Intrinsics(520.9, 521.0, 325.1, 249.7);
  const Keyframe one = Load(dir + "/1.png", dir + "/1_depth.png", 5000.0, in, nullptr);
  const Keyframe two = Load(dir + "/2.png", dir + "/2_depth.png", 5000.0, in, nullptr);
  const VerificationResult forward = VerifyKeyframes(one, two, VerificationOptions{});
  const VerificationResult backward = VerifyKeyframes(two, one, VerificationOptions{});
  ASSERT_TRUE(forward.verified) << forward.reason;
  ASSERT_TRUE(backward.verified) << backward.reason;
  EXPECT_GE(forward.inliers, 100);
  EXPECT_GE(backward.inliers, 100);
  // No ground truth: each image's own depth gives the same motion (one is the other's inverse),
  // and it is the ~0.15 m, ~4 degree step the README describes.
  const common::Rigid3d loop = forward.T_a_b * backward.T_a_b;
  std::cout << "TUM pair: inliers " << forward.inliers << " / " << backward.inliers << ", |t| "
            << forward.T_a_b.translation().norm() << " m, round trip "
            << loop.translation().norm() * 1000.0 << " mm, "
            << loop.rotation().angularDistance(Eigen::Quaterniond::Identity()) * 180.0 / M_PI << " deg\n";
  EXPECT_LT(loop.translation().norm(), 0.02);
  EXPECT_LT(loop.rotation().angularDistance(Eigen::Quaterniond::Identity()), 0.5 * M_PI / 180.0);
  EXPECT_NEAR(forward.T_a_b.translation().norm(), 0.15, 0.03);
}

// On real Kinect images the refinement on pixels keeps the pair's two estimates (each from its
// own depth) each other's inverse.
TEST(RealImagesTest, TumPairPatchRefinementKeepsThePoseConsistent) {
  const std::string dir = kVisual + "/slambook2_tum_fr2/pair_ch7";
  SKIP_WITHOUT(dir);
  const sensor::PinholeIntrinsics in = Intrinsics(520.9, 521.0, 325.1, 249.7);
  CameraImage images[2];
  Keyframe keyframes[2];
  for (int i = 0; i < 2; ++i) {
    const std::string stem = dir + "/" + std::to_string(i + 1);
    images[i].gray = cv::imread(stem + ".png", cv::IMREAD_GRAYSCALE);
    images[i].depth_m = DepthToMeters(cv::imread(stem + "_depth.png", cv::IMREAD_ANYDEPTH), 5000.0);
    images[i].intrinsics = in;
    keyframes[i] = Load(stem + ".png", stem + "_depth.png", 5000.0, in, nullptr);
  }
  VerificationResult forward = VerifyKeyframes(keyframes[0], keyframes[1], VerificationOptions{});
  VerificationResult backward = VerifyKeyframes(keyframes[1], keyframes[0], VerificationOptions{});
  ASSERT_TRUE(forward.verified && backward.verified);
  const common::Rigid3d loop_before = forward.T_a_b * backward.T_a_b;
  const int aligned_forward = RefineByPatchAlignment(keyframes[0], images[0], keyframes[1],
                                                     images[1], PatchAlignmentOptions{}, &forward);
  const int aligned_backward = RefineByPatchAlignment(
      keyframes[1], images[1], keyframes[0], images[0], PatchAlignmentOptions{}, &backward);
  const common::Rigid3d loop = forward.T_a_b * backward.T_a_b;
  const double loop_deg =
      loop.rotation().angularDistance(Eigen::Quaterniond::Identity()) * 180.0 / M_PI;
  std::cout << "TUM pair refined on pixels: " << aligned_forward << " / " << aligned_backward
            << " aligned, round trip " << loop_before.translation().norm() * 1000.0 << " -> "
            << loop.translation().norm() * 1000.0 << " mm, " << loop_deg << " deg\n";
  EXPECT_GE(aligned_forward, 100);
  EXPECT_GE(aligned_backward, 100);
  EXPECT_LT(loop.translation().norm(), 0.02);
  EXPECT_LT(loop_deg, 0.5);
  EXPECT_NEAR(forward.T_a_b.translation().norm(), 0.15, 0.03);
}

TEST(RealImagesTest, LoopCh11DetectsTenRevisitingOneAndNothingElse) {
  const std::string dir = kVisual + "/slambook2_tum_fr2/loop_ch11";
  SKIP_WITHOUT(dir);
  const std::optional<Vocabulary> vocabulary = CommittedVocabulary();
  ASSERT_TRUE(vocabulary);
  std::string error;
  const std::vector<std::string> images = ListImages(dir, &error);
  ASSERT_EQ(images.size(), 10u) << error;
  LoopDetector detector(ImageSequenceDetectorOptions(), vocabulary->num_words());
  std::vector<std::pair<std::string, std::string>> loops;
  for (size_t i = 0; i < images.size(); ++i) {
    Keyframe keyframe = Load(images[i], "", 1.0, sensor::PinholeIntrinsics{}, &*vocabulary);
    keyframe.id = static_cast<int>(i);
    if (const auto loop = detector.Process(std::move(keyframe))) {
      loops.emplace_back(std::filesystem::path(images[loop->query_id]).filename().string(),
                         std::filesystem::path(images[loop->match_id]).filename().string());
    }
  }
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].first, "10.png");
  EXPECT_EQ(loops[0].second, "1.png");
}

// EuRoC cam0 (radtan): undistorted with its own intrinsics before anything else.
Keyframe LoadEuroc(int index, const Vocabulary& vocabulary) {
  const std::string path = kVisual + "/kimera_euroc_lcd/left_img_" + std::to_string(index) + ".png";
  const cv::Mat raw = cv::imread(path, cv::IMREAD_GRAYSCALE);
  EXPECT_FALSE(raw.empty()) << path;
  const cv::Matx33d K(458.654, 0, 367.215, 0, 457.296, 248.375, 0, 0, 1);
  const cv::Vec4d distortion(-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05);
  cv::Mat image;
  cv::undistort(raw, image, K, distortion);
  return MakeKeyframe(image, cv::Mat(), Intrinsics(458.654, 457.296, 367.215, 248.375),
                      OrbExtractor(OrbOptions{}), &vocabulary, KeyframeOptions{});
}

common::Rigid3d BodyPose(double w, double x, double y, double z, double px, double py, double pz) {
  return common::Rigid3d(Eigen::Vector3d(px, py, pz), Eigen::Quaterniond(w, x, y, z));
}

TEST(RealImagesTest, EurocQueriesRetrieveAndVerifyTheirMatches) {
  SKIP_WITHOUT(kVisual + "/kimera_euroc_lcd");
  const std::optional<Vocabulary> vocabulary = CommittedVocabulary();
  ASSERT_TRUE(vocabulary);
  // Ground truth from the Kimera fixture (world_T_body) and T_body_cam0 from sensorLeft.yaml.
  Eigen::Matrix3d R_body_cam;
  R_body_cam << 0.0148655429818, -0.999880929698, 0.00414029679422, 0.999557249008,
      0.0149672133247, 0.025715529948, -0.0257744366974, 0.00375618835797, 0.999660727178;
  const common::Rigid3d T_body_cam(Eigen::Vector3d(-0.0216401454975, -0.064676986768, 0.00981073058949),
                                   Eigen::Quaterniond(R_body_cam));
  const common::Rigid3d match1 = BodyPose(0.338337, 0.608466, -0.535476, 0.478082, 1.573832, 2.023348, 1.738755);
  const common::Rigid3d query1 = BodyPose(0.478634, 0.415595, -0.700197, 0.328505, 1.872115, 1.786064, 1.586159);
  const common::Rigid3d match2 = BodyPose(0.3394, -0.672895, -0.492724, -0.435018, -0.662997, -0.495046, 1.347300);
  const common::Rigid3d query2 = BodyPose(0.39266, -0.590667, -0.58023, -0.400326, -0.345638, -0.501712, 1.320441);
  struct Pair {
    int match;
    int query;
    common::Rigid3d T_match_query_cam;
  };
  const Pair pairs[] = {
      {0, 1, T_body_cam.inverse() * match1.inverse() * query1 * T_body_cam},
      {2, 3, T_body_cam.inverse() * match2.inverse() * query2 * T_body_cam},
  };
  // Both match images are in the database; each query must rank its own first and verify.
  KeyframeDatabase database(vocabulary->num_words());
  std::vector<Keyframe> keyframes;
  for (int i = 0; i < 4; ++i) keyframes.push_back(LoadEuroc(i, *vocabulary));
  database.Add(0, keyframes[0].bow);
  database.Add(2, keyframes[2].bow);
  for (const Pair& pair : pairs) {
    const std::vector<DatabaseResult> results = database.Query(keyframes[pair.query].bow, 4, 2);
    ASSERT_EQ(results.size(), 2u);
    EXPECT_EQ(results[0].id, pair.match) << "query " << pair.query;
    const VerificationResult result =
        VerifyKeyframes(keyframes[pair.match], keyframes[pair.query], VerificationOptions{});
    ASSERT_TRUE(result.verified) << "query " << pair.query << ": " << result.reason;
    const double rotation_error_deg = testing::AngleBetweenDeg(result.T_a_b, pair.T_match_query_cam);
    const double direction_cos = result.T_a_b.translation().normalized().dot(
        pair.T_match_query_cam.translation().normalized());
    std::cout << "EuRoC " << pair.query << " -> " << pair.match << ": score " << results[0].score
              << " vs " << results[1].score << ", inliers " << result.inliers << ", true rotation "
              << testing::AngleBetweenDeg(pair.T_match_query_cam, common::Rigid3d::Identity())
              << " deg, error " << rotation_error_deg << " deg, translation direction cos "
              << direction_cos << "\n";
    // Monocular and on a 0.5 m / 37 degree step: the README's own check with OpenCV found 3.1 and
    // 3.9 degrees; this is a sanity bound, recognition is what is asserted.
    EXPECT_LT(rotation_error_deg, 8.0);
    EXPECT_GT(direction_cos, 0.9);
  }
  // And the unrelated pairs do not verify.
  for (const auto& [a, b] : {std::pair{0, 3}, std::pair{2, 1}}) {
    EXPECT_FALSE(VerifyKeyframes(keyframes[a], keyframes[b], VerificationOptions{}).verified) << a << "-" << b;
  }
}

}  // namespace
}  // namespace visual_loop
}  // namespace fusemap
