#include "drvslam/loop/vocabulary_builder.h"

#include <climits>
#include <cmath>
#include <sstream>
#include <utility>

#include "drvslam/core/error.h"

namespace drvslam {

VocabularyBuilder::VocabularyBuilder(int branching_factor, int depth, std::string source,
                                     const std::string& where)
    : source_(std::move(source)) {
  if (branching_factor < BowVocabulary::kMinBranchingFactor ||
      branching_factor > BowVocabulary::kMaxBranchingFactor) {
    throw Error(source_ + ": " + where +
                ": branching factor k = " + std::to_string(branching_factor) + " out of range [" +
                std::to_string(BowVocabulary::kMinBranchingFactor) + ", " +
                std::to_string(BowVocabulary::kMaxBranchingFactor) + "]");
  }
  if (depth < 1 || depth > BowVocabulary::kMaxDepth) {
    throw Error(source_ + ": " + where + ": depth L = " + std::to_string(depth) +
                " out of range [1, " + std::to_string(BowVocabulary::kMaxDepth) + "]");
  }
  vocabulary_.branching_factor_ = branching_factor;
  vocabulary_.depth_ = depth;
  // The root: no descriptor, never a word.
  vocabulary_.descriptors_.push_back(PackedDescriptor{});
  vocabulary_.parent_.push_back(-1);
  vocabulary_.level_.push_back(0);
  vocabulary_.weight_.push_back(0.0);
  is_leaf_.push_back(0);
  child_count_.push_back(0);
  position_.push_back(0);
}

void VocabularyBuilder::Reserve(std::size_t nodes) {
  vocabulary_.descriptors_.reserve(nodes);
  vocabulary_.parent_.reserve(nodes);
  vocabulary_.level_.reserve(nodes);
  vocabulary_.weight_.reserve(nodes);
  is_leaf_.reserve(nodes);
  child_count_.reserve(nodes);
  position_.reserve(nodes);
}

void VocabularyBuilder::Fail(const char* unit, int64_t position, const std::string& problem) const {
  throw Error(source_ + ": " + unit + " " + std::to_string(position) + ": " + problem);
}

int VocabularyBuilder::AddNode(int parent, bool is_leaf, const uint8_t* descriptor, double weight,
                               const char* unit, int64_t position) {
  const int id = static_cast<int>(vocabulary_.parent_.size());
  if (id == INT_MAX) Fail(unit, position, "too many nodes");
  if (parent < 0 || parent >= id) {
    Fail(unit, position,
         "parent id " + std::to_string(parent) + " of node " + std::to_string(id) +
             " out of range [0, " + std::to_string(id) +
             ") (a parent must come before its children)");
  }
  if (is_leaf_[parent]) {
    Fail(unit, position,
         "parent id " + std::to_string(parent) + " of node " + std::to_string(id) + " is a leaf (" +
             unit_ + " " + std::to_string(position_[parent]) + ")");
  }
  if (child_count_[parent] >= vocabulary_.branching_factor_) {
    Fail(unit, position,
         "node " + std::to_string(parent) +
             " gets more than k = " + std::to_string(vocabulary_.branching_factor_) + " children");
  }
  const int level = vocabulary_.level_[parent] + 1;
  if (level > vocabulary_.depth_) {
    Fail(unit, position,
         "node " + std::to_string(id) + " sits at level " + std::to_string(level) +
             ", deeper than L = " + std::to_string(vocabulary_.depth_));
  }
  if (!std::isfinite(weight) || weight < 0.0) {
    std::ostringstream text;
    text << "weight " << weight << " of node " << id << " must be finite and >= 0";
    Fail(unit, position, text.str());
  }
  unit_ = unit;
  ++child_count_[parent];
  vocabulary_.descriptors_.push_back(PackDescriptor(descriptor));
  vocabulary_.parent_.push_back(parent);
  vocabulary_.level_.push_back(static_cast<uint8_t>(level));
  vocabulary_.weight_.push_back(weight);
  is_leaf_.push_back(is_leaf ? 1 : 0);
  child_count_.push_back(0);
  position_.push_back(position);
  return id;
}

BowVocabulary VocabularyBuilder::Finish() {
  BowVocabulary& v = vocabulary_;
  const int node_count = static_cast<int>(v.parent_.size());
  if (node_count == 1) throw Error(source_ + ": the vocabulary has no nodes");
  for (int node = 0; node < node_count; ++node) {
    if (!is_leaf_[node] && child_count_[node] == 0) {
      Fail(unit_.c_str(), position_[node],
           "node " + std::to_string(node) +
               " is marked as an inner node but no node names it as parent");
    }
  }
  v.child_begin_.assign(node_count + 1, 0);
  for (int node = 1; node < node_count; ++node) ++v.child_begin_[v.parent_[node] + 1];
  for (int node = 0; node < node_count; ++node) v.child_begin_[node + 1] += v.child_begin_[node];
  v.children_.assign(node_count - 1, 0);
  std::vector<int> next(v.child_begin_.begin(), v.child_begin_.end() - 1);
  for (int node = 1; node < node_count; ++node) v.children_[next[v.parent_[node]]++] = node;
  v.node_word_.assign(node_count, -1);
  v.word_node_.clear();
  for (int node = 1; node < node_count; ++node) {
    if (is_leaf_[node]) {
      v.node_word_[node] = static_cast<int>(v.word_node_.size());
      v.word_node_.push_back(node);
    }
  }
  BowVocabulary result = std::move(vocabulary_);
  vocabulary_ = BowVocabulary();
  is_leaf_.clear();
  child_count_.clear();
  position_.clear();
  return result;
}

}  // namespace drvslam
