#include <cstdio>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include "fusemap/common/command_line.h"
#include "fusemap/visual_loop/image_sequence.h"
#include "fusemap/visual_loop/keyframe.h"
#include "fusemap/visual_loop/loop_detector.h"
#include "vloop_common.h"

namespace fusemap {
namespace vloop {
namespace {

constexpr char kHelp[] =
    "usage: fusemap_vloop detect DIR [--intrinsics fx,fy,cx,cy] [--vocabulary V]\n"
    "                            [--exclude-recent N] [--consistency N] [--verbose]\n"
    "Reads DIR's images (.png .jpg .jpeg .pgm .ppm .bmp) as one sequence in natural name order\n"
    "(2.png before 10.png), retrieves earlier images by bag of words, and verifies the best\n"
    "candidates geometrically (essential matrix with --intrinsics, else fundamental matrix).\n"
    "Prints 'loop QUERY MATCH score=S inliers=I' per accepted revisit (S: the score normalised\n"
    "by the query's score against its previous image), then 'frames=N loops=M'.\n"
    "  --exclude-recent N  the N images before the query are never candidates (default 3)\n"
    "  --consistency N     earlier consecutive queries that must agree (default 1)\n"
    "  --verbose           also print every candidate island\n";

struct DetectArgs {
  std::string directory, vocabulary;
  sensor::PinholeIntrinsics intrinsics;
  visual_loop::LoopDetectorOptions options = visual_loop::ImageSequenceDetectorOptions();
  bool verbose = false;
};

// Runs the loop detector over the directory's images and prints the loops: 0, or 1 for bad
// input.
int Detect(const DetectArgs& args) {
  const visual_loop::LoopDetectorOptions& options = args.options;
  const sensor::PinholeIntrinsics& intrinsics = args.intrinsics;
  const bool verbose = args.verbose;
  std::string error;
  const std::string& directory = args.directory;
  if (!std::filesystem::is_directory(directory)) {
    std::fprintf(stderr, "error: %s: not a directory\n", directory.c_str());
    return common::kExitFailure;
  }
  const std::vector<std::string> images = visual_loop::ListImages(directory, &error);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return common::kExitFailure;
  }
  const std::optional<visual_loop::Vocabulary> vocabulary =
      LoadVocabularyOrReport(VocabularyPath(args.vocabulary));
  if (!vocabulary) return common::kExitFailure;

  const visual_loop::OrbExtractor extractor{visual_loop::OrbOptions{}};
  visual_loop::LoopDetector detector(options, vocabulary->num_words());
  int loops = 0;
  for (size_t i = 0; i < images.size(); ++i) {
    const cv::Mat image = ReadImage(images[i], cv::IMREAD_GRAYSCALE);
    if (image.empty()) return common::kExitFailure;
    visual_loop::Keyframe keyframe = visual_loop::MakeKeyframe(
        image, cv::Mat(), intrinsics, extractor, &*vocabulary, visual_loop::KeyframeOptions{});
    keyframe.id = static_cast<int>(i);
    std::vector<visual_loop::PlaceCandidate> candidates;
    const auto loop = detector.Process(std::move(keyframe), &candidates);
    const auto name = [&](int id) { return std::filesystem::path(images[id]).filename().string(); };
    if (verbose) {
      for (const auto& c : candidates) {
        std::printf("candidate %s %s score=%.4f normalized=%.3f island=%s..%s consistent_queries=%d\n",
                    name(static_cast<int>(i)).c_str(), name(c.id).c_str(), c.score, c.normalized_score,
                    name(c.island_first).c_str(), name(c.island_last).c_str(), c.consistent_queries);
      }
    }
    if (loop) {
      ++loops;
      std::printf("loop %s %s score=%.3f inliers=%d\n", name(loop->query_id).c_str(),
                  name(loop->match_id).c_str(), loop->normalized_score, loop->verification.inliers);
    }
  }
  std::printf("frames=%zu loops=%d\n", images.size(), loops);
  return common::kExitSuccess;
}

}  // namespace

int DetectCommand(int argc, char** argv) {
  DetectArgs args;
  std::vector<double> intrinsics;
  common::CommandLine command_line("fusemap_vloop detect", kHelp);
  command_line.AddPositional("DIR", &args.directory);
  command_line.AddDoubleList("--intrinsics", &intrinsics, {}, 4);
  command_line.AddString("--vocabulary", &args.vocabulary);
  command_line.AddInt("--exclude-recent", &args.options.recognition.num_recent_excluded, 0,
                      1000000000);
  command_line.AddInt("--consistency", &args.options.recognition.temporal_consistency, 0,
                      1000000000);
  command_line.AddFlag("--verbose", &args.verbose);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  if (command_line.Given("--intrinsics") && !IntrinsicsFromList(intrinsics, &args.intrinsics)) {
    return command_line.UsageError("--intrinsics wants fx,fy,cx,cy with fx, fy > 0");
  }
  return Detect(args);
}

}  // namespace vloop
}  // namespace fusemap
