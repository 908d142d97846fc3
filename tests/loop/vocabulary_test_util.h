// Inputs shared by the vocabulary tests: random and clustered ORB-like descriptors, a small
// hand-built vocabulary, and a scratch folder.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <random>
#include <string>
#include <vector>

#include "drvslam/loop/bow_vocabulary.h"
#include "drvslam/loop/vocabulary_builder.h"
#include "test_support/temp_folder.h"

namespace drvslam::test {

// N x 32 CV_8UC1 of uniformly random bytes.
inline cv::Mat RandomDescriptors(int rows, uint64_t seed) {
  std::mt19937_64 rng(seed);
  cv::Mat descriptors(rows, 32, CV_8UC1);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < 32; ++c) descriptors.at<uint8_t>(r, c) = static_cast<uint8_t>(rng());
  }
  return descriptors;
}

// `prototype` with `flips` distinct random bits inverted.
inline cv::Mat FlipBits(const cv::Mat& prototype, int flips, std::mt19937_64* rng) {
  cv::Mat noisy = prototype.clone();
  std::vector<int> bits(256);
  for (int i = 0; i < 256; ++i) bits[i] = i;
  for (int i = 0; i < flips; ++i) {
    const int j = i + static_cast<int>((*rng)() % (256 - i));
    std::swap(bits[i], bits[j]);
    noisy.at<uint8_t>(0, bits[i] / 8) ^= static_cast<uint8_t>(1u << (bits[i] % 8));
  }
  return noisy;
}

// Descriptors scattered around `clusters` random prototypes (up to max_flips bits each), split
// over `images` images round-robin.
inline std::vector<cv::Mat> ClusteredImages(int clusters, int per_cluster, int max_flips,
                                            int images, uint64_t seed) {
  std::mt19937_64 rng(seed);
  const cv::Mat prototypes = RandomDescriptors(clusters, seed + 1);
  std::vector<cv::Mat> result(images);
  int next = 0;
  for (int c = 0; c < clusters; ++c) {
    for (int i = 0; i < per_cluster; ++i) {
      const int flips = static_cast<int>(rng() % (max_flips + 1));
      result[next++ % images].push_back(FlipBits(prototypes.row(c), flips, &rng));
    }
  }
  return result;
}

// A descriptor whose 32 bytes all equal `value`.
inline std::vector<uint8_t> Filled(uint8_t value) { return std::vector<uint8_t>(32, value); }

inline cv::Mat FilledRow(uint8_t value) { return cv::Mat(1, 32, CV_8UC1, cv::Scalar(value)); }

// k = 2, L = 2, every byte of a node's descriptor equal: root -> a (0x00), b (0xFF); a -> a0
// (0x00), a1 (0x01); b -> b0 (0xFE), b1 (0xFF). Words in node order: a0 = 0, a1 = 1, b0 = 2,
// b1 = 3 (nodes 3..6), weights 1, 2, 3, 4.
inline BowVocabulary TinyVocabulary() {
  VocabularyBuilder builder(2, 2, "tiny", "header");
  const int a = builder.AddNode(0, false, Filled(0x00).data(), 0.0, "node", 1);
  const int b = builder.AddNode(0, false, Filled(0xFF).data(), 0.0, "node", 2);
  builder.AddNode(a, true, Filled(0x00).data(), 1.0, "node", 3);
  builder.AddNode(a, true, Filled(0x01).data(), 2.0, "node", 4);
  builder.AddNode(b, true, Filled(0xFE).data(), 3.0, "node", 5);
  builder.AddNode(b, true, Filled(0xFF).data(), 4.0, "node", 6);
  return builder.Finish();
}

// An empty folder in this process's own temporary folder (testing::ProcessTempFolder, removed
// when the process ends): never one another run or user holds.
inline std::string ScratchFolder(const std::string& name) {
  const std::filesystem::path folder = drvslam::testing::ProcessTempFolder() / ("loop_" + name);
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder.string();
}

inline void WriteText(const std::string& path, const std::string& text) {
  std::ofstream file(path, std::ios::binary);
  file << text;
}

}  // namespace drvslam::test
