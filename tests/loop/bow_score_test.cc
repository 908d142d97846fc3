// BowVocabulary::Score: DBoW2's L1 score of two bag-of-words vectors.
#include <gtest/gtest.h>

#include "drvslam/loop/bow_vocabulary.h"
#include "vocabulary_test_util.h"

namespace drvslam {
namespace {

TEST(BowScoreTest, IdenticalVectorsScoreOne) {
  const BowVector v{{3, 0.2}, {7, 0.5}, {11, 0.3}};
  EXPECT_DOUBLE_EQ(BowVocabulary::Score(v, v), 1.0);
}

TEST(BowScoreTest, DisjointVectorsScoreZero) {
  const BowVector a{{1, 0.5}, {2, 0.5}};
  const BowVector b{{3, 0.25}, {4, 0.75}};
  EXPECT_DOUBLE_EQ(BowVocabulary::Score(a, b), 0.0);
}

TEST(BowScoreTest, HandComputedMiddleCase) {
  // |a - b|_1 = |0.5 - 0| + |0.5 - 0.25| + |0 - 0.75| = 1.5, so s = 1 - 0.75 = 0.25.
  const BowVector a{{1, 0.5}, {2, 0.5}};
  const BowVector b{{2, 0.25}, {3, 0.75}};
  EXPECT_DOUBLE_EQ(BowVocabulary::Score(a, b), 0.25);
  EXPECT_DOUBLE_EQ(BowVocabulary::Score(b, a), 0.25);
  // Scores compare directions: scaling either vector changes nothing.
  const BowVector a2{{1, 2.0}, {2, 2.0}};
  const BowVector b3{{2, 0.75}, {3, 2.25}};
  EXPECT_DOUBLE_EQ(BowVocabulary::Score(a2, b3), 0.25);
  // c on words 1..3, d on words 2 and 3: |c - d|_1 = 0.2 + |0.3 - 0.5| + |0.5 - 0.5| = 0.4.
  const BowVector c{{1, 0.2}, {2, 0.3}, {3, 0.5}};
  const BowVector d{{2, 0.5}, {3, 0.5}};
  EXPECT_NEAR(BowVocabulary::Score(c, d), 1.0 - 0.5 * (0.2 + 0.2 + 0.0), 1e-15);
}

TEST(BowScoreTest, EmptyVectorsScoreZero) {
  const BowVector v{{1, 1.0}};
  EXPECT_DOUBLE_EQ(BowVocabulary::Score(BowVector(), v), 0.0);
  EXPECT_DOUBLE_EQ(BowVocabulary::Score(v, BowVector()), 0.0);
  EXPECT_DOUBLE_EQ(BowVocabulary::Score(BowVector(), BowVector()), 0.0);
}

TEST(BowScoreTest, TransformedImagesScoreByTheirSharedWords) {
  const BowVocabulary vocabulary = test::TinyVocabulary();  // weights 1, 2, 3, 4
  cv::Mat first;
  first.push_back(test::FilledRow(0x00));  // word 0: 1
  first.push_back(test::FilledRow(0xFF));  // word 3: 4
  cv::Mat second;
  second.push_back(test::FilledRow(0x01));  // word 1: 2
  second.push_back(test::FilledRow(0xFF));  // word 3: 4
  BowVector a;
  BowVector b;
  vocabulary.Transform(first, &a, nullptr, 0);
  vocabulary.Transform(second, &b, nullptr, 0);
  // a = (0.2, 0, 0, 0.8), b = (0, 1/3, 0, 2/3): |a - b|_1 = 0.2 + 1/3 + 0.8 - 2/3.
  EXPECT_NEAR(BowVocabulary::Score(a, b), 1.0 - 0.5 * (0.2 + 1.0 / 3.0 + 0.8 - 2.0 / 3.0), 1e-15);
}

}  // namespace
}  // namespace drvslam
