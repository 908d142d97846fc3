// BowVocabulary::Transform: descriptors to words, bag-of-words vectors and the direct index.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/feature/descriptor_distance.h"
#include "drvslam/tools/vocab/vocabulary_trainer.h"
#include "vocabulary_test_util.h"

namespace drvslam {
namespace {

// Descends the tree the slow way, with the feature module's DescriptorDistance.
int BruteForceWord(const BowVocabulary& vocabulary, const cv::Mat& descriptor, int level,
                   int* node_at_level) {
  int node = 0;
  *node_at_level = 0;
  while (!vocabulary.NodeIsLeaf(node)) {
    int best = -1;
    int best_distance = 1000;
    for (int child : vocabulary.NodeChildren(node)) {
      const cv::Mat centre(1, 32, CV_8UC1, const_cast<uint8_t*>(vocabulary.NodeDescriptor(child)));
      const int distance = DescriptorDistance(descriptor, centre);
      if (distance < best_distance) {
        best_distance = distance;
        best = child;
      }
    }
    node = best;
    if (vocabulary.NodeLevel(node) <= level) *node_at_level = node;
  }
  return vocabulary.NodeWord(node);
}

BowVocabulary TrainedVocabulary() {
  VocabularyTrainerOptions options;
  options.branching_factor = 6;
  options.depth = 3;
  return TrainVocabulary(test::ClusteredImages(40, 25, 40, 8, 21), options);
}

TEST(BowTransformTest, DescriptorFollowsTheNearestChildPathToItsWord) {
  const BowVocabulary vocabulary = TrainedVocabulary();
  const cv::Mat queries = test::RandomDescriptors(300, 99);
  std::vector<cv::Mat> training = test::ClusteredImages(40, 25, 40, 8, 21);
  cv::Mat all = queries.clone();
  for (const cv::Mat& image : training) all.push_back(image);
  for (int r = 0; r < all.rows; ++r) {
    int expected_node = -1;
    const int expected = BruteForceWord(vocabulary, all.row(r), 2, &expected_node);
    EXPECT_EQ(vocabulary.Transform(all.row(r)), expected) << "row " << r;
    EXPECT_EQ(vocabulary.Transform(all.ptr<uint8_t>(r)), expected) << "row " << r;
    int node = -1;
    EXPECT_EQ(vocabulary.Transform(all.ptr<uint8_t>(r), 2, &node), expected);
    EXPECT_EQ(node, expected_node) << "row " << r;
  }
}

TEST(BowTransformTest, HandBuiltTreeWordsAndTies) {
  const BowVocabulary vocabulary = test::TinyVocabulary();
  EXPECT_EQ(vocabulary.Transform(test::FilledRow(0x00)), 0);
  EXPECT_EQ(vocabulary.Transform(test::FilledRow(0x01)), 1);
  EXPECT_EQ(vocabulary.Transform(test::FilledRow(0x03)), 1);
  EXPECT_EQ(vocabulary.Transform(test::FilledRow(0xFE)), 2);
  EXPECT_EQ(vocabulary.Transform(test::FilledRow(0xFF)), 3);
  // 0x0F is 128 bits from both a and b: the first child, a, wins; then a1 (0x01) is nearer.
  EXPECT_EQ(vocabulary.Transform(test::FilledRow(0x0F)), 1);
}

TEST(BowTransformTest, BowVectorIsTheL1NormalisedSumOfWordWeights) {
  const BowVocabulary vocabulary = test::TinyVocabulary();  // weights 1, 2, 3, 4
  cv::Mat descriptors;
  descriptors.push_back(test::FilledRow(0x00));  // word 0
  descriptors.push_back(test::FilledRow(0x00));  // word 0
  descriptors.push_back(test::FilledRow(0x01));  // word 1
  descriptors.push_back(test::FilledRow(0xFF));  // word 3
  descriptors.push_back(test::FilledRow(0xFF));  // word 3
  BowVector bow;
  FeatureVector features;
  vocabulary.Transform(descriptors, &bow, &features, 2);
  // Raw sums 2, 2, 8 over 12.
  ASSERT_EQ(bow.size(), 3u);
  EXPECT_DOUBLE_EQ(bow.at(0), 2.0 / 12.0);
  EXPECT_DOUBLE_EQ(bow.at(1), 2.0 / 12.0);
  EXPECT_DOUBLE_EQ(bow.at(3), 8.0 / 12.0);
  double sum = 0.0;
  for (const auto& entry : bow) sum += entry.second;
  EXPECT_NEAR(sum, 1.0, 1e-12);
}

TEST(BowTransformTest, WordsOfWeightZeroAreLeftOut) {
  BowVocabulary vocabulary = test::TinyVocabulary();
  vocabulary.SetWordWeights({0.0, 2.0, 0.0, 4.0});
  cv::Mat descriptors;
  descriptors.push_back(test::FilledRow(0x00));  // word 0, weight 0
  descriptors.push_back(test::FilledRow(0x01));  // word 1
  descriptors.push_back(test::FilledRow(0xFE));  // word 2, weight 0
  BowVector bow;
  FeatureVector features;
  vocabulary.Transform(descriptors, &bow, &features, 1);
  ASSERT_EQ(bow.size(), 1u);
  EXPECT_DOUBLE_EQ(bow.at(1), 1.0);
  ASSERT_EQ(features.size(), 1u);
  EXPECT_EQ(features.at(1), std::vector<unsigned>({1}));
}

TEST(BowTransformTest, DirectIndexGroupsFeaturesByTheirNodeAtTheLevel) {
  const BowVocabulary tiny = test::TinyVocabulary();
  cv::Mat descriptors;
  for (uint8_t value : {0x00, 0xFF, 0x01, 0xFE, 0x00, 0x03}) {
    descriptors.push_back(test::FilledRow(value));
  }
  BowVector bow;
  FeatureVector features;
  tiny.Transform(descriptors, &bow, &features, 1);
  // Level 1: node a (1) or b (2).
  ASSERT_EQ(features.size(), 2u);
  EXPECT_EQ(features.at(1), std::vector<unsigned>({0, 2, 4, 5}));
  EXPECT_EQ(features.at(2), std::vector<unsigned>({1, 3}));
  tiny.Transform(descriptors, &bow, &features, 0);
  ASSERT_EQ(features.size(), 1u);
  EXPECT_EQ(features.at(0).size(), 6u);
  tiny.Transform(descriptors, &bow, &features, 2);
  // Level L: the word nodes a0 = 3, a1 = 4, b0 = 5, b1 = 6.
  ASSERT_EQ(features.size(), 4u);
  EXPECT_EQ(features.at(3), std::vector<unsigned>({0, 4}));
  EXPECT_EQ(features.at(4), std::vector<unsigned>({2, 5}));
  EXPECT_EQ(features.at(5), std::vector<unsigned>({3}));
  EXPECT_EQ(features.at(6), std::vector<unsigned>({1}));

  // On a trained tree, against the brute-force ancestor at each level.
  const BowVocabulary vocabulary = TrainedVocabulary();
  const cv::Mat queries = test::RandomDescriptors(200, 5);
  for (int level = 0; level <= vocabulary.Depth(); ++level) {
    vocabulary.Transform(queries, &bow, &features, level);
    std::size_t grouped = 0;
    for (const auto& [node, rows] : features) {
      EXPECT_LE(vocabulary.NodeLevel(node), level);
      for (std::size_t i = 0; i < rows.size(); ++i) {
        if (i > 0) {
          EXPECT_LT(rows[i - 1], rows[i]);
        }
        int expected_node = -1;
        BruteForceWord(vocabulary, queries.row(static_cast<int>(rows[i])), level, &expected_node);
        EXPECT_EQ(node, expected_node) << "level " << level << " row " << rows[i];
      }
      grouped += rows.size();
    }
    std::size_t weighted = 0;
    for (int r = 0; r < queries.rows; ++r) {
      weighted += vocabulary.WordWeight(vocabulary.Transform(queries.row(r))) > 0.0 ? 1 : 0;
    }
    EXPECT_EQ(grouped, weighted);
  }
}

TEST(BowTransformTest, EmptyInputGivesEmptyOutputs) {
  const BowVocabulary vocabulary = test::TinyVocabulary();
  BowVector bow{{1, 1.0}};
  FeatureVector features{{1, {0}}};
  vocabulary.Transform(cv::Mat(), &bow, &features, 1);
  EXPECT_TRUE(bow.empty());
  EXPECT_TRUE(features.empty());
  vocabulary.Transform(cv::Mat(), &bow, nullptr, 1);
  EXPECT_TRUE(bow.empty());
}

TEST(BowTransformTest, RejectsBadInputs) {
  BowVocabulary vocabulary = test::TinyVocabulary();
  BowVector bow;
  FeatureVector features;
  EXPECT_THROW(vocabulary.Transform(cv::Mat(2, 32, CV_8UC1, cv::Scalar(0))), Error);
  EXPECT_THROW(vocabulary.Transform(cv::Mat(1, 31, CV_8UC1, cv::Scalar(0))), Error);
  EXPECT_THROW(vocabulary.Transform(cv::Mat(4, 32, CV_32FC1), &bow, &features, 1), Error);
  EXPECT_THROW(vocabulary.Transform(test::FilledRow(0), &bow, &features, -1), Error);
  EXPECT_THROW(vocabulary.Transform(test::FilledRow(0), &bow, &features, 3), Error);
  EXPECT_THROW(vocabulary.Transform(test::FilledRow(0), nullptr, &features, 1), Error);
  EXPECT_THROW(BowVocabulary().Transform(test::FilledRow(0)), Error);
  EXPECT_THROW(vocabulary.WordWeight(4), Error);
  EXPECT_THROW(vocabulary.NodeParent(7), Error);
  EXPECT_THROW(vocabulary.SetWordWeights({1.0, 2.0}), Error);
  EXPECT_THROW(vocabulary.SetWordWeights({1.0, 2.0, -1.0, 0.0}), Error);
  EXPECT_THROW(vocabulary.SetWordWeights({1.0, 2.0, NAN, 0.0}), Error);
}

}  // namespace
}  // namespace drvslam
