// `drvslam vocab train|info|eval` end to end through the built CLI.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "test_support/cli_run.h"
#include "test_support/missing_data.h"
#include "vocabulary_test_util.h"

namespace drvslam {
namespace {

using drvslam::testing::CliRun;
using drvslam::testing::RunCli;

// Blurred noise: plenty of corners for ORB.
void WriteTexturedImages(const std::string& folder, int count) {
  cv::RNG rng(7);
  for (int i = 0; i < count; ++i) {
    cv::Mat noise(240, 320, CV_8UC1);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(noise, noise, cv::Size(5, 5), 1.5);
    cv::imwrite(folder + "/image" + std::to_string(i) + ".png", noise);
  }
}

class VocabCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::is_regular_file(DRVSLAM_CLI)) {
      DRVSLAM_MISSING_TEST_DATA() << "CLI not built: " << DRVSLAM_CLI;
    }
  }
};

TEST_F(VocabCommandTest, TrainInfoAndEval) {
  const std::string folder = test::ScratchFolder("cli_train");
  WriteTexturedImages(folder, 4);
  const std::string vocabulary = folder + "/voc.txt";
  const CliRun train = RunCli("vocab train --images " + folder + " --out " + vocabulary +
                              " --k 4 --levels 3 --features 300 --format text");
  ASSERT_EQ(train.status, 0) << train.output;
  EXPECT_NE(train.output.find("images:      4"), std::string::npos) << train.output;
  EXPECT_NE(train.output.find("k, L:        4, 3"), std::string::npos) << train.output;
  EXPECT_NE(train.output.find("(text)"), std::string::npos) << train.output;

  const CliRun info = RunCli("vocab info " + vocabulary);
  ASSERT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("k:       4"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("L:       3"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("words:   "), std::string::npos) << info.output;

  const CliRun eval =
      RunCli("vocab eval --vocab " + vocabulary + " --images " + folder + " --rotate 10");
  ASSERT_EQ(eval.status, 0) << eval.output;
  EXPECT_NE(eval.output.find("database: 4 images, queries: 4"), std::string::npos) << eval.output;
}

TEST_F(VocabCommandTest, BadInputExitsTwoWithAnError) {
  const std::string folder = test::ScratchFolder("cli_errors");
  const CliRun missing = RunCli("vocab info " + folder + "/missing.bin");
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.output.find("error: " + folder + "/missing.bin: cannot open"),
            std::string::npos)
      << missing.output;
  test::WriteText(folder + "/bad.txt", "10 6 3 0\n");
  const CliRun scoring = RunCli("vocab info " + folder + "/bad.txt");
  EXPECT_EQ(scoring.status, 2);
  EXPECT_NE(scoring.output.find("line 1: unsupported scoring type 3"), std::string::npos)
      << scoring.output;
  const CliRun format = RunCli("vocab train --images " + folder + " --out x.bin --format yaml");
  EXPECT_EQ(format.status, 2);
  EXPECT_NE(format.output.find("error: vocabulary format 'yaml' unknown"), std::string::npos)
      << format.output;
}

}  // namespace
}  // namespace drvslam
