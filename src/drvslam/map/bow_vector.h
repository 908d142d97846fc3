// The bag-of-words representation of one image: which vocabulary words it contains and how
// strongly (BowVector), and which of its features fell under each node of a chosen tree level
// (FeatureVector, the "direct index" that restricts descriptor matching to features sharing a
// node). Ordered maps keep iteration, and hence every score and match, deterministic. They live
// in map/ because frames and keyframes carry them; the vocabulary that fills them is loop/'s.
#pragma once

#include <map>
#include <vector>

namespace drvslam {

// word id -> TF-IDF weight; BowVocabulary::Transform returns it L1-normalised.
using BowVector = std::map<int, double>;

// node id (at the direct-index level) -> indices of the descriptor rows under that node, in
// increasing order.
using FeatureVector = std::map<int, std::vector<unsigned>>;

}  // namespace drvslam
