// Finding the build's default vocabulary.
#include "drvslam/loop/default_vocabulary.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/loop/vocabulary_io.h"
#include "test_support/missing_data.h"
#include "vocabulary_test_util.h"

namespace drvslam {
namespace {

TEST(DefaultVocabularyTest, EnvironmentVariableComesFirst) {
  const std::string folder = test::ScratchFolder("default_env");
  const std::string path = folder + "/mine.bin";
  WriteBinaryVocabulary(test::TinyVocabulary(), path);
  setenv(kDefaultVocabularyEnvironment, path.c_str(), 1);
  const std::vector<std::string> candidates = DefaultVocabularyCandidates();
  ASSERT_GE(candidates.size(), 2u);
  EXPECT_EQ(candidates[0], path);
  EXPECT_EQ(DefaultVocabularyPath(), path);
  EXPECT_TRUE(LoadDefaultVocabulary() == test::TinyVocabulary());
  // A variable naming no file is passed over.
  setenv(kDefaultVocabularyEnvironment, (folder + "/absent.bin").c_str(), 1);
  EXPECT_NE(DefaultVocabularyPath(), folder + "/absent.bin");
  unsetenv(kDefaultVocabularyEnvironment);
}

TEST(DefaultVocabularyTest, LooksBesideTheExecutableInTheBuildTreeAndInTheInstallPrefix) {
  unsetenv(kDefaultVocabularyEnvironment);
  const std::vector<std::string> candidates = DefaultVocabularyCandidates();
  ASSERT_EQ(candidates.size(), 3u);
  const std::string suffix = "/share/drvslam/default_vocab.bin";
  for (const std::string& candidate : candidates) {
    ASSERT_GE(candidate.size(), suffix.size());
    EXPECT_EQ(candidate.substr(candidate.size() - suffix.size()), suffix);
  }
}

TEST(DefaultVocabularyTest, TheBuildTrainedOneLoads) {
  unsetenv(kDefaultVocabularyEnvironment);
  if (DefaultVocabularyPath().empty()) {
    EXPECT_THROW(LoadDefaultVocabulary(), Error);
    DRVSLAM_MISSING_TEST_DATA() << "no default vocabulary was built (opencv-doc images missing?)";
  }
  const BowVocabulary vocabulary = LoadDefaultVocabulary();
  EXPECT_EQ(vocabulary.BranchingFactor(), 10);
  EXPECT_EQ(vocabulary.Depth(), 6);
  EXPECT_GT(vocabulary.WordCount(), 50000u);
}

}  // namespace
}  // namespace drvslam
