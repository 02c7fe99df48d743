#include <chrono>
#include <cstdio>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include "fusemap/visual_loop/image_sequence.h"
#include "fusemap/visual_loop/orb_extractor.h"
#include "fusemap/visual_loop/vocabulary_trainer.h"
#include "vloop_common.h"

namespace fusemap {
namespace vloop {
namespace {

constexpr char kHelp[] =
    "usage: fusemap_vloop train-vocabulary OUT.bin IMAGE_OR_DIR... [--k K] [--levels L]\n"
    "                                      [--max-features N] [--seed S]\n"
    "Extracts up to N ORB features per image (directories: their images, natural order) and\n"
    "trains a vocabulary tree by hierarchical k-majority with kmeans++ seeding; idf weights.\n"
    "Defaults: K=10, L=4, N=1000, S=1 (same inputs and seed: same file).\n";

}  // namespace

int TrainVocabularyCommand(int argc, char** argv) {
  Arguments args;
  std::string error;
  if (!ParseArguments(argc, argv, 2, {"--k", "--levels", "--max-features", "--seed"}, {}, &args,
                      &error)) {
    std::fprintf(stderr, "error: %s\n%s", error.c_str(), kHelp);
    return kExitUsage;
  }
  if (args.help) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  if (args.positional.size() < 2) {
    std::fprintf(stderr, "error: need OUT.bin and at least one image or directory\n%s", kHelp);
    return kExitUsage;
  }
  visual_loop::VocabularyTrainingOptions options;
  visual_loop::OrbOptions orb_options;
  int seed = 1;
  const std::pair<const char*, int*> ints[] = {{"--k", &options.branching},
                                               {"--levels", &options.levels},
                                               {"--max-features", &orb_options.max_features},
                                               {"--seed", &seed}};
  for (const auto& [name, target] : ints) {
    if (const auto value = args.Get(name); value && !ParseInt(*value, target)) {
      std::fprintf(stderr, "error: %s: not an integer: '%s'\n", name, value->c_str());
      return kExitUsage;
    }
  }
  options.seed = static_cast<uint32_t>(seed);
  if (!options.IsValid(&error) || !orb_options.IsValid(&error)) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return kExitUsage;
  }

  std::vector<std::string> images;
  for (size_t i = 1; i < args.positional.size(); ++i) {
    const std::string& input = args.positional[i];
    if (std::filesystem::is_directory(input)) {
      const std::vector<std::string> listed = visual_loop::ListImages(input, &error);
      if (listed.empty()) {
        std::fprintf(stderr, "error: %s: no images%s%s\n", input.c_str(), error.empty() ? "" : ": ",
                     error.c_str());
        return kExitBadInput;
      }
      images.insert(images.end(), listed.begin(), listed.end());
    } else {
      images.push_back(input);
    }
  }
  const auto start = std::chrono::steady_clock::now();
  const visual_loop::OrbExtractor extractor(orb_options);
  std::vector<cv::Mat> descriptors;
  size_t total = 0;
  for (const std::string& path : images) {
    const cv::Mat gray = ReadImage(path, cv::IMREAD_GRAYSCALE);
    if (gray.empty()) return kExitBadInput;
    descriptors.push_back(extractor.Extract(gray).descriptors);
    total += descriptors.back().rows;
  }
  if (total == 0) {
    std::fprintf(stderr, "error: no ORB features in the given images\n");
    return kExitBadInput;
  }
  const visual_loop::Vocabulary vocabulary = visual_loop::TrainVocabulary(descriptors, options);
  const std::string& out = args.positional[0];
  if (!vocabulary.Save(out, &error)) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return kExitBadInput;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("images=%zu descriptors=%zu k=%d levels=%d nodes=%d words=%d bytes=%zu wall_s=%.1f\n",
              images.size(), total, options.branching, options.levels, vocabulary.num_nodes(),
              vocabulary.num_words(), vocabulary.ToBytes().size(), seconds);
  return kExitOk;
}

}  // namespace vloop
}  // namespace fusemap
