#include <cmath>
#include <cstdio>

#include <opencv2/imgcodecs.hpp>

#include "fusemap/common/command_line.h"
#include "fusemap/visual_loop/geometric_verifier.h"
#include "fusemap/visual_loop/keyframe.h"
#include "fusemap/visual_loop/planar_constraint.h"
#include "vloop_common.h"

namespace fusemap {
namespace vloop {
namespace {

constexpr char kHelp[] =
    "usage: fusemap_vloop match A.png B.png [--depth-a DA.png] [--depth-b DB.png]\n"
    "                           [--depth-scale S] [--intrinsics fx,fy,cx,cy] [--vocabulary V]\n"
    "Matches ORB features of A and B (Hamming, ratio test, mutual check) and verifies them:\n"
    "with --depth-a (16-bit, value/S = metres; S defaults to 1000) by PnP + RANSAC on A's 3D\n"
    "points, metric; without depth by the essential matrix (needs --intrinsics; translation is\n"
    "a unit vector, scale unknown) or else the fundamental matrix (no pose). Prints matches,\n"
    "inliers and T_a_b, the pose of camera B in camera A (x right, y down, z forward), with its\n"
    "1-sigma from the covariance (PnP). Exit code 0 when verified, 1 when not or on bad input.\n";

// No path: no depth.
bool LoadDepth(const std::string& path, double scale, const cv::Size& size, cv::Mat* depth_m) {
  if (path.empty()) return true;
  const cv::Mat raw = ReadImage(path, cv::IMREAD_ANYDEPTH);
  if (raw.empty()) return false;
  if (raw.type() != CV_16UC1 || raw.size() != size) {
    std::fprintf(stderr, "error: %s: depth must be 16-bit and the colour image's size\n",
                 path.c_str());
    return false;
  }
  *depth_m = visual_loop::DepthToMeters(raw, scale);
  return true;
}

struct MatchArgs {
  std::string image_a, image_b, depth_a, depth_b, vocabulary;
  double depth_scale = 1000.0;
  sensor::PinholeIntrinsics intrinsics;
};

// Matches and verifies the pair and prints the result: 0 when verified, else 1.
int Match(MatchArgs args) {
  sensor::PinholeIntrinsics& intrinsics = args.intrinsics;
  const double depth_scale = args.depth_scale;
  std::string error;
  std::optional<visual_loop::Vocabulary> vocabulary;
  if (!args.vocabulary.empty()) {
    vocabulary = LoadVocabularyOrReport(args.vocabulary);
    if (!vocabulary) return common::kExitFailure;
  } else {
    vocabulary = visual_loop::Vocabulary::Load(VocabularyPath(""), &error);  // optional here
  }

  const cv::Mat image_a = ReadImage(args.image_a, cv::IMREAD_COLOR);
  const cv::Mat image_b = ReadImage(args.image_b, cv::IMREAD_COLOR);
  if (image_a.empty() || image_b.empty()) return common::kExitFailure;
  cv::Mat depth_a;
  cv::Mat depth_b;
  if (!LoadDepth(args.depth_a, depth_scale, image_a.size(), &depth_a) ||
      !LoadDepth(args.depth_b, depth_scale, image_b.size(), &depth_b)) {
    return common::kExitFailure;
  }
  intrinsics.width = image_a.cols;
  intrinsics.height = image_a.rows;
  const visual_loop::OrbExtractor extractor{visual_loop::OrbOptions{}};
  const visual_loop::Vocabulary* vocabulary_ptr = vocabulary ? &*vocabulary : nullptr;
  const visual_loop::Keyframe a = visual_loop::MakeKeyframe(image_a, depth_a, intrinsics, extractor,
                                                            vocabulary_ptr, visual_loop::KeyframeOptions{});
  const visual_loop::Keyframe b = visual_loop::MakeKeyframe(image_b, depth_b, intrinsics, extractor,
                                                            vocabulary_ptr, visual_loop::KeyframeOptions{});
  const visual_loop::VerificationResult result =
      visual_loop::VerifyKeyframes(a, b, visual_loop::VerificationOptions{});

  std::printf("features_a=%zu features_b=%zu depth_points_a=%d\n", a.keypoints.size(),
              b.keypoints.size(), a.num_points_with_depth());
  if (vocabulary) std::printf("bow_score=%.4f\n", visual_loop::L1Score(a.bow, b.bow));
  std::printf("method=%s matches=%d inliers=%d occupied_cells=%d mean_error_px=%.3f\n",
              visual_loop::ToString(result.method), result.matches, result.inliers,
              result.occupied_cells, result.mean_reprojection_px);
  if (result.has_pose) {
    const Eigen::Vector3d& t = result.T_a_b.translation();
    const Eigen::AngleAxisd axis_angle(result.T_a_b.rotation());
    const Eigen::Vector3d rpy = visual_loop::RollPitchYaw(result.T_a_b.rotation()) * 180.0 / M_PI;
    std::printf("T_a_b translation%s=%.4f %.4f %.4f norm=%.4f\n", result.metric ? "_m" : "_unit",
                t.x(), t.y(), t.z(), t.norm());
    std::printf("T_a_b rotation axis_angle_deg=%.3f axis=%.4f %.4f %.4f rpy_deg=%.3f %.3f %.3f\n",
                axis_angle.angle() * 180.0 / M_PI, axis_angle.axis().x(), axis_angle.axis().y(),
                axis_angle.axis().z(), rpy.x(), rpy.y(), rpy.z());
    if (result.metric && result.verified) {
      const auto sd = result.covariance.diagonal().cwiseSqrt();
      std::printf("sigma translation_m=%.4f %.4f %.4f rotation_deg=%.3f %.3f %.3f\n", sd[0], sd[1],
                  sd[2], sd[3] * 180.0 / M_PI, sd[4] * 180.0 / M_PI, sd[5] * 180.0 / M_PI);
    } else if (!result.metric) {
      std::printf("note: no depth, translation is known up to scale only\n");
    }
  }
  if (!result.verified) {
    std::printf("verified=no reason=%s\n", result.reason.c_str());
    return common::kExitFailure;
  }
  std::printf("verified=yes\n");
  return common::kExitSuccess;
}

}  // namespace

int MatchCommand(int argc, char** argv) {
  MatchArgs args;
  std::vector<double> intrinsics;
  common::CommandLine command_line("fusemap_vloop match", kHelp);
  command_line.AddPositional("A", &args.image_a);
  command_line.AddPositional("B", &args.image_b);
  command_line.AddString("--depth-a", &args.depth_a);
  command_line.AddString("--depth-b", &args.depth_b);
  command_line.AddDouble("--depth-scale", &args.depth_scale, common::NumberRange::Positive());
  command_line.AddDoubleList("--intrinsics", &intrinsics, {}, 4);
  command_line.AddString("--vocabulary", &args.vocabulary);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  if (command_line.Given("--intrinsics") && !IntrinsicsFromList(intrinsics, &args.intrinsics)) {
    return command_line.UsageError("--intrinsics wants fx,fy,cx,cy with fx, fy > 0");
  }
  if ((!args.depth_a.empty() || !args.depth_b.empty()) && args.intrinsics.fx <= 0.0) {
    return command_line.UsageError("depth needs --intrinsics to back-project");
  }
  return Match(args);
}

}  // namespace vloop
}  // namespace fusemap
