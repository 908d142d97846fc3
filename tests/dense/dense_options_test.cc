#include "drvslam/dense/dense_options.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "drvslam/core/error.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

std::string WriteYaml(const std::string& name, const std::string& body) {
  const std::string path = (testing::ProcessTempFolder() / name).string();
  std::ofstream(path) << "%YAML:1.0\n" << body;
  return path;
}

TEST(DenseMapOptions, DefaultsAreValid) {
  const DenseMapOptions options;
  EXPECT_NO_THROW(options.Check());
  EXPECT_TRUE(options.enabled);
  EXPECT_LT(options.object_leaf_size, options.leaf_size);
}

TEST(DenseMapOptions, BadValuesNameTheKey) {
  DenseMapOptions o;
  o.leaf_size = 0.0;
  try {
    o.Check();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("DenseMap.leafSize"), std::string::npos);
  }
  o = DenseMapOptions();
  o.object_leaf_size = 0.1;  // coarser than the global leaf
  EXPECT_THROW(o.Check(), Error);
  o = DenseMapOptions();
  o.max_depth = o.min_depth;
  EXPECT_THROW(o.Check(), Error);
  o = DenseMapOptions();
  o.enhancement_frames = -1;
  EXPECT_THROW(o.Check(), Error);
}

TEST(DenseMapOptions, LoadsKeysAndRejectsBadOnes) {
  const std::string good = WriteYaml("drvslam_dense_good.yaml",
                                     "DenseMap.enabled: 0\nDenseMap.leafSize: 0.05\n"
                                     "DenseMap.enhancementFrames: 2\n"
                                     "DenseMap.removeAllPotentiallyMoving: 1\n");
  const DenseMapOptions o = LoadDenseMapOptions(SettingsFile(good));
  EXPECT_FALSE(o.enabled);
  EXPECT_DOUBLE_EQ(o.leaf_size, 0.05);
  EXPECT_EQ(o.enhancement_frames, 2);
  EXPECT_TRUE(o.remove_all_potentially_moving);
  const std::string bad = WriteYaml("drvslam_dense_bad.yaml", "DenseMap.minNeighbours: 40\n");
  try {
    LoadDenseMapOptions(SettingsFile(bad));
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(bad), std::string::npos);
    EXPECT_NE(message.find("DenseMap.minNeighbours"), std::string::npos);
  }
}

}  // namespace
}  // namespace drvslam
