#include "drvslam/tools/truth/ground_truth_segmenter.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/semantic/segmenter_factory.h"
#include "drvslam/tools/truth/evaluation_segmenter_factory.h"
#include "test_data.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

// A two-frame sequence in the layout drvslam synth writes.
class GroundTruthSegmenterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::FreshTempDir("gt_segmenter");
    fs::create_directories(dir_ / "masks");
    std::ofstream(dir_ / "rgb.txt") << "# timestamp filename\n"
                                       "1305031102.175304 rgb/1305031102.175304.png\n"
                                       "1305031102.211214 rgb/1305031102.211214.png\n";
    std::ofstream(dir_ / "instances.txt") << "instance 1 person 0\n"
                                             "instance 7 cell_phone 67\n"
                                             "instance 9 cardboard_box -1\n"
                                             "frame 1305031102.175304 1 0 0\n"
                                             "frame 1305031102.211214 0 0 1\n";
    cv::Mat labels = cv::Mat::zeros(48, 64, CV_16UC1);
    labels(cv::Rect(2, 3, 10, 20)).setTo(1);
    labels(cv::Rect(30, 30, 6, 4)).setTo(7);
    labels(cv::Rect(50, 2, 3, 3)).setTo(9);
    cv::imwrite((dir_ / "masks" / "1305031102.175304.png").string(), labels);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  cv::Mat image_ = cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(9));
};

TEST_F(GroundTruthSegmenterTest, GivesExactMasksClassesAndMotionFlags) {
  GroundTruthSegmenter segmenter(dir_.string());
  const Segmentation seg = segmenter.Segment(image_, 1305031102.175304, 0);
  ASSERT_EQ(seg.instances.size(), 3u);
  EXPECT_EQ(seg.instances[0].source_id, 1);
  EXPECT_EQ(seg.instances[0].class_id, 0);
  EXPECT_EQ(seg.instances[0].class_name, "person");
  EXPECT_FLOAT_EQ(seg.instances[0].score, 1.0f);
  EXPECT_EQ(seg.instances[0].box, cv::Rect(2, 3, 10, 20));
  EXPECT_EQ(cv::countNonZero(seg.instances[0].mask), 200);
  EXPECT_EQ(seg.instances[1].class_id, 67);
  EXPECT_EQ(seg.instances[1].class_name, "cell phone");
  EXPECT_EQ(seg.instances[1].box, cv::Rect(30, 30, 6, 4));
  // A class outside COCO gets the first id after COCO's 80.
  EXPECT_EQ(seg.instances[2].class_id, 80);
  EXPECT_EQ(seg.instances[2].class_name, "cardboard box");
  ASSERT_EQ(segmenter.ClassNames().size(), 81u);
  EXPECT_TRUE(segmenter.IsMoving(9, 1305031102.211214));

  EXPECT_TRUE(segmenter.IsMoving(1, 1305031102.175304));
  EXPECT_FALSE(segmenter.IsMoving(7, 1305031102.175304));
  EXPECT_FALSE(segmenter.IsMoving(1, 1305031102.211214));
  EXPECT_FALSE(segmenter.IsMoving(42, 1305031102.175304));
  EXPECT_FALSE(segmenter.IsMoving(1, 1.0));
  EXPECT_EQ(segmenter.Instances().instances.size(), 3u);
}

// The runtime factory refuses the oracle; the tools' factory builds it from the sequence folder
// and leaves every other backend to the runtime factory.
TEST_F(GroundTruthSegmenterTest, OnlyTheEvaluationFactoryBuildsIt) {
  SegmentationOptions options;
  options.backend = SegmenterBackend::kGroundTruth;
  EXPECT_THROW(CreateSegmenter(options, dir_.string()), Error);
  const std::unique_ptr<Segmenter> segmenter = CreateEvaluationSegmenter(options, dir_.string());
  ASSERT_NE(segmenter, nullptr);
  EXPECT_EQ(segmenter->Segment(image_, 1305031102.175304, 0).instances.size(), 3u);
  EXPECT_THROW(CreateEvaluationSegmenter(options, ""), Error);
  EXPECT_THROW(CreateEvaluationSegmenter(options, (dir_ / "masks").string()), Error);
  options.backend = SegmenterBackend::kNone;
  EXPECT_EQ(CreateEvaluationSegmenter(options, dir_.string()), nullptr);
}

TEST_F(GroundTruthSegmenterTest, MissingFilesAndWrongSizesAreNamed) {
  GroundTruthSegmenter segmenter(dir_.string());
  const std::string missing = (dir_ / "masks" / "1305031102.211214.png").string();
  try {
    segmenter.Segment(image_, 1305031102.211214, 1);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  try {
    segmenter.Segment(cv::Mat(480, 640, CV_8UC3), 1305031102.175304, 0);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("1305031102.175304.png"), std::string::npos);
  }
  EXPECT_THROW(segmenter.Segment(image_, 99.0, 2), Error);  // no such frame in rgb.txt

  fs::remove(dir_ / "instances.txt");
  try {
    GroundTruthSegmenter broken(dir_.string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((dir_ / "instances.txt").string()), std::string::npos);
  }
}

TEST_F(GroundTruthSegmenterTest, UnlistedIdsInAMaskAreAnError) {
  cv::Mat labels = cv::Mat::zeros(48, 64, CV_16UC1);
  labels(cv::Rect(0, 0, 4, 4)).setTo(5);
  cv::imwrite((dir_ / "masks" / "1305031102.211214.png").string(), labels);
  GroundTruthSegmenter segmenter(dir_.string());
  try {
    segmenter.Segment(image_, 1305031102.211214, 1);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("instance id 5"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace drvslam
