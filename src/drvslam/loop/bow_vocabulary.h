// BowVocabulary: a hierarchical bag-of-words vocabulary for 256-bit ORB descriptors (the DBoW2
// model ORB-SLAM uses for place recognition). A k-ary tree of binary cluster centres: a
// descriptor descends to the nearest child at every level until it reaches a leaf, its word.
// Words carry TF-IDF weights; images compare by DBoW2's L1 score. Built by VocabularyBuilder
// (from a file or the trainer); immutable afterwards apart from the word weights, so one
// instance can be shared by every thread without locking.
#pragma once

#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/loop/bow_vector.h"
#include "drvslam/loop/packed_descriptor.h"

namespace drvslam {

class BowVocabulary {
 public:
  // DBoW2's codes for the one scoring (L1 norm) and weighting (TF-IDF) supported.
  static constexpr int kL1Scoring = 0;
  static constexpr int kTfIdfWeighting = 0;
  // Limits on the header values a file may carry.
  static constexpr int kMinBranchingFactor = 2;
  static constexpr int kMaxBranchingFactor = 256;
  static constexpr int kMaxDepth = 16;

  // An empty vocabulary: no words; Transform throws drvslam::Error.
  BowVocabulary() = default;

  bool Empty() const { return word_node_.empty(); }
  // k: the most children a node may have.
  int BranchingFactor() const { return branching_factor_; }
  // L: the deepest level a word may sit at (the root is level 0). Words may sit higher where
  // training data ran out.
  int Depth() const { return depth_; }
  std::size_t WordCount() const { return word_node_.size(); }
  // Including the root.
  std::size_t NodeCount() const { return parent_.size(); }

  // The word a descriptor falls into: at every level the child at the smallest Hamming
  // distance, the first such child on ties. descriptor_row: 1x32 CV_8UC1; anything else throws.
  int Transform(const cv::Mat& descriptor_row) const;
  int Transform(const uint8_t* descriptor) const;
  // The same, also giving the node the descriptor passes at `direct_index_level` (0 = root,
  // Depth() = the words; where the word sits higher, the word's node).
  int Transform(const uint8_t* descriptor, int direct_index_level, int* node_at_level) const;

  // The bag of words of an image's descriptors (N x 32 CV_8UC1; N = 0 gives empty outputs):
  // the sum of the word weights of its features, L1-normalised. Features whose word has weight
  // 0 (seen in every training image) are left out of both outputs, as DBoW2 does. `features`
  // may be null; otherwise it groups the feature rows by their node at `direct_index_level`
  // (0..Depth()). Throws drvslam::Error on an empty vocabulary, a bad descriptor matrix or
  // level.
  void Transform(const cv::Mat& descriptors, BowVector* bow, FeatureVector* features,
                 int direct_index_level) const;

  // DBoW2's L1 score, 1 - 0.5 * |a/|a|_1 - b/|b|_1|_1, in [0, 1]: 1 for proportional vectors,
  // 0 when they share no word or either is empty.
  static double Score(const BowVector& a, const BowVector& b);

  // The word's TF-IDF weight (idf = log(N / n_i) from training). Throws on an invalid word.
  double WordWeight(int word) const;
  // Replaces every word weight (one per word, finite, >= 0); throws drvslam::Error otherwise.
  void SetWordWeights(const std::vector<double>& weights);

  // The tree, for writers, tools and tests. Node ids run 0 (root) .. NodeCount() - 1; a parent
  // always has a smaller id than its children. Invalid ids throw drvslam::Error.
  int NodeParent(int node) const;  // -1 for the root
  bool NodeIsLeaf(int node) const;
  int NodeLevel(int node) const;
  // The node's 32 descriptor bytes (all zero for the root).
  const uint8_t* NodeDescriptor(int node) const;
  // For a word's node its weight; inner nodes keep whatever their file said (DBoW2 writes 0).
  double NodeWeight(int node) const;
  std::vector<int> NodeChildren(int node) const;
  int NodeWord(int node) const;  // -1 for inner nodes
  int WordNode(int word) const;

  // Same shape, nodes, descriptors and weights (weights compared exactly).
  bool operator==(const BowVocabulary& other) const;
  bool operator!=(const BowVocabulary& other) const { return !(*this == other); }

 private:
  friend class VocabularyBuilder;

  void CheckNode(int node) const;
  void CheckWord(int word) const;

  int branching_factor_ = 0;
  int depth_ = 0;
  // Per node, indexed by node id.
  std::vector<PackedDescriptor> descriptors_;
  std::vector<int> parent_;
  std::vector<uint8_t> level_;
  std::vector<double> weight_;
  std::vector<int> node_word_;
  // Children of node n: children_[child_begin_[n] .. child_begin_[n + 1]), in id order.
  std::vector<int> child_begin_;
  std::vector<int> children_;
  // Per word: its node.
  std::vector<int> word_node_;
};

}  // namespace drvslam
