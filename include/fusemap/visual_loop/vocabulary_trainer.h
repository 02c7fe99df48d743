#ifndef FUSEMAP_VISUAL_LOOP_VOCABULARY_TRAINER_H_
#define FUSEMAP_VISUAL_LOOP_VOCABULARY_TRAINER_H_

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "fusemap/visual_loop/vocabulary.h"

namespace fusemap {
namespace visual_loop {

struct VocabularyTrainingOptions {
  int branching = 10;
  int levels = 4;
  int max_iterations = 15;  // k-majority rounds per node
  uint32_t seed = 1;        // std::mt19937: the same inputs and seed give the same file
  bool IsValid(std::string* error) const;
};

// Trains a vocabulary tree by hierarchical k-majority clustering (k-medians for binary
// descriptors: centres are the bitwise majority of their members, Grana et al. 2013), seeded
// by k-means++ (Arthur & Vassilvitskii 2007) with Hamming distance, as DBoW2 builds its trees.
// Word weights are idf = ln(N / n_i) over the N training images, n_i of which contain word i.
// descriptors_per_image: one CV_8UC1 N x 32 matrix per training image.
Vocabulary TrainVocabulary(const std::vector<cv::Mat>& descriptors_per_image,
                           const VocabularyTrainingOptions& options);

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_VOCABULARY_TRAINER_H_
