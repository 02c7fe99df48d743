#ifndef FUSEMAP_VISUAL_LOOP_VOCABULARY_H_
#define FUSEMAP_VISUAL_LOOP_VOCABULARY_H_

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "fusemap/visual_loop/bow_vector.h"

namespace fusemap {
namespace visual_loop {

using OrbDescriptor = std::array<uint8_t, 32>;

int HammingDistance(const uint8_t* a, const uint8_t* b);

// A vocabulary tree of binary words (Nister & Stewenius 2006; Galvez-Lopez & Tardos 2012):
// each node holds a 256-bit centre; a descriptor descends to the nearest child (Hamming) at
// every level and the leaf it reaches is its word. Every word has an idf weight. Invariants:
// node 0 is the root (no centre), children of a node are contiguous, leaves carry word ids
// 0..num_words-1.
class Vocabulary {
 public:
  struct Node {
    uint32_t first_child = 0;
    uint32_t num_children = 0;
    int32_t word = -1;  // -1 for inner nodes
  };

  Vocabulary() = default;
  // centres has one row per node (row 0, the root's, is unused). Checked by IsConsistent().
  Vocabulary(int branching, int levels, std::vector<Node> nodes, std::vector<OrbDescriptor> centres,
             std::vector<float> word_weights);

  int branching() const { return branching_; }
  int levels() const { return levels_; }
  int num_words() const { return static_cast<int>(word_weights_.size()); }
  int num_nodes() const { return static_cast<int>(nodes_.size()); }
  bool empty() const { return nodes_.empty(); }
  float word_weight(int word) const { return word_weights_[word]; }

  // The word of a descriptor; node_at_level (optional) receives the node it passed at
  // node_level (1 = a child of the root; a leaf above that level is its own node).
  int WordOf(const uint8_t* descriptor, int node_level = 0, uint32_t* node_at_level = nullptr) const;
  // tf-idf vector of an image's descriptors (CV_8UC1, N x 32), L1-normalised. Words whose idf is
  // 0 (seen in every training image) carry no information and are left out. nodes (optional)
  // receives per descriptor its node at node_level: the "direct index" that restricts matching
  // to descriptors under the same node (Galvez-Lopez & Tardos 2012, Sec. VI).
  BowVector Transform(const cv::Mat& descriptors, int node_level = 0,
                      std::vector<uint32_t>* nodes = nullptr) const;

  // Binary file: "FMBOWVOC" magic, u32 version, u32 branching, u32 levels, u32 node count,
  // u32 word count, per node (32-byte centre, u32 first child, u32 child count, i32 word), per
  // word a f32 weight, then the CRC-32 of all that; little-endian.
  std::vector<uint8_t> ToBytes() const;
  static std::optional<Vocabulary> FromBytes(const std::vector<uint8_t>& bytes,
                                             std::string* error);
  bool Save(const std::string& path, std::string* error) const;
  static std::optional<Vocabulary> Load(const std::string& path, std::string* error);

  // Structural check of the invariants above (a loaded file passed its CRC but may still lie).
  bool IsConsistent(std::string* error) const;

 private:
  int branching_ = 0;
  int levels_ = 0;
  std::vector<Node> nodes_;
  std::vector<OrbDescriptor> centres_;
  std::vector<float> word_weights_;
};

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_VOCABULARY_H_
