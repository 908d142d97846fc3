// Training a BowVocabulary from ORB descriptors, as DBoW2 does: hierarchical binary k-medians
// (k-means++ seeding, per-bit majority centres) down to L levels, then TF-IDF word weights from
// the training images. A fixed seed makes training deterministic: the same descriptors in the
// same order give the identical tree on every run and platform.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "drvslam/loop/bow_vocabulary.h"
#include "drvslam/loop/packed_descriptor.h"

namespace drvslam {

struct VocabularyTrainerOptions {
  int branching_factor = 10;  // k
  int depth = 6;              // L
  // k-medians rounds per node; clustering usually settles well before.
  int max_iterations = 10;
  uint64_t seed = 5489;

  // Throws drvslam::Error naming the bad option.
  void Check() const;
};

struct KMediansResult {
  std::vector<PackedDescriptor> centres;
  // Per member (same order as the `members` argument): its centre, the nearest one (the first
  // on ties).
  std::vector<int> labels;
  int iterations = 0;
};

// Binary k-medians of the descriptors data[members[i]]. Seeds k centres k-means++-style (the
// first uniformly, each next with probability proportional to its squared Hamming distance to
// the nearest centre so far) drawing from `rng`, then alternates per-bit majority centres (ties
// give 0) and nearest-centre assignment until no label changes or `max_iterations` rounds.
// Gives fewer than k centres when there are fewer distinct descriptors; centres left without
// members are dropped. Throws drvslam::Error on k < 1, empty members or an index out of range.
KMediansResult KMediansCluster(const std::vector<PackedDescriptor>& data,
                               const std::vector<uint32_t>& members, int k, int max_iterations,
                               std::mt19937_64* rng);

// image_descriptors: one N x 32 CV_8UC1 matrix per training image (empty ones allowed). A node
// becomes a word when it reaches level L or all its descriptors are equal. Children are
// numbered consecutively and each subtree follows its parent's children, DBoW2's order. Throws
// drvslam::Error on bad options, a bad matrix or no descriptors at all.
BowVocabulary TrainVocabulary(const std::vector<cv::Mat>& image_descriptors,
                              const VocabularyTrainerOptions& options);

// Sets every word's weight to idf = log(N / n_i): N the number of non-empty images, n_i the
// number of them with a descriptor in word i. A word no image reaches gets log(N), as if seen
// once: rarer than any seen word, but finite.
void ComputeIdfWeights(const std::vector<cv::Mat>& image_descriptors, BowVocabulary* vocabulary);

}  // namespace drvslam
