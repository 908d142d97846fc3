// Reading and writing BowVocabulary files. Two formats:
//  - text: DBoW2's, as ORB-SLAM2's ORBvoc.txt uses it. Line 1 "k L scoring weighting"; then one
//    node per line, "parent_id is_leaf d0 ... d31 weight", node ids implicit (1, 2, ... in line
//    order, the root being 0), descriptor bytes as decimal numbers. Only scoring 0 (L1 norm)
//    and weighting 0 (TF-IDF) are accepted.
//  - binary: drvslam's own, for fast start-up. Little-endian: the 8 bytes "DRVSBOW\0", uint32
//    version (1), uint32 k, L, scoring, weighting, uint64 node count (without the root), then
//    per node uint32 parent, uint8 is_leaf, 32 descriptor bytes, float64 weight.
// Every problem with a file (missing, truncated, bad header or number, a parent out of range,
// a broken tree, wrong magic or version) throws drvslam::Error naming the file and the line or
// byte offset.
#pragma once

#include <string>

#include "drvslam/loop/bow_vocabulary.h"

namespace drvslam {

enum class VocabularyFormat { kText, kBinary };

// "text" or "binary"; throws drvslam::Error otherwise.
VocabularyFormat ParseVocabularyFormat(const std::string& name);
const char* VocabularyFormatName(VocabularyFormat format);

BowVocabulary ReadTextVocabulary(const std::string& path);
BowVocabulary ReadBinaryVocabulary(const std::string& path);
// Binary when the file starts with the binary magic, text otherwise. Throws drvslam::Error when
// the file cannot be opened.
VocabularyFormat DetectVocabularyFormat(const std::string& path);
// Reads the file in its detected format.
BowVocabulary LoadVocabulary(const std::string& path);

// Weights are written in their shortest exact decimal form, so a text round trip is lossless.
void WriteTextVocabulary(const BowVocabulary& vocabulary, const std::string& path);
void WriteBinaryVocabulary(const BowVocabulary& vocabulary, const std::string& path);
void WriteVocabulary(const BowVocabulary& vocabulary, const std::string& path,
                     VocabularyFormat format);

}  // namespace drvslam
