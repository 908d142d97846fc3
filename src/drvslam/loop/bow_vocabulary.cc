#include "drvslam/loop/bow_vocabulary.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

constexpr int kDescriptorBytes = static_cast<int>(sizeof(PackedDescriptor));

void CheckDescriptorMatrix(const cv::Mat& descriptors, const char* what) {
  if (descriptors.type() != CV_8UC1 || descriptors.cols != kDescriptorBytes) {
    throw Error(std::string("BowVocabulary::Transform: ") + what +
                " must be N x 32 CV_8UC1 rows, got " + std::to_string(descriptors.rows) + "x" +
                std::to_string(descriptors.cols) + " of type " +
                std::to_string(descriptors.type()));
  }
}

// The tree arrays the descent reads.
struct TreeView {
  const int* child_begin;
  const int* children;
  const PackedDescriptor* centres;
};

// From the root to a leaf, at each level to the nearest child (the first on ties); returns the
// leaf and sets *at_level to the node passed at `level` (the leaf when it sits higher).
// `distance` is inlined into each caller, so each caller's instruction set applies to it.
template <typename Distance>
inline __attribute__((always_inline)) int Descend(const TreeView& tree,
                                                  const PackedDescriptor& query, int level,
                                                  int* at_level, Distance distance) {
  int node = 0;
  int depth = 0;
  while (tree.child_begin[node] != tree.child_begin[node + 1]) {
    const int* child = tree.children + tree.child_begin[node];
    const int* const end = tree.children + tree.child_begin[node + 1];
    int best = *child;
    int best_distance = distance(query, tree.centres[best]);
    for (++child; child != end; ++child) {
      const int d = distance(query, tree.centres[*child]);
      if (d < best_distance) {
        best_distance = d;
        best = *child;
      }
    }
    node = best;
    ++depth;
    if (depth <= level) *at_level = node;
  }
  return node;
}

int DescendPortable(const TreeView& tree, const PackedDescriptor& query, int level, int* at_level) {
  return Descend(tree, query, level, at_level, HammingDistance);
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define DRVSLAM_HAVE_POPCNT_DISPATCH 1
// The same descent with the popcnt instruction, about twice as fast; chosen at run time so the
// build needs no -mpopcnt and still runs on any x86-64.
__attribute__((target("popcnt"))) int DescendWithPopcnt(const TreeView& tree,
                                                        const PackedDescriptor& query, int level,
                                                        int* at_level) {
  return Descend(tree, query, level, at_level,
                 [](const PackedDescriptor& a, const PackedDescriptor& b) {
                   return __builtin_popcountll(a[0] ^ b[0]) + __builtin_popcountll(a[1] ^ b[1]) +
                          __builtin_popcountll(a[2] ^ b[2]) + __builtin_popcountll(a[3] ^ b[3]);
                 });
}
#else
#define DRVSLAM_HAVE_POPCNT_DISPATCH 0
#endif

}  // namespace

void BowVocabulary::CheckNode(int node) const {
  if (node < 0 || node >= static_cast<int>(parent_.size())) {
    throw Error("BowVocabulary: node id " + std::to_string(node) + " out of range [0, " +
                std::to_string(parent_.size()) + ")");
  }
}

void BowVocabulary::CheckWord(int word) const {
  if (word < 0 || word >= static_cast<int>(word_node_.size())) {
    throw Error("BowVocabulary: word id " + std::to_string(word) + " out of range [0, " +
                std::to_string(word_node_.size()) + ")");
  }
}

int BowVocabulary::Transform(const cv::Mat& descriptor_row) const {
  CheckDescriptorMatrix(descriptor_row, "descriptor_row");
  if (descriptor_row.rows != 1) {
    throw Error("BowVocabulary::Transform: descriptor_row must have 1 row, got " +
                std::to_string(descriptor_row.rows));
  }
  return Transform(descriptor_row.ptr<uint8_t>(0));
}

int BowVocabulary::Transform(const uint8_t* descriptor) const {
  int node_at_level = 0;
  return Transform(descriptor, 0, &node_at_level);
}

int BowVocabulary::Transform(const uint8_t* descriptor, int direct_index_level,
                             int* node_at_level) const {
  if (Empty()) throw Error("BowVocabulary::Transform: the vocabulary is empty");
  const TreeView tree{child_begin_.data(), children_.data(), descriptors_.data()};
  const PackedDescriptor query = PackDescriptor(descriptor);
  int at_level = 0;
#if DRVSLAM_HAVE_POPCNT_DISPATCH
  static const bool kHardwarePopcount = __builtin_cpu_supports("popcnt");
  const int leaf = kHardwarePopcount ? DescendWithPopcnt(tree, query, direct_index_level, &at_level)
                                     : DescendPortable(tree, query, direct_index_level, &at_level);
#else
  const int leaf = DescendPortable(tree, query, direct_index_level, &at_level);
#endif
  if (node_at_level != nullptr) *node_at_level = at_level;
  return node_word_[leaf];
}

