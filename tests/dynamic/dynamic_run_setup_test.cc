// How `drvslam run` picks its segmenter and dynamic handling: defaults from the dataset, the
// command line over the settings file, and errors that name the option.
#include "drvslam/tools/runner/dynamic_run_setup.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "drvslam/core/error.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

class DynamicRunSetupTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // A new folder of this process's own (gtest's random_seed() is 0 unless shuffling: a name
    // made of it was the same for every run and user).
    root_ =
        testing::UniqueTempFolder(std::string("drvslam_run_setup_") +
                                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(root_ / "plain");
    fs::create_directories(root_ / "synthetic" / "masks");
    std::ofstream(root_ / "synthetic" / "instances.txt")
        << "# drvslam synthetic instances\ninstance 1 person 0\nframe 1.000000 1\n";
    std::ofstream(root_ / "synthetic" / "rgb.txt") << "1.000000 rgb/1.000000.png\n";
  }
  void TearDown() override { fs::remove_all(root_); }

  DynamicRunSetup Resolve(const DynamicRunChoice& choice, const std::string& dataset,
                          SegmenterBackend settings_backend = SegmenterBackend::kAuto) {
    SegmentationOptions segmentation;
    segmentation.backend = settings_backend;
    return ResolveDynamicRun(choice, (root_ / dataset).string(), segmentation, DynamicOptions());
  }

  fs::path root_;
};

TEST_F(DynamicRunSetupTest, DefaultsFollowTheDataset) {
  const DynamicRunSetup synthetic = Resolve({}, "synthetic");
  EXPECT_EQ(synthetic.backend, SegmenterBackend::kGroundTruth);
  ASSERT_TRUE(synthetic.config.has_value());
  ASSERT_NE(synthetic.config->segmenter, nullptr);
  EXPECT_EQ(synthetic.description, "segmenter gt, dynamic on");
  // Ground-truth masks chosen for the user are an oracle, and labelled so.
  EXPECT_TRUE(synthetic.oracle);
  EXPECT_TRUE(synthetic.implicit_ground_truth);
  EXPECT_EQ(synthetic.segmenter_label, "gt (ground-truth masks: ORACLE)");

  const DynamicRunSetup plain = Resolve({}, "plain");
  EXPECT_EQ(plain.backend, SegmenterBackend::kNone);
  EXPECT_FALSE(plain.config.has_value());
  EXPECT_EQ(plain.description, "segmenter none, dynamic off");
  EXPECT_FALSE(plain.oracle);
  EXPECT_EQ(plain.segmenter_label, "none");
}

TEST_F(DynamicRunSetupTest, TheCommandLineWins) {
  DynamicRunChoice off;
  off.dynamic = "off";
  const DynamicRunSetup baseline = Resolve(off, "synthetic");
  EXPECT_FALSE(baseline.config.has_value());
  EXPECT_EQ(baseline.description, "segmenter gt, dynamic off");
  // Off uses no masks at all: not an oracle result.
  EXPECT_FALSE(baseline.oracle);
  EXPECT_EQ(baseline.segmenter_label, "none");

  DynamicRunChoice explicit_gt;
  explicit_gt.segmenter = "gt";
  const DynamicRunSetup chosen = Resolve(explicit_gt, "synthetic");
  EXPECT_TRUE(chosen.oracle);
  EXPECT_FALSE(chosen.implicit_ground_truth);

  // Geometry only: no segmenter, dynamic handling on.
  DynamicRunChoice geometry;
  geometry.segmenter = "none";
  geometry.dynamic = "on";
  geometry.realtime = true;
  const DynamicRunSetup only_geometry = Resolve(geometry, "synthetic");
  ASSERT_TRUE(only_geometry.config.has_value());
  EXPECT_EQ(only_geometry.config->segmenter, nullptr);
  EXPECT_TRUE(only_geometry.config->realtime);
  EXPECT_EQ(only_geometry.description, "segmenter none, dynamic on, realtime");

  // A settings file's backend is used when the command line names none.
  const DynamicRunSetup from_settings = Resolve({}, "synthetic", SegmenterBackend::kNone);
  EXPECT_EQ(from_settings.backend, SegmenterBackend::kNone);
  EXPECT_FALSE(from_settings.config.has_value());
}

TEST_F(DynamicRunSetupTest, AnAutoBackendInTheSettingsIsTheDatasetDefault) {
  // A dumped settings file says `Segmentation.backend: "auto"`: the same as naming none.
  const DynamicRunSetup synthetic = Resolve({}, "synthetic", SegmenterBackend::kAuto);
  EXPECT_EQ(synthetic.backend, SegmenterBackend::kGroundTruth);
  EXPECT_TRUE(synthetic.implicit_ground_truth);
  ASSERT_TRUE(synthetic.config.has_value());
  ASSERT_NE(synthetic.config->segmenter, nullptr);
  const DynamicRunSetup plain = Resolve({}, "plain", SegmenterBackend::kAuto);
  EXPECT_EQ(plain.backend, SegmenterBackend::kNone);
  EXPECT_FALSE(plain.config.has_value());
  // The command line still wins over it.
  DynamicRunChoice none;
  none.segmenter = "none";
  EXPECT_EQ(Resolve(none, "synthetic", SegmenterBackend::kAuto).backend, SegmenterBackend::kNone);
}

TEST_F(DynamicRunSetupTest, AModelMeansYolo) {
  DynamicRunChoice choice;
  choice.model = (root_ / "missing.onnx").string();
  try {
    Resolve(choice, "synthetic");
    FAIL() << "a missing model must be an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.onnx"), std::string::npos) << e.what();
  }
  // Off: the model is never opened.
  choice.dynamic = "off";
  EXPECT_EQ(Resolve(choice, "synthetic").backend, SegmenterBackend::kYolo);
  EXPECT_EQ(SegmenterLabel(SegmenterBackend::kYolo, "/models/yolov8n-seg-320x256.onnx"),
            "yolo (yolov8n-seg-320x256.onnx)");
}

TEST_F(DynamicRunSetupTest, BadChoicesNameTheOption) {
  const auto expect_error = [&](const DynamicRunChoice& choice, const std::string& option) {
    try {
      Resolve(choice, "synthetic");
      FAIL() << "expected an error naming " << option;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(option), std::string::npos) << e.what();
    }
  };
  DynamicRunChoice choice;
  choice.segmenter = "sam";
  expect_error(choice, "--segmenter");
  choice = {};
  choice.segmenter = "yolo";
  expect_error(choice, "--model");
  choice = {};
  choice.dynamic = "sometimes";
  expect_error(choice, "--dynamic");
  choice = {};
  choice.dynamic = "off";
  choice.debug_dir = (root_ / "pictures").string();
  expect_error(choice, "--debug-frames");
}

TEST_F(DynamicRunSetupTest, MotionTruthNeedsInstances) {
  EXPECT_EQ(DatasetMotionTruth::Open((root_ / "plain").string(), SegmenterBackend::kNone), nullptr);
  EXPECT_NE(
      DatasetMotionTruth::Open((root_ / "synthetic").string(), SegmenterBackend::kGroundTruth),
      nullptr);
}

}  // namespace
}  // namespace drvslam
