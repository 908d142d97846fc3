// Dynamic.* settings: defaults pass Check, each bad value names its key, and a settings file's
// values are read (and its errors name the file).
#include "drvslam/dynamic/dynamic_options.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "drvslam/core/error.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

void ExpectKeyError(const std::function<void(DynamicOptions&)>& spoil, const std::string& key) {
  DynamicOptions options;
  spoil(options);
  try {
    options.Check();
    FAIL() << "expected an error naming " << key;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

TEST(DynamicOptionsTest, DefaultsPass) { EXPECT_NO_THROW(DynamicOptions().Check()); }

TEST(DynamicOptionsTest, BadValuesNameTheirKey) {
  ExpectKeyError([](DynamicOptions& o) { o.flow_window = 20; }, "Dynamic.flowWindow");
  ExpectKeyError([](DynamicOptions& o) { o.flow_levels = 9; }, "Dynamic.flowLevels");
  ExpectKeyError([](DynamicOptions& o) { o.max_flow_points = 3; }, "Dynamic.maxFlowPoints");
  ExpectKeyError([](DynamicOptions& o) { o.flow_check = -1; }, "Dynamic.flowCheck");
  ExpectKeyError([](DynamicOptions& o) { o.epipolar_threshold = 0; }, "Dynamic.epipolarThreshold");
  ExpectKeyError([](DynamicOptions& o) { o.ransac_confidence = 1.0; }, "Dynamic.ransacConfidence");
  ExpectKeyError([](DynamicOptions& o) { o.min_model_pairs = 7; }, "Dynamic.minModelPairs");
  ExpectKeyError([](DynamicOptions& o) { o.min_parallax_share = 1.5; }, "Dynamic.minParallaxShare");
  ExpectKeyError([](DynamicOptions& o) { o.min_id_matches = 0; }, "Dynamic.minIdMatches");
  ExpectKeyError([](DynamicOptions& o) { o.object_memory_frames = -1; },
                 "Dynamic.objectMemoryFrames");
  ExpectKeyError([](DynamicOptions& o) { o.object_memory_iou = 0.0; }, "Dynamic.objectMemoryIou");
  ExpectKeyError([](DynamicOptions& o) { o.box_margin = -0.1; }, "Dynamic.boxMargin");
  ExpectKeyError([](DynamicOptions& o) { o.delta_static = 1.2; }, "Dynamic.deltaStatic");
  ExpectKeyError(
      [](DynamicOptions& o) {
        o.delta_moving = 0.7;
        o.delta_static = 0.5;
      },
      "Dynamic.deltaMoving");
  ExpectKeyError([](DynamicOptions& o) { o.moving_share = -0.5; }, "Dynamic.movingShare");
  ExpectKeyError([](DynamicOptions& o) { o.limb_share = 2.0; }, "Dynamic.limbShare");
  ExpectKeyError([](DynamicOptions& o) { o.min_moving_tracks = 0; }, "Dynamic.minMovingTracks");
  ExpectKeyError([](DynamicOptions& o) { o.reprojection_threshold = 0; },
                 "Dynamic.reprojectionThreshold");
  ExpectKeyError([](DynamicOptions& o) { o.flow_scale = 2; }, "Dynamic.flowScale");
  ExpectKeyError([](DynamicOptions& o) { o.large_share = 2; }, "Dynamic.largeShare");
  ExpectKeyError([](DynamicOptions& o) { o.boost_share = 1.0; }, "Dynamic.boostShare");
  ExpectKeyError([](DynamicOptions& o) { o.max_feature_boost = 0.5; }, "Dynamic.maxFeatureBoost");
  ExpectKeyError([](DynamicOptions& o) { o.mask_dilation = -1; }, "Dynamic.maskDilation");
  ExpectKeyError([](DynamicOptions& o) { o.cluster_radius = 0; }, "Dynamic.clusterRadius");
  ExpectKeyError([](DynamicOptions& o) { o.min_cluster_points = 1; }, "Dynamic.minClusterPoints");
  ExpectKeyError([](DynamicOptions& o) { o.region_depth_step = std::nan(""); },
                 "Dynamic.regionDepthStep");
  ExpectKeyError([](DynamicOptions& o) { o.blur_ratio = 1.5; }, "Dynamic.blurRatio");
  ExpectKeyError([](DynamicOptions& o) { o.sharpness_window = 0; }, "Dynamic.sharpnessWindow");
  ExpectKeyError([](DynamicOptions& o) { o.min_inlier_share = -0.1; }, "Dynamic.minInlierShare");
  ExpectKeyError([](DynamicOptions& o) { o.residual_factor = -1; }, "Dynamic.residualFactor");
  ExpectKeyError([](DynamicOptions& o) { o.max_unlabelled_share = 1.1; },
                 "Dynamic.maxUnlabelledShare");
  ExpectKeyError([](DynamicOptions& o) { o.unlabelled_frames = 0; }, "Dynamic.unlabelledFrames");
  ExpectKeyError([](DynamicOptions& o) { o.min_kept_features = -5; }, "Dynamic.minKeptFeatures");
}

class DynamicOptionsFileTest : public ::testing::Test {
 protected:
  std::string Write(const std::string& body) {
    // In this process's own folder: gtest's random_seed() is 0 unless shuffling, so a name made
    // of it was the same for every run and user.
    const std::filesystem::path path =
        testing::ProcessTempFolder() /
        (std::string("dynamic_options_") +
         ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".yaml");
    std::ofstream out(path);
    out << "%YAML:1.0\n" << body;
    paths_.push_back(path);
    return path.string();
  }
  void TearDown() override {
    for (const auto& path : paths_) std::filesystem::remove(path);
  }
  std::vector<std::filesystem::path> paths_;
};

TEST_F(DynamicOptionsFileTest, ReadsValues) {
  const std::string path = Write(
      "Dynamic.epipolarThreshold: 2.5\nDynamic.largeShare: 0.4\nDynamic.motionRule: delta\n"
      "Dynamic.unlabelledMotion: 0\nDynamic.flowWindow: 15\nDynamic.objectMemoryFrames: 2\n"
      "Dynamic.objectMemoryIou: 0.5\nDynamic.blurRatio: 0.4\n"
      "Dynamic.sharpnessWindow: 10\nDynamic.minInlierShare: 0.6\nDynamic.residualFactor: 2.5\n"
      "Dynamic.maxUnlabelledShare: 0.25\nDynamic.unlabelledFrames: 3\n"
      "Dynamic.minKeptFeatures: 150\n");
  const DynamicOptions options = LoadDynamicOptions(SettingsFile(path));
  EXPECT_EQ(options.epipolar_threshold, 2.5);
  EXPECT_EQ(options.large_share, 0.4);
  EXPECT_EQ(options.rule, MotionRule::kDelta);
  EXPECT_FALSE(options.unlabelled_motion);
  EXPECT_EQ(options.flow_window, 15);
  EXPECT_EQ(options.object_memory_frames, 2);
  EXPECT_EQ(options.object_memory_iou, 0.5);
  EXPECT_EQ(options.blur_ratio, 0.4);
  EXPECT_EQ(options.sharpness_window, 10);
  EXPECT_EQ(options.min_inlier_share, 0.6);
  EXPECT_EQ(options.residual_factor, 2.5);
  EXPECT_EQ(options.max_unlabelled_share, 0.25);
  EXPECT_EQ(options.unlabelled_frames, 3);
  EXPECT_EQ(options.min_kept_features, 150);
  EXPECT_EQ(options.delta_static, DynamicOptions().delta_static);
}

TEST_F(DynamicOptionsFileTest, ErrorsNameTheFileAndKey) {
  const std::string path = Write("Dynamic.largeShare: 1.5\n");
  try {
    LoadDynamicOptions(SettingsFile(path));
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("Dynamic.largeShare"), std::string::npos) << message;
  }
  const std::string rule = Write("Dynamic.motionRule: magic\n");
  EXPECT_THROW(LoadDynamicOptions(SettingsFile(rule)), Error);
}

}  // namespace
}  // namespace drvslam
