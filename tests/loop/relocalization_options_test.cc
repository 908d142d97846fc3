// RelocalizationOptions: defaults are valid, every key is read, bad values name their key and
// the file, and a relative vocabulary path is taken beside the settings file.
#include "drvslam/loop/relocalization_options.h"

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

namespace fs = std::filesystem;

fs::path WriteSettings(const std::string& name, const std::string& body) {
  const fs::path path = drvslam::testing::ProcessTempFolder() / name;
  std::ofstream(path) << "%YAML:1.0\n" << body;
  return path;
}

std::string ErrorOf(const RelocalizationOptions& options) {
  return testing::ErrorMessageOf([&] { options.Check(); });
}

TEST(RelocalizationOptionsTest, DefaultsAreValid) {
  EXPECT_EQ(ErrorOf(RelocalizationOptions{}), "");
}

TEST(RelocalizationOptionsTest, BadValuesNameTheirKey) {
  RelocalizationOptions options;
  options.min_bow_matches = 3;
  EXPECT_NE(ErrorOf(options).find("Relocalization.minBowMatches"), std::string::npos);
  options = RelocalizationOptions{};
  options.ransac_iterations = 0;
  EXPECT_NE(ErrorOf(options).find("Relocalization.ransacIterations"), std::string::npos);
  options = RelocalizationOptions{};
  options.ransac_reprojection_error = std::nan("");
  EXPECT_NE(ErrorOf(options).find("Relocalization.ransacReprojectionError"), std::string::npos);
  options = RelocalizationOptions{};
  options.min_pnp_inliers = 2;
  EXPECT_NE(ErrorOf(options).find("Relocalization.minPnpInliers"), std::string::npos);
  options = RelocalizationOptions{};
  options.min_inliers = 9;
  EXPECT_NE(ErrorOf(options).find("Relocalization.minInliers"), std::string::npos);
}

TEST(RelocalizationOptionsTest, ReadsEveryKey) {
  const fs::path path = WriteSettings("all.yaml",
                                      "Relocalization.enabled: 0\n"
                                      "Relocalization.vocabulary: \"vocab/words.bin\"\n"
                                      "Relocalization.minBowMatches: 20\n"
                                      "Relocalization.ransacIterations: 100\n"
                                      "Relocalization.ransacReprojectionError: 2.5\n"
                                      "Relocalization.minPnpInliers: 12\n"
                                      "Relocalization.minInliers: 40\n");
  const RelocalizationOptions options = LoadRelocalizationOptions(SettingsFile(path.string()));
  EXPECT_FALSE(options.enabled);
  EXPECT_EQ(fs::path(options.vocabulary), (path.parent_path() / "vocab/words.bin"));
  EXPECT_EQ(options.min_bow_matches, 20);
  EXPECT_EQ(options.ransac_iterations, 100);
  EXPECT_DOUBLE_EQ(options.ransac_reprojection_error, 2.5);
  EXPECT_EQ(options.min_pnp_inliers, 12);
  EXPECT_EQ(options.min_inliers, 40);
}

TEST(RelocalizationOptionsTest, ABadFileValueNamesTheFileAndKey) {
  const fs::path path = WriteSettings("bad.yaml", "Relocalization.minInliers: 3\n");
  const std::string message =
      testing::ErrorMessageOf([&] { LoadRelocalizationOptions(SettingsFile(path.string())); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("Relocalization.minInliers"), std::string::npos) << message;
}

}  // namespace
}  // namespace drvslam
