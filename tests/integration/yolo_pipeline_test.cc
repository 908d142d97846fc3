// End to end with the real network: people cut out of the opencv-doc photographs by the shared
// YOLOv8n-seg model walk through a short synthetic sequence, which is run in sequential mode
// with the same model segmenting every frame (network -> dynamic handling -> tracking -> local
// mapping), and once with dynamic handling off, the plain ORB-SLAM2 baseline. Skipped, with a
// message, when the model or the photographs are absent.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../semantic/test_data.h"
#include "drvslam/semantic/yolo_segmenter.h"
#include "drvslam/tools/runner/cutout_sequence.h"
#include "drvslam/tools/runner/sequence_runner.h"
#include "synthesized_sequence.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr char kModelName[] = "yolov8n-seg-320x256.onnx";
constexpr int kFrames = 100;
// Measured with this model at 320x240, 100 frames, sequential, one run each (ATE RMSE, yolo /
// dynamic off): seed 1: 0.43 / 0.36 cm, seed 2: 0.52 / 11.86 cm, seed 3: 1.81 / 8.83 cm,
// seed 4: 0.97 / 38.30 cm, seed 5: 0.90 / 0.80 cm. Seed 2 is one where the actors ruin plain
// tracking. With feature removal disabled (moving map points still culled) its yolo run gives
// 1.16 cm: the absolute bound fails, as does the removal count.
constexpr unsigned kSeed = 2;
constexpr double kAteBound = 0.010;  // m: about twice what seed 2 measured
constexpr double kAteFactor = 0.25;  // of the baseline's ATE (measured: 0.044)

class YoloPipelineTest : public ::testing::Test {
 protected:
  // The one place this test needs data from outside the repository.
  void SetUp() override {
    model_ = drvslam::testing::SharedModel(kModelName);
    DRVSLAM_SKIP_IF_MISSING(model_, std::string("shared model ") + kModelName);
    for (const std::string& photo : DefaultCutoutPhotos()) {
      DRVSLAM_SKIP_IF_MISSING(drvslam::testing::OpenCvData(photo),
                              "opencv-doc photograph " + photo);
    }
    root_ = test::FreshTempFolder("drvslam_yolo_pipeline");
  }
  void TearDown() override {
    if (!root_.empty()) fs::remove_all(root_);
  }

  // Cut-outs by the network, then a walking_xyz sequence with them as its two actors.
  std::string MakeSequence(unsigned seed) {
    SegmentationOptions segmentation;
    segmentation.backend = SegmenterBackend::kYolo;
    segmentation.model = model_;
    YoloSegmenter cutter(segmentation);
    CutoutSequenceOptions options;
    options.photo_dir = DRVSLAM_OPENCV_DATA_DIR;
    options.synth.scenario = "walking_xyz";
    options.synth.frames = kFrames;
    options.synth.seed = seed;
    options.synth.width = 320;
    options.synth.height = 240;
    const fs::path folder = root_ / ("seed" + std::to_string(seed));
    const CutoutSequence made = MakeCutoutSequence(cutter, options, folder.string());
    EXPECT_GE(made.cutouts, 2u);
    EXPECT_EQ(made.synth.actors, 2);
    return made.sequence_dir;
  }

  RunSummary Run(const std::string& sequence, const std::string& out_name, bool dynamic) {
    RunOptions options;
    options.dataset = sequence;
    options.out_dir = (root_ / out_name).string();
    options.sequential = true;
    options.dense = "off";  // the dense map is not what is measured here
    options.dynamic.segmenter = dynamic ? "yolo" : "none";
    options.dynamic.model = dynamic ? model_ : "";
    options.dynamic.dynamic = dynamic ? "on" : "off";
    return RunSequence(options);
  }

  static double Ate(const std::string& sequence, const RunSummary& run) {
    return test::AteAgainstGroundTruth(sequence, run.camera_trajectory_path).errors.rmse;
  }

  std::string model_;
  fs::path root_;
};

TEST_F(YoloPipelineTest, NetworkSegmentedRunTracksEveryFrameAndBeatsPlainTracking) {
  const std::string sequence = MakeSequence(kSeed);
  const RunSummary on = Run(sequence, "yolo", true);
  const RunSummary off = Run(sequence, "off", false);
  EXPECT_EQ(on.dynamic_setup, "segmenter yolo, dynamic on");
  ASSERT_TRUE(on.stats.dynamic.has_value());
  // The network found the actors: features were taken off them.
  EXPECT_GT(on.stats.dynamic->removed_on_objects, 0u);
  ASSERT_EQ(on.stats.frames, static_cast<std::size_t>(kFrames));
  EXPECT_GE(on.stats.tracked, static_cast<std::size_t>(kFrames) * 95 / 100);
  const double ate_on = Ate(sequence, on);
  const double ate_off = Ate(sequence, off);
  EXPECT_LT(ate_on, kAteBound) << "ATE " << ate_on << " m with yolo, " << ate_off << " m off";
  EXPECT_LT(ate_on, kAteFactor * ate_off)
      << "ATE " << ate_on << " m with yolo, " << ate_off << " m off";
}

}  // namespace
}  // namespace drvslam
