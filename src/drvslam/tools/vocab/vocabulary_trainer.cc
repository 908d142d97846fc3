#include "drvslam/tools/vocab/vocabulary_trainer.h"

#include <climits>
#include <cmath>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/loop/vocabulary_builder.h"

namespace drvslam {
namespace {

constexpr int kBits = 256;

void CheckDescriptorMatrix(const cv::Mat& descriptors, std::size_t image) {
  if (descriptors.empty()) return;
  if (descriptors.type() != CV_8UC1 || descriptors.cols != 32) {
    throw Error("vocabulary training: descriptors of image " + std::to_string(image) +
                " must be N x 32 CV_8UC1, got " + std::to_string(descriptors.rows) + "x" +
                std::to_string(descriptors.cols) + " of type " +
                std::to_string(descriptors.type()));
  }
}

// A uniform double in [0, 1) from the generator's raw output, so the draw is the same with
// every standard library (std::uniform_real_distribution is not specified bit for bit).
double Uniform01(std::mt19937_64* rng) { return static_cast<double>((*rng)() >> 11) * 0x1.0p-53; }

std::vector<PackedDescriptor> SeedCentres(const std::vector<PackedDescriptor>& data,
                                          const std::vector<uint32_t>& members, int k,
                                          std::mt19937_64* rng) {
  const std::size_t n = members.size();
  std::vector<PackedDescriptor> centres;
  centres.push_back(data[members[(*rng)() % n]]);
  std::vector<int> nearest(n, INT_MAX);
  while (static_cast<int>(centres.size()) < k) {
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const int distance = HammingDistance(data[members[i]], centres.back());
      if (distance < nearest[i]) nearest[i] = distance;
      total += static_cast<double>(nearest[i]) * nearest[i];
    }
    // Every descriptor already equals a centre: no new one can be told apart.
    if (total <= 0.0) break;
    const double threshold = Uniform01(rng) * total;
    double cumulative = 0.0;
    std::size_t chosen = n;
    for (std::size_t i = 0; i < n; ++i) {
      if (nearest[i] == 0) continue;
      cumulative += static_cast<double>(nearest[i]) * nearest[i];
      chosen = i;
      if (cumulative > threshold) break;
    }
    centres.push_back(data[members[chosen]]);
  }
  return centres;
}

// Nearest centre of every member; true when any label changed.
bool Assign(const std::vector<PackedDescriptor>& data, const std::vector<uint32_t>& members,
            const std::vector<PackedDescriptor>& centres, std::vector<int>* labels) {
  bool changed = false;
  const int k = static_cast<int>(centres.size());
  for (std::size_t i = 0; i < members.size(); ++i) {
    const PackedDescriptor& d = data[members[i]];
    int best = 0;
    int best_distance = HammingDistance(d, centres[0]);
    for (int c = 1; c < k; ++c) {
      const int distance = HammingDistance(d, centres[c]);
      if (distance < best_distance) {
        best_distance = distance;
        best = c;
      }
    }
    if ((*labels)[i] != best) {
      (*labels)[i] = best;
      changed = true;
    }
  }
  return changed;
}

// Per-bit majority of each centre's members; a centre without members keeps its value.
void UpdateCentres(const std::vector<PackedDescriptor>& data, const std::vector<uint32_t>& members,
                   const std::vector<int>& labels, std::vector<PackedDescriptor>* centres) {
  const std::size_t k = centres->size();
  std::vector<int> counts(k * kBits, 0);
  std::vector<int> sizes(k, 0);
  for (std::size_t i = 0; i < members.size(); ++i) {
    const int c = labels[i];
    ++sizes[c];
    int* count = &counts[c * kBits];
    const PackedDescriptor& d = data[members[i]];
    for (int w = 0; w < 4; ++w) {
      uint64_t bits = d[w];
      while (bits != 0) {
        ++count[w * 64 + __builtin_ctzll(bits)];
        bits &= bits - 1;
      }
    }
  }
  for (std::size_t c = 0; c < k; ++c) {
    if (sizes[c] == 0) continue;
    PackedDescriptor centre{};
    for (int bit = 0; bit < kBits; ++bit) {
      if (2 * counts[c * kBits + bit] > sizes[c]) centre[bit / 64] |= uint64_t{1} << (bit % 64);
    }
    (*centres)[c] = centre;
  }
}

bool AllEqual(const std::vector<PackedDescriptor>& data, const std::vector<uint32_t>& members) {
  for (uint32_t member : members) {
    if (data[member] != data[members.front()]) return false;
  }
  return true;
}

struct TrainingNode {
  int parent;
  PackedDescriptor centre;
  bool is_leaf;
};

class TreeGrower {
 public:
  TreeGrower(const std::vector<PackedDescriptor>& data, const VocabularyTrainerOptions& options)
      : data_(data), options_(options), rng_(options.seed) {
    nodes_.push_back({-1, PackedDescriptor{}, false});
  }