void BowVocabulary::Transform(const cv::Mat& descriptors, BowVector* bow, FeatureVector* features,
                              int direct_index_level) const {
  if (bow == nullptr) throw Error("BowVocabulary::Transform: bow output is null");
  if (Empty()) throw Error("BowVocabulary::Transform: the vocabulary is empty");
  if (direct_index_level < 0 || direct_index_level > depth_) {
    throw Error("BowVocabulary::Transform: direct_index_level " +
                std::to_string(direct_index_level) + " out of range [0, " + std::to_string(depth_) +
                "]");
  }
  bow->clear();
  if (features != nullptr) features->clear();
  if (descriptors.empty()) return;
  CheckDescriptorMatrix(descriptors, "descriptors");
  // Sorted (key, row) pairs fill the maps in order with end hints: linear instead of a tree
  // search per feature.
  std::vector<std::pair<int, int>> words;
  std::vector<std::pair<int, unsigned>> nodes;
  words.reserve(descriptors.rows);
  if (features != nullptr) nodes.reserve(descriptors.rows);
  for (int row = 0; row < descriptors.rows; ++row) {
    int node_at_level = 0;
    const int word = Transform(descriptors.ptr<uint8_t>(row), direct_index_level, &node_at_level);
    if (weight_[word_node_[word]] <= 0.0) continue;
    words.emplace_back(word, row);
    if (features != nullptr) nodes.emplace_back(node_at_level, static_cast<unsigned>(row));
  }
  std::sort(words.begin(), words.end());
  for (const auto& [word, row] : words) {
    const double weight = weight_[word_node_[word]];
    if (!bow->empty() && bow->rbegin()->first == word) {
      bow->rbegin()->second += weight;
    } else {
      bow->emplace_hint(bow->end(), word, weight);
    }
  }
  if (features != nullptr) {
    std::sort(nodes.begin(), nodes.end());
    for (const auto& [node, row] : nodes) {
      if (features->empty() || features->rbegin()->first != node) {
        features->emplace_hint(features->end(), node, std::vector<unsigned>());
      }
      features->rbegin()->second.push_back(row);
    }
  }
  double sum = 0.0;
  for (const auto& entry : *bow) sum += entry.second;
  if (sum > 0.0) {
    for (auto& entry : *bow) entry.second /= sum;
  }
}

double BowVocabulary::Score(const BowVector& a, const BowVector& b) {
  double norm_a = 0.0;
  double norm_b = 0.0;
  for (const auto& entry : a) norm_a += std::abs(entry.second);
  for (const auto& entry : b) norm_b += std::abs(entry.second);
  if (norm_a <= 0.0 || norm_b <= 0.0) return 0.0;
  // Only shared words change the L1 distance from its maximum of 2:
  // |x - y| = |x| + |y| - (|x| + |y| - |x - y|), so 1 - 0.5 |a - b|_1 sums the brackets.
  double shared = 0.0;
  auto ia = a.begin();
  auto ib = b.begin();
  while (ia != a.end() && ib != b.end()) {
    if (ia->first < ib->first) {
      ++ia;
    } else if (ib->first < ia->first) {
      ++ib;
    } else {
      const double x = ia->second / norm_a;
      const double y = ib->second / norm_b;
      shared += std::abs(x) + std::abs(y) - std::abs(x - y);
      ++ia;
      ++ib;
    }
  }
  return 0.5 * shared;
}

double BowVocabulary::WordWeight(int word) const {
  CheckWord(word);
  return weight_[word_node_[word]];
}

void BowVocabulary::SetWordWeights(const std::vector<double>& weights) {
  if (weights.size() != word_node_.size()) {
    throw Error("BowVocabulary::SetWordWeights: " + std::to_string(weights.size()) +
                " weights for " + std::to_string(word_node_.size()) + " words");
  }
  for (std::size_t word = 0; word < weights.size(); ++word) {
    if (!std::isfinite(weights[word]) || weights[word] < 0.0) {
      throw Error("BowVocabulary::SetWordWeights: weight of word " + std::to_string(word) + " is " +
                  std::to_string(weights[word]) + ", must be finite and >= 0");
    }
  }
  for (std::size_t word = 0; word < weights.size(); ++word) {
    weight_[word_node_[word]] = weights[word];
  }
}

int BowVocabulary::NodeParent(int node) const {
  CheckNode(node);
  return parent_[node];
}

bool BowVocabulary::NodeIsLeaf(int node) const {
  CheckNode(node);
  return child_begin_[node] == child_begin_[node + 1];
}

int BowVocabulary::NodeLevel(int node) const {
  CheckNode(node);
  return level_[node];
}

const uint8_t* BowVocabulary::NodeDescriptor(int node) const {
  CheckNode(node);
  // Reading an object's bytes through an unsigned char pointer is well defined.
  return reinterpret_cast<const uint8_t*>(descriptors_[node].data());
}

double BowVocabulary::NodeWeight(int node) const {
  CheckNode(node);
  return weight_[node];
}

std::vector<int> BowVocabulary::NodeChildren(int node) const {
  CheckNode(node);
  return std::vector<int>(children_.begin() + child_begin_[node],
                          children_.begin() + child_begin_[node + 1]);
}

int BowVocabulary::NodeWord(int node) const {
  CheckNode(node);
  return node_word_[node];
}

int BowVocabulary::WordNode(int word) const {
  CheckWord(word);
  return word_node_[word];
}

bool BowVocabulary::operator==(const BowVocabulary& other) const {
  return branching_factor_ == other.branching_factor_ && depth_ == other.depth_ &&
         descriptors_ == other.descriptors_ && parent_ == other.parent_ &&
         weight_ == other.weight_ && child_begin_ == other.child_begin_ &&
         children_ == other.children_;
}

}  // namespace drvslam
