// VocabularyBuilder: assembles a BowVocabulary node by node and checks that the nodes form a
// valid tree, so the text and binary readers and the trainer share one set of rules and every
// reader error can name the line or byte offset of the offending node.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "drvslam/loop/bow_vocabulary.h"

namespace drvslam {

class VocabularyBuilder {
 public:
  // source: what errors name (a file path). where: the location of k and L in it (e.g.
  // "line 1"). Throws drvslam::Error when k or L is out of BowVocabulary's limits.
  VocabularyBuilder(int branching_factor, int depth, std::string source, const std::string& where);

  void Reserve(std::size_t nodes);

  // Appends node number NodeCount() (the root, 0, exists from the start). unit/position say
  // where it came from ("line", 17) for error messages. Throws drvslam::Error when the parent
  // does not exist yet or is a leaf, already has k children, the node would sit deeper than
  // L, or the weight is negative or not finite. Returns the new node's id.
  int AddNode(int parent, bool is_leaf, const uint8_t* descriptor, double weight, const char* unit,
              int64_t position);

  std::size_t NodeCount() const { return vocabulary_.parent_.size(); }

  // Checks that every inner node has a child and that there is at least one word, then hands
  // the tree over (the builder is left empty). Words are numbered in node-id order.
  BowVocabulary Finish();

 private:
  [[noreturn]] void Fail(const char* unit, int64_t position, const std::string& problem) const;

  BowVocabulary vocabulary_;
  std::string source_;
  std::vector<uint8_t> is_leaf_;
  std::vector<int> child_count_;
  std::vector<int64_t> position_;
  std::string unit_ = "node";
};

}  // namespace drvslam