  // Clusters the members of `node` into its children at `level`, then each child's members.
  void Split(int node, const std::vector<uint32_t>& members, int level) {
    const KMediansResult clusters =
        KMediansCluster(data_, members, options_.branching_factor, options_.max_iterations, &rng_);
    const int first_child = static_cast<int>(nodes_.size());
    const int child_count = static_cast<int>(clusters.centres.size());
    for (const PackedDescriptor& centre : clusters.centres) {
      nodes_.push_back({node, centre, true});
    }
    std::vector<std::vector<uint32_t>> groups(child_count);
    for (std::size_t i = 0; i < members.size(); ++i) {
      groups[clusters.labels[i]].push_back(members[i]);
    }
    for (int c = 0; c < child_count; ++c) {
      if (level < options_.depth && !AllEqual(data_, groups[c])) {
        nodes_[first_child + c].is_leaf = false;
        Split(first_child + c, groups[c], level + 1);
      }
      std::vector<uint32_t>().swap(groups[c]);
    }
  }

  const std::vector<TrainingNode>& Nodes() const { return nodes_; }

 private:
  const std::vector<PackedDescriptor>& data_;
  const VocabularyTrainerOptions& options_;
  std::mt19937_64 rng_;
  std::vector<TrainingNode> nodes_;
};

}  // namespace

void VocabularyTrainerOptions::Check() const {
  if (branching_factor < BowVocabulary::kMinBranchingFactor ||
      branching_factor > BowVocabulary::kMaxBranchingFactor) {
    throw Error("vocabulary training: k = " + std::to_string(branching_factor) + " out of range [" +
                std::to_string(BowVocabulary::kMinBranchingFactor) + ", " +
                std::to_string(BowVocabulary::kMaxBranchingFactor) + "]");
  }
  if (depth < 1 || depth > BowVocabulary::kMaxDepth) {
    throw Error("vocabulary training: levels L = " + std::to_string(depth) + " out of range [1, " +
                std::to_string(BowVocabulary::kMaxDepth) + "]");
  }
  if (max_iterations < 1) {
    throw Error("vocabulary training: max_iterations = " + std::to_string(max_iterations) +
                " must be >= 1");
  }
}

KMediansResult KMediansCluster(const std::vector<PackedDescriptor>& data,
                               const std::vector<uint32_t>& members, int k, int max_iterations,
                               std::mt19937_64* rng) {
  if (k < 1) throw Error("KMediansCluster: k = " + std::to_string(k) + " must be >= 1");
  if (members.empty()) throw Error("KMediansCluster: no members to cluster");
  if (rng == nullptr) throw Error("KMediansCluster: null random generator");
  for (uint32_t member : members) {
    if (member >= data.size()) {
      throw Error("KMediansCluster: member index " + std::to_string(member) + " out of range [0, " +
                  std::to_string(data.size()) + ")");
    }
  }
  KMediansResult result;
  result.centres = SeedCentres(data, members, k, rng);
  result.labels.assign(members.size(), -1);
  // Assignment comes last, so every label names its nearest centre.
  for (int round = 1;; ++round) {
    result.iterations = round;
    const bool changed = Assign(data, members, result.centres, &result.labels);
    if (!changed || round >= max_iterations) break;
    UpdateCentres(data, members, result.labels, &result.centres);
  }
  // Drop centres that lost all their members, keeping the others' order.
  std::vector<int> sizes(result.centres.size(), 0);
  for (int label : result.labels) ++sizes[label];
  std::vector<int> remap(result.centres.size(), -1);
  std::vector<PackedDescriptor> kept;
  for (std::size_t c = 0; c < result.centres.size(); ++c) {
    if (sizes[c] == 0) continue;
    remap[c] = static_cast<int>(kept.size());
    kept.push_back(result.centres[c]);
  }
  if (kept.size() != result.centres.size()) {
    for (int& label : result.labels) label = remap[label];
    result.centres = std::move(kept);
  }
  return result;
}

