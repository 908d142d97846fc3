// Vocabulary training: the tree's shape, determinism, and TF-IDF word weights.
#include "drvslam/tools/vocab/vocabulary_trainer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "drvslam/core/error.h"
#include "vocabulary_test_util.h"

namespace drvslam {
namespace {

VocabularyTrainerOptions SmallTree(int k, int levels) {
  VocabularyTrainerOptions options;
  options.branching_factor = k;
  options.depth = levels;
  return options;
}

TEST(VocabularyTrainerTest, SameInputGivesTheIdenticalTree) {
  const std::vector<cv::Mat> images = test::ClusteredImages(30, 40, 20, 8, 1);
  const BowVocabulary a = TrainVocabulary(images, SmallTree(5, 3));
  const BowVocabulary b = TrainVocabulary(images, SmallTree(5, 3));
  ASSERT_FALSE(a.Empty());
  EXPECT_TRUE(a == b);
  // The seed is what fixes it: another seed grows another tree.
  VocabularyTrainerOptions other = SmallTree(5, 3);
  other.seed = 12345;
  EXPECT_FALSE(a == TrainVocabulary(images, other));
}

TEST(VocabularyTrainerTest, TreeRespectsKAndLAndParentsPrecedeChildren) {
  const std::vector<cv::Mat> images = test::ClusteredImages(50, 30, 30, 10, 2);
  const BowVocabulary vocabulary = TrainVocabulary(images, SmallTree(4, 4));
  EXPECT_EQ(vocabulary.BranchingFactor(), 4);
  EXPECT_EQ(vocabulary.Depth(), 4);
  EXPECT_GT(vocabulary.WordCount(), 50u);
  EXPECT_LE(vocabulary.WordCount(), 256u);
  std::size_t words = 0;
  for (int node = 0; node < static_cast<int>(vocabulary.NodeCount()); ++node) {
    const std::vector<int> children = vocabulary.NodeChildren(node);
    EXPECT_LE(children.size(), 4u);
    EXPECT_LE(vocabulary.NodeLevel(node), 4);
    EXPECT_EQ(vocabulary.NodeIsLeaf(node), children.empty());
    for (int child : children) {
      EXPECT_GT(child, node);
      EXPECT_EQ(vocabulary.NodeParent(child), node);
      EXPECT_EQ(vocabulary.NodeLevel(child), vocabulary.NodeLevel(node) + 1);
    }
    // Siblings are numbered consecutively, DBoW2's layout.
    for (std::size_t c = 1; c < children.size(); ++c)
      EXPECT_EQ(children[c], children[0] + static_cast<int>(c));
    if (vocabulary.NodeIsLeaf(node)) {
      EXPECT_EQ(vocabulary.WordNode(vocabulary.NodeWord(node)), node);
      ++words;
    }
  }
  EXPECT_EQ(words, vocabulary.WordCount());
}

TEST(VocabularyTrainerTest, IdenticalDescriptorsStopSplittingEarly) {
  // Two distinct descriptors, 10 copies each: two words right under the root, however deep L.
  cv::Mat descriptors;
  for (int i = 0; i < 10; ++i) {
    descriptors.push_back(test::FilledRow(0x00));
    descriptors.push_back(test::FilledRow(0xFF));
  }
  const BowVocabulary vocabulary = TrainVocabulary({descriptors}, SmallTree(10, 6));
  EXPECT_EQ(vocabulary.WordCount(), 2u);
  EXPECT_EQ(vocabulary.NodeCount(), 3u);
  EXPECT_NE(vocabulary.Transform(test::FilledRow(0x00)),
            vocabulary.Transform(test::FilledRow(0xFF)));
}

TEST(VocabularyTrainerTest, TrainingDescriptorsLandNearTheirWord) {
  // Clusters far apart relative to their spread: each training descriptor's word centre must be
  // closer to it than to any other cluster's prototype (>= ~100 bits away).
  const std::vector<cv::Mat> images = test::ClusteredImages(8, 50, 8, 4, 3);
  const BowVocabulary vocabulary = TrainVocabulary(images, SmallTree(8, 2));
  for (const cv::Mat& image : images) {
    for (int r = 0; r < image.rows; ++r) {
      const int word = vocabulary.Transform(image.row(r));
      const PackedDescriptor centre =
          PackDescriptor(vocabulary.NodeDescriptor(vocabulary.WordNode(word)));
      EXPECT_LE(HammingDistance(centre, PackDescriptor(image.ptr<uint8_t>(r))), 16);
    }
  }
}

TEST(VocabularyTrainerTest, IdfIsLogOfImagesOverImagesWithTheWord) {
  BowVocabulary vocabulary = test::TinyVocabulary();
  // Word 0 (0x00) in all four non-empty images, word 1 (0x01) in two, word 2 (0xFE) in one,
  // word 3 (0xFF) in none; the empty image does not count.
  std::vector<cv::Mat> images(5);
  images[0].push_back(test::FilledRow(0x00));
  images[0].push_back(test::FilledRow(0x00));
  images[0].push_back(test::FilledRow(0x01));
  images[1].push_back(test::FilledRow(0x00));
  images[1].push_back(test::FilledRow(0x01));
  images[1].push_back(test::FilledRow(0xFE));
  images[2].push_back(test::FilledRow(0x00));
  images[4].push_back(test::FilledRow(0x00));
  ComputeIdfWeights(images, &vocabulary);
  EXPECT_DOUBLE_EQ(vocabulary.WordWeight(0), 0.0);
  EXPECT_DOUBLE_EQ(vocabulary.WordWeight(1), std::log(4.0 / 2.0));
  EXPECT_DOUBLE_EQ(vocabulary.WordWeight(2), std::log(4.0 / 1.0));
  // Never seen: as rare as a word seen once.
  EXPECT_DOUBLE_EQ(vocabulary.WordWeight(3), std::log(4.0));
}

TEST(VocabularyTrainerTest, TrainedWeightsAreIdfOfTheTrainingImages) {
  const std::vector<cv::Mat> images = test::ClusteredImages(20, 20, 16, 6, 4);
  const BowVocabulary vocabulary = TrainVocabulary(images, SmallTree(6, 2));
  std::vector<int> seen(vocabulary.WordCount(), 0);
  for (const cv::Mat& image : images) {
    std::vector<bool> in_image(vocabulary.WordCount(), false);
    for (int r = 0; r < image.rows; ++r) in_image[vocabulary.Transform(image.row(r))] = true;
    for (std::size_t w = 0; w < in_image.size(); ++w) seen[w] += in_image[w] ? 1 : 0;
  }
  for (std::size_t w = 0; w < seen.size(); ++w) {
    const double expected = std::log(6.0 / std::max(seen[w], 1));
    EXPECT_DOUBLE_EQ(vocabulary.WordWeight(static_cast<int>(w)), expected) << "word " << w;
  }
}

TEST(VocabularyTrainerTest, RejectsBadOptionsAndInputs) {
  const std::vector<cv::Mat> images = test::ClusteredImages(5, 5, 5, 2, 5);
  EXPECT_THROW(TrainVocabulary(images, SmallTree(1, 3)), Error);
  EXPECT_THROW(TrainVocabulary(images, SmallTree(10, 0)), Error);
  EXPECT_THROW(TrainVocabulary(images, SmallTree(10, 17)), Error);
  VocabularyTrainerOptions no_iterations = SmallTree(4, 2);
  no_iterations.max_iterations = 0;
  EXPECT_THROW(TrainVocabulary(images, no_iterations), Error);
  EXPECT_THROW(TrainVocabulary({cv::Mat(), cv::Mat()}, SmallTree(4, 2)), Error);
  EXPECT_THROW(TrainVocabulary({cv::Mat(3, 32, CV_32FC1)}, SmallTree(4, 2)), Error);
  EXPECT_THROW(TrainVocabulary({cv::Mat(3, 31, CV_8UC1)}, SmallTree(4, 2)), Error);
}

}  // namespace
}  // namespace drvslam
