#include <chrono>
#include <cstdio>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include "fusemap/common/command_line.h"
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

struct TrainArgs {
  std::string out;
  std::vector<std::string> inputs;
  visual_loop::VocabularyTrainingOptions options;
  visual_loop::OrbOptions orb_options;
};

// Trains on the inputs' images and writes the vocabulary: 0, or 1 for bad input or a failed
// write.
int TrainVocabulary(const TrainArgs& args) {
  const visual_loop::VocabularyTrainingOptions& options = args.options;
  std::string error;
  std::vector<std::string> images;
  for (const std::string& input : args.inputs) {
    if (std::filesystem::is_directory(input)) {
      const std::vector<std::string> listed = visual_loop::ListImages(input, &error);
      if (listed.empty()) {
        std::fprintf(stderr, "error: %s: no images%s%s\n", input.c_str(), error.empty() ? "" : ": ",
                     error.c_str());
        return common::kExitFailure;
      }
      images.insert(images.end(), listed.begin(), listed.end());
    } else {
      images.push_back(input);
    }
  }
  const auto start = std::chrono::steady_clock::now();
  const visual_loop::OrbExtractor extractor(args.orb_options);
  std::vector<cv::Mat> descriptors;
  size_t total = 0;
  for (const std::string& path : images) {
    const cv::Mat gray = ReadImage(path, cv::IMREAD_GRAYSCALE);
    if (gray.empty()) return common::kExitFailure;
    descriptors.push_back(extractor.Extract(gray).descriptors);
    total += descriptors.back().rows;
  }
  if (total == 0) {
    std::fprintf(stderr, "error: no ORB features in the given images\n");
    return common::kExitFailure;
  }
  const visual_loop::Vocabulary vocabulary = visual_loop::TrainVocabulary(descriptors, options);
  const std::string& out = args.out;
  if (!vocabulary.Save(out, &error)) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return common::kExitFailure;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("images=%zu descriptors=%zu k=%d levels=%d nodes=%d words=%d bytes=%zu wall_s=%.1f\n",
              images.size(), total, options.branching, options.levels, vocabulary.num_nodes(),
              vocabulary.num_words(), vocabulary.ToBytes().size(), seconds);
  return common::kExitSuccess;
}

}  // namespace

int TrainVocabularyCommand(int argc, char** argv) {
  TrainArgs args;
  int seed = 1;
  const int kLimit = 1000000000;
  common::CommandLine command_line("fusemap_vloop train-vocabulary", kHelp);
  command_line.AddPositional("OUT.bin", &args.out);
  command_line.AddPositionalList("IMAGE_OR_DIR", &args.inputs, 1);
  command_line.AddInt("--k", &args.options.branching, -kLimit, kLimit);
  command_line.AddInt("--levels", &args.options.levels, -kLimit, kLimit);
  command_line.AddInt("--max-features", &args.orb_options.max_features, -kLimit, kLimit);
  command_line.AddInt("--seed", &seed, -kLimit, kLimit);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  // As before: a negative seed wraps around (-1 is 4294967295).
  args.options.seed = static_cast<uint32_t>(seed);
  std::string error;
  if (!args.options.IsValid(&error) || !args.orb_options.IsValid(&error)) {
    return command_line.UsageError(error);
  }
  return TrainVocabulary(args);
}

}  // namespace vloop
}  // namespace fusemap
