// fusemap_vloop: the ORB visual loop checker over image files (train a vocabulary, verify a
// pair, detect revisits in a sequence).
#include "fusemap/common/command_line.h"
#include "vloop_common.h"

namespace {

constexpr char kUsage[] =
    "usage: fusemap_vloop COMMAND ...\n"
    "  train-vocabulary OUT.bin IMAGE_OR_DIR... [--k K] [--levels L] [--max-features N] [--seed S]\n"
    "      trains a binary bag-of-words vocabulary (hierarchical k-majority, kmeans++ seeding)\n"
    "  match A.png B.png [--depth-a DA.png --depth-b DB.png --depth-scale S]\n"
    "        [--intrinsics fx,fy,cx,cy] [--vocabulary V]\n"
    "      matches two images and prints inliers and T_a_b (pose of B in A): with --depth-a by\n"
    "      PnP on A's 3D points (metric), else by the essential matrix (translation up to scale)\n"
    "      with --intrinsics, else the fundamental matrix (no pose)\n"
    "  detect DIR [--intrinsics fx,fy,cx,cy] [--vocabulary V] [--exclude-recent N]\n"
    "             [--consistency N] [--verbose]\n"
    "      reads DIR's images as one sequence in natural name order and prints\n"
    "      'loop QUERY MATCH score=... inliers=...' per accepted revisit, then 'frames=N loops=M'\n"
    "Each command takes --help. Exit codes: 0 success, 1 bad input, 2 usage error.\n";

}  // namespace

int main(int argc, char** argv) {
  using namespace fusemap::vloop;
  return fusemap::common::RunSubcommand("fusemap_vloop", kUsage,
                                        {{"train-vocabulary", TrainVocabularyCommand},
                                         {"match", MatchCommand},
                                         {"detect", DetectCommand}},
                                        argc, argv);
}