BowVocabulary TrainVocabulary(const std::vector<cv::Mat>& image_descriptors,
                              const VocabularyTrainerOptions& options) {
  options.Check();
  std::vector<PackedDescriptor> data;
  std::size_t total = 0;
  for (std::size_t image = 0; image < image_descriptors.size(); ++image) {
    CheckDescriptorMatrix(image_descriptors[image], image);
    total += image_descriptors[image].empty() ? 0 : image_descriptors[image].rows;
  }
  if (total == 0) throw Error("vocabulary training: no descriptors to train on");
  if (total > UINT32_MAX) throw Error("vocabulary training: too many descriptors");
  data.reserve(total);
  for (const cv::Mat& descriptors : image_descriptors) {
    for (int row = 0; row < (descriptors.empty() ? 0 : descriptors.rows); ++row) {
      data.push_back(PackDescriptor(descriptors.ptr<uint8_t>(row)));
    }
  }
  std::vector<uint32_t> members(data.size());
  for (std::size_t i = 0; i < members.size(); ++i) members[i] = static_cast<uint32_t>(i);

  TreeGrower grower(data, options);
  grower.Split(0, members, 1);
  std::vector<uint32_t>().swap(members);

  const std::vector<TrainingNode>& nodes = grower.Nodes();
  VocabularyBuilder builder(options.branching_factor, options.depth, "vocabulary training",
                            "options");
  builder.Reserve(nodes.size());
  uint8_t bytes[32];
  for (std::size_t id = 1; id < nodes.size(); ++id) {
    UnpackDescriptor(nodes[id].centre, bytes);
    builder.AddNode(nodes[id].parent, nodes[id].is_leaf, bytes, 0.0, "node",
                    static_cast<int64_t>(id));
  }
  BowVocabulary vocabulary = builder.Finish();
  ComputeIdfWeights(image_descriptors, &vocabulary);
  return vocabulary;
}

void ComputeIdfWeights(const std::vector<cv::Mat>& image_descriptors, BowVocabulary* vocabulary) {
  if (vocabulary == nullptr) throw Error("ComputeIdfWeights: null vocabulary");
  if (vocabulary->Empty()) throw Error("ComputeIdfWeights: the vocabulary is empty");
  const std::size_t words = vocabulary->WordCount();
  std::vector<int> images_with_word(words, 0);
  // The last image that counted each word, so a word counts once per image.
  std::vector<int> last_image(words, -1);
  int images = 0;
  for (std::size_t image = 0; image < image_descriptors.size(); ++image) {
    const cv::Mat& descriptors = image_descriptors[image];
    CheckDescriptorMatrix(descriptors, image);
    if (descriptors.empty() || descriptors.rows == 0) continue;
    for (int row = 0; row < descriptors.rows; ++row) {
      const int word = vocabulary->Transform(descriptors.ptr<uint8_t>(row));
      if (last_image[word] != images) {
        last_image[word] = images;
        ++images_with_word[word];
      }
    }
    ++images;
  }
  std::vector<double> weights(words, 0.0);
  for (std::size_t word = 0; word < words; ++word) {
    const int seen = images_with_word[word] > 0 ? images_with_word[word] : 1;
    weights[word] = images > 0 ? std::log(static_cast<double>(images) / seen) : 0.0;
  }
  vocabulary->SetWordWeights(weights);
}

}  // namespace drvslam
