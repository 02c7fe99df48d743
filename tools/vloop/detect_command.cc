#include <cstdio>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

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

}  // namespace

int DetectCommand(int argc, char** argv) {
  Arguments args;
  std::string error;
  if (!ParseArguments(argc, argv, 2, {"--intrinsics", "--vocabulary", "--exclude-recent", "--consistency"},
                      {"--verbose"}, &args, &error)) {
    std::fprintf(stderr, "error: %s\n%s", error.c_str(), kHelp);
    return kExitUsage;
  }
  if (args.help) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  if (args.positional.size() != 1) {
    std::fprintf(stderr, "error: need exactly one directory\n%s", kHelp);
    return kExitUsage;
  }
  visual_loop::LoopDetectorOptions options = visual_loop::ImageSequenceDetectorOptions();
  sensor::PinholeIntrinsics intrinsics;
  if (const auto text = args.Get("--intrinsics"); text && !ParseIntrinsics(*text, &intrinsics)) {
    std::fprintf(stderr, "error: --intrinsics wants fx,fy,cx,cy (fx, fy > 0), got '%s'\n", text->c_str());
    return kExitUsage;
  }
  const std::pair<const char*, int*> ints[] = {
      {"--exclude-recent", &options.recognition.num_recent_excluded},
      {"--consistency", &options.recognition.temporal_consistency}};
  for (const auto& [name, target] : ints) {
    if (const auto value = args.Get(name); value && (!ParseInt(*value, target) || *target < 0)) {
      std::fprintf(stderr, "error: %s wants a non-negative integer, got '%s'\n", name, value->c_str());
      return kExitUsage;
    }
  }
  const bool verbose = args.Get("--verbose").has_value();
  const std::string& directory = args.positional[0];
  if (!std::filesystem::is_directory(directory)) {
    std::fprintf(stderr, "error: %s: not a directory\n", directory.c_str());
    return kExitBadInput;
  }
  const std::vector<std::string> images = visual_loop::ListImages(directory, &error);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return kExitBadInput;
  }
  const std::optional<visual_loop::Vocabulary> vocabulary = LoadVocabularyOrReport(VocabularyPath(args));
  if (!vocabulary) return kExitBadInput;

  const visual_loop::OrbExtractor extractor{visual_loop::OrbOptions{}};
  visual_loop::LoopDetector detector(options, vocabulary->num_words());
  int loops = 0;
  for (size_t i = 0; i < images.size(); ++i) {
    const cv::Mat image = ReadImage(images[i], cv::IMREAD_GRAYSCALE);
    if (image.empty()) return kExitBadInput;
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
  return kExitOk;
}

}  // namespace vloop
}  // namespace fusemap
