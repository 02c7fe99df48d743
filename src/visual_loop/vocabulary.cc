#include "fusemap/visual_loop/vocabulary.h"

#include <zlib.h>

#include <algorithm>
#include <cassert>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

namespace fusemap {
namespace visual_loop {
namespace {

constexpr char kMagic[8] = {'F', 'M', 'B', 'O', 'W', 'V', 'O', 'C'};
constexpr uint32_t kVersion = 1;
constexpr size_t kHeaderBytes = 8 + 5 * 4;
constexpr size_t kNodeBytes = 32 + 3 * 4;

template <typename T>
void Put(std::vector<uint8_t>* out, T value) {
  uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out->insert(out->end(), bytes, bytes + sizeof(T));
}

template <typename T>
T Get(const uint8_t* in) {
  T value;
  std::memcpy(&value, in, sizeof(T));
  return value;
}

uint32_t Crc32(const uint8_t* data, size_t size) {
  uLong crc = crc32(0L, Z_NULL, 0);
  // zlib takes uInt lengths: feed it in chunks.
  while (size > 0) {
    const uInt chunk = static_cast<uInt>(std::min<size_t>(size, 1u << 30));
    crc = crc32(crc, data, chunk);
    data += chunk;
    size -= chunk;
  }
  return static_cast<uint32_t>(crc);
}

}  // namespace

int HammingDistance(const uint8_t* a, const uint8_t* b) {
  int distance = 0;
  for (int i = 0; i < 32; i += 8) {
    uint64_t wa;
    uint64_t wb;
    std::memcpy(&wa, a + i, 8);
    std::memcpy(&wb, b + i, 8);
    distance += __builtin_popcountll(wa ^ wb);
  }
  return distance;
}

Vocabulary::Vocabulary(int branching, int levels, std::vector<Node> nodes,
                       std::vector<OrbDescriptor> centres, std::vector<float> word_weights)
    : branching_(branching),
      levels_(levels),
      nodes_(std::move(nodes)),
      centres_(std::move(centres)),
      word_weights_(std::move(word_weights)) {}

int Vocabulary::WordOf(const uint8_t* descriptor, int node_level, uint32_t* node_at_level) const {
  assert(!nodes_.empty());
  uint32_t node = 0;
  int level = 0;
  if (node_at_level != nullptr) *node_at_level = 0;
  while (nodes_[node].word < 0) {
    const Node& parent = nodes_[node];
    uint32_t best = parent.first_child;
    int best_distance = std::numeric_limits<int>::max();
    for (uint32_t child = parent.first_child; child < parent.first_child + parent.num_children;
         ++child) {
      const int distance = HammingDistance(descriptor, centres_[child].data());
      if (distance < best_distance) {
        best_distance = distance;
        best = child;
      }
    }
    node = best;
    ++level;
    if (node_at_level != nullptr && level <= node_level) *node_at_level = node;
  }
  return nodes_[node].word;
}

BowVector Vocabulary::Transform(const cv::Mat& descriptors, int node_level,
                                std::vector<uint32_t>* nodes) const {
  assert(descriptors.empty() || (descriptors.type() == CV_8UC1 && descriptors.cols == 32));
  BowVector vector;
  vector.reserve(descriptors.rows);
  if (nodes != nullptr) nodes->resize(descriptors.rows);
  for (int i = 0; i < descriptors.rows; ++i) {
    const int word = WordOf(descriptors.ptr<uint8_t>(i), node_level,
                            nodes != nullptr ? &(*nodes)[i] : nullptr);
    const float weight = word_weights_[word];
    // tf-idf: each occurrence adds the idf; the division by the image's feature count is the
    // same for all words and disappears in the L1 normalisation.
    if (weight > 0.0f) vector.emplace_back(static_cast<uint32_t>(word), weight);
  }
  NormalizeBowVector(&vector);
  return vector;
}

std::vector<uint8_t> Vocabulary::ToBytes() const {
  std::vector<uint8_t> out;
  out.reserve(kHeaderBytes + nodes_.size() * kNodeBytes + word_weights_.size() * 4 + 4);
  out.resize(sizeof(kMagic));
  std::memcpy(out.data(), kMagic, sizeof(kMagic));
  Put<uint32_t>(&out, kVersion);
  Put<uint32_t>(&out, static_cast<uint32_t>(branching_));
  Put<uint32_t>(&out, static_cast<uint32_t>(levels_));
  Put<uint32_t>(&out, static_cast<uint32_t>(nodes_.size()));
  Put<uint32_t>(&out, static_cast<uint32_t>(word_weights_.size()));
  for (size_t i = 0; i < nodes_.size(); ++i) {
    out.insert(out.end(), centres_[i].begin(), centres_[i].end());
    Put<uint32_t>(&out, nodes_[i].first_child);
    Put<uint32_t>(&out, nodes_[i].num_children);
    Put<int32_t>(&out, nodes_[i].word);
  }
  for (float weight : word_weights_) Put<float>(&out, weight);
  Put<uint32_t>(&out, Crc32(out.data(), out.size()));
  return out;
}

std::optional<Vocabulary> Vocabulary::FromBytes(const std::vector<uint8_t>& bytes,
                                                std::string* error) {
  if (bytes.size() < kHeaderBytes + 4 || std::memcmp(bytes.data(), kMagic, 8) != 0) {
    *error = "not a fusemap vocabulary (bad magic or shorter than its header)";
    return std::nullopt;
  }
  const uint8_t* p = bytes.data() + 8;
  const uint32_t version = Get<uint32_t>(p);
  if (version != kVersion) {
    *error = "unsupported vocabulary version " + std::to_string(version);
    return std::nullopt;
  }
  const uint32_t branching = Get<uint32_t>(p + 4);
  const uint32_t levels = Get<uint32_t>(p + 8);
  const uint64_t num_nodes = Get<uint32_t>(p + 12);
  const uint64_t num_words = Get<uint32_t>(p + 16);
  const uint64_t expected = kHeaderBytes + num_nodes * kNodeBytes + num_words * 4 + 4;
  if (bytes.size() != expected) {
    *error = "size " + std::to_string(bytes.size()) + " bytes, header implies " +
             std::to_string(expected) + " (truncated or corrupt)";
    return std::nullopt;
  }
  const uint32_t stored_crc = Get<uint32_t>(bytes.data() + bytes.size() - 4);
  if (Crc32(bytes.data(), bytes.size() - 4) != stored_crc) {
    *error = "CRC mismatch (corrupt file)";
    return std::nullopt;
  }
  std::vector<Node> nodes(num_nodes);
  std::vector<OrbDescriptor> centres(num_nodes);
  p = bytes.data() + kHeaderBytes;
  for (uint64_t i = 0; i < num_nodes; ++i, p += kNodeBytes) {
    std::memcpy(centres[i].data(), p, 32);
    nodes[i].first_child = Get<uint32_t>(p + 32);
    nodes[i].num_children = Get<uint32_t>(p + 36);
    nodes[i].word = Get<int32_t>(p + 40);
  }
  std::vector<float> weights(num_words);
  for (uint64_t i = 0; i < num_words; ++i, p += 4) weights[i] = Get<float>(p);
  Vocabulary vocabulary(static_cast<int>(branching), static_cast<int>(levels), std::move(nodes),
                        std::move(centres), std::move(weights));
  if (!vocabulary.IsConsistent(error)) return std::nullopt;
  return vocabulary;
}

bool Vocabulary::IsConsistent(std::string* error) const {
  if (branching_ < 2 || levels_ < 1 || nodes_.empty() || centres_.size() != nodes_.size()) {
    *error = "vocabulary: bad branching, levels or node table";
    return false;
  }
  std::vector<bool> word_seen(word_weights_.size(), false);
  for (size_t i = 0; i < nodes_.size(); ++i) {
    const Node& node = nodes_[i];
    if (node.word >= 0) {
      if (node.num_children != 0 || static_cast<size_t>(node.word) >= word_seen.size() ||
          word_seen[node.word]) {
        *error = "vocabulary: leaf " + std::to_string(i) + " has children or a bad word id";
        return false;
      }
      word_seen[node.word] = true;
      continue;
    }
    // Children come after their parent, so descending always ends at a leaf.
    if (node.num_children == 0 || node.first_child <= i ||
        static_cast<uint64_t>(node.first_child) + node.num_children > nodes_.size()) {
      *error = "vocabulary: inner node " + std::to_string(i) + " has a bad child range";
      return false;
    }
  }
  for (size_t w = 0; w < word_seen.size(); ++w) {
    if (!word_seen[w] || !(word_weights_[w] >= 0.0f)) {
      *error = "vocabulary: word " + std::to_string(w) + " has no leaf or a bad weight";
      return false;
    }
  }
  return true;
}

bool Vocabulary::Save(const std::string& path, std::string* error) const {
  const std::vector<uint8_t> bytes = ToBytes();
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!file) {
    *error = path + ": cannot write";
    return false;
  }
  return true;
}

std::optional<Vocabulary> Vocabulary::Load(const std::string& path, std::string* error) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    *error = path + ": cannot open";
    return std::nullopt;
  }
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                   std::istreambuf_iterator<char>());
  std::optional<Vocabulary> vocabulary = FromBytes(bytes, error);
  if (!vocabulary) *error = path + ": " + *error;
  return vocabulary;
}

}  // namespace visual_loop
}  // namespace fusemap
