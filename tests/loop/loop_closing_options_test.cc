#include "drvslam/loop/loop_closing_options.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "drvslam/core/error.h"
#include "test_support/error_message.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

std::string ErrorOf(const LoopClosingOptions& options) {
  return testing::ErrorMessageOf([&] { options.Check(); });
}

TEST(LoopClosingOptionsTest, DefaultsAreValid) { EXPECT_EQ(ErrorOf(LoopClosingOptions{}), ""); }

TEST(LoopClosingOptionsTest, BadValuesNameTheirKey) {
  LoopClosingOptions options;
  options.min_inliers = 2;
  EXPECT_NE(ErrorOf(options).find("LoopClosing.minInliers"), std::string::npos);
  options = LoopClosingOptions{};
  options.ransac_tolerance = 0.0;
  EXPECT_NE(ErrorOf(options).find("LoopClosing.ransacTolerance"), std::string::npos);
  options = LoopClosingOptions{};
  options.min_consistency = -1;
  EXPECT_NE(ErrorOf(options).find("LoopClosing.minConsistency"), std::string::npos);
  options = LoopClosingOptions{};
  options.queue_capacity = 0;
  EXPECT_NE(ErrorOf(options).find("LoopClosing.queueCapacity"), std::string::npos);
  options = LoopClosingOptions{};
  options.global_ba_iterations = 0;
  EXPECT_NE(ErrorOf(options).find("LoopClosing.globalBaIterations"), std::string::npos);
}

class LoopClosingOptionsFileTest : public ::testing::Test {
 protected:
  void SetUp() override { path_ = drvslam::testing::ProcessTempFolder() / "loop_options.yaml"; }
  void TearDown() override { std::filesystem::remove(path_); }
  void Write(const std::string& body) {
    std::ofstream out(path_);
    out << "%YAML:1.0\n" << body;
  }
  std::filesystem::path path_;
};

TEST_F(LoopClosingOptionsFileTest, ReadsKeysAndKeepsDefaults) {
  Write(
      "LoopClosing.enabled: 0\nLoopClosing.minConsistency: 2\nLoopClosing.ransacTolerance: 0.05\n");
  const LoopClosingOptions options = LoadLoopClosingOptions(SettingsFile(path_.string()));
  EXPECT_FALSE(options.enabled);
  EXPECT_EQ(options.min_consistency, 2);
  EXPECT_DOUBLE_EQ(options.ransac_tolerance, 0.05);
  EXPECT_EQ(options.min_total_matches, LoopClosingOptions{}.min_total_matches);
}

TEST_F(LoopClosingOptionsFileTest, BadValueNamesFileAndKey) {
  Write("LoopClosing.minTotalMatches: 1\n");
  const std::string message =
      testing::ErrorMessageOf([&] { LoadLoopClosingOptions(SettingsFile(path_.string())); });
  EXPECT_NE(message.find(path_.string()), std::string::npos) << message;
  EXPECT_NE(message.find("LoopClosing.minTotalMatches"), std::string::npos) << message;
}

}  // namespace
}  // namespace drvslam
