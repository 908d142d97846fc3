#include "drvslam/semantic/mask_file_segmenter.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "drvslam/core/coco_classes.h"
#include "drvslam/core/error.h"
#include "drvslam/semantic/segmenter_factory.h"
#include "test_data.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

class MaskFileSegmenterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::FreshTempDir(std::string("mask_files_") +
                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
    masks_ = dir_ / "masks";
    fs::create_directories(masks_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A 16-bit id image: id 300 a rectangle, id 7 an L shape.
  static cv::Mat Labels16() {
    cv::Mat labels = cv::Mat::zeros(48, 64, CV_16UC1);
    labels(cv::Rect(10, 5, 20, 30)).setTo(300);
    labels(cv::Rect(40, 10, 5, 30)).setTo(7);
    labels(cv::Rect(40, 35, 20, 5)).setTo(7);
    return labels;
  }

  void ExpectError(const std::function<void()>& run, const std::string& needle1,
                   const std::string& needle2) {
    try {
      run();
      FAIL() << "no error (" << needle1 << ")";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(needle1), std::string::npos) << message;
      EXPECT_NE(message.find(needle2), std::string::npos) << message;
    }
  }

  fs::path dir_;
  fs::path masks_;
  cv::Mat image_ = cv::Mat(48, 64, CV_8UC3, cv::Scalar(1, 2, 3));
};

TEST_F(MaskFileSegmenterTest, SixteenBitIdsByTimestampWithInstancesFile) {
  ASSERT_TRUE(cv::imwrite((masks_ / "1305031102.175304.png").string(), Labels16()));
  ASSERT_TRUE(
      cv::imwrite((masks_ / "1305031102.211214.png").string(), cv::Mat::zeros(48, 64, CV_16UC1)));
  std::ofstream(dir_ / "instances.txt") << "# id class coco\n"
                                           "instance 300 person 0\n"
                                           "instance 7 cell_phone 67\n"
                                           "12 forklift\n"
                                           "frame 1305031102.175304 1 0\n";
  MaskFileSegmenter segmenter(masks_.string(), SegmentationOptions());
  // A stamp that differs in the 7th decimal still finds its file.
  const Segmentation seg = segmenter.Segment(image_, 1305031102.1753041, 3);
  EXPECT_EQ(seg.frame_index, 3u);
  EXPECT_EQ(seg.image_size, image_.size());
  ASSERT_EQ(seg.instances.size(), 2u);
  const Instance& phone = seg.instances[0];  // increasing id order
  EXPECT_EQ(phone.source_id, 7);
  EXPECT_EQ(phone.class_id, 67);
  EXPECT_EQ(phone.class_name, "cell phone");
  EXPECT_FLOAT_EQ(phone.score, 1.0f);
  EXPECT_EQ(phone.box, cv::Rect(40, 10, 20, 30));
  EXPECT_EQ(cv::countNonZero(phone.mask), 5 * 30 + 15 * 5);
  const Instance& person = seg.instances[1];
  EXPECT_EQ(person.source_id, 300);
  EXPECT_EQ(person.class_name, "person");
  EXPECT_EQ(person.box, cv::Rect(10, 5, 20, 30));
  EXPECT_EQ(cv::countNonZero(person.mask), 600);
  EXPECT_EQ(person.mask.at<unsigned char>(5, 10), 255);
  EXPECT_EQ(person.mask.at<unsigned char>(4, 10), 0);
  EXPECT_TRUE(segmenter.Segment(image_, 1305031102.211214, 4).instances.empty());
  // A class named only by name follows COCO's 80.
  ASSERT_EQ(segmenter.ClassNames().size(), 81u);
  EXPECT_EQ(segmenter.ClassNames()[80], "forklift");
}

TEST_F(MaskFileSegmenterTest, BinaryMasksByIndexAreOneInstanceOfTheSettingsClass) {
  cv::Mat binary = cv::Mat::zeros(48, 64, CV_8UC1);
  binary(cv::Rect(3, 4, 10, 12)).setTo(255);
  ASSERT_TRUE(cv::imwrite((masks_ / "000004.png").string(), binary));
  ASSERT_TRUE(cv::imwrite((masks_ / "5.png").string(), binary));
  SegmentationOptions options;
  const Segmentation seg = MaskFileSegmenter(masks_.string(), options).Segment(image_, 0.13, 4);
  ASSERT_EQ(seg.instances.size(), 1u);
  EXPECT_EQ(seg.instances[0].class_name, "person");
  EXPECT_EQ(seg.instances[0].box, cv::Rect(3, 4, 10, 12));
  EXPECT_EQ(cv::countNonZero(seg.instances[0].mask), 120);

  options.mask_class = "dog";
  MaskFileSegmenter dogs(masks_.string(), options);
  EXPECT_EQ(dogs.Segment(image_, 0.0, 5).instances.at(0).class_id, CocoClassId("dog"));
  ExpectError([&] { dogs.Segment(image_, 0.0, 6); }, (masks_ / "6.png").string(), "frame 6");
}

TEST_F(MaskFileSegmenterTest, FrameNamesPickTheMaskOfTheColourImage) {
  ASSERT_TRUE(cv::imwrite((masks_ / "img_a.png").string(), Labels16()));
  SegmentationOptions options;
  options.backend = SegmenterBackend::kMaskFiles;
  options.masks_dir = "masks";  // relative: under the dataset folder
  const std::unique_ptr<Segmenter> segmenter =
      CreateSegmenter(options, dir_.string(), {"rgb/img_a.jpg", "rgb/img_b.jpg"});
  EXPECT_EQ(segmenter->Segment(image_, 0.0, 0).instances.size(), 2u);
  ExpectError([&] { segmenter->Segment(image_, 0.0, 1); }, (masks_ / "img_b.png").string(),
              "no mask file");
  ExpectError([&] { segmenter->Segment(image_, 0.0, 2); }, masks_.string(), "past the 2");
}

TEST_F(MaskFileSegmenterTest, FactoryBuildsTheNamedBackend) {
  SegmentationOptions options;
  EXPECT_EQ(CreateSegmenter(options, dir_.string()), nullptr);  // backend none
  options.backend = SegmenterBackend::kGroundTruth;
  EXPECT_THROW(CreateSegmenter(options, dir_.string()), Error);  // an evaluation-only backend
  options.backend = SegmenterBackend::kYolo;
  EXPECT_THROW(CreateSegmenter(options), Error);  // no model
  options.model = (dir_ / "absent.onnx").string();
  EXPECT_THROW(CreateSegmenter(options), Error);
  ASSERT_TRUE(cv::imwrite((masks_ / "0.png").string(), Labels16()));
  options.backend = SegmenterBackend::kMaskFiles;
  options.masks_dir = masks_.string();  // absolute: the dataset folder does not matter
  const std::unique_ptr<Segmenter> masks = CreateSegmenter(options, "/elsewhere");
  ASSERT_NE(masks, nullptr);
  EXPECT_EQ(masks->Name(), "masks(" + masks_.string() + ")");
}

TEST_F(MaskFileSegmenterTest, BadInputsNameTheFile) {
  ExpectError([&] { MaskFileSegmenter((dir_ / "nope").string(), SegmentationOptions()); },
              (dir_ / "nope").string(), "does not exist");
  ExpectError([&] { MaskFileSegmenter(masks_.string(), SegmentationOptions()); }, masks_.string(),
              "no .png");

  ASSERT_TRUE(cv::imwrite((masks_ / "1.000000.png").string(), Labels16()));
  std::ofstream((masks_ / "2.000000.png").string()) << "not a png at all";
  cv::Mat colour(48, 64, CV_8UC3, cv::Scalar(1, 2, 3));
  ASSERT_TRUE(cv::imwrite((masks_ / "3.000000.png").string(), colour));
  MaskFileSegmenter segmenter(masks_.string(), SegmentationOptions());
  // Wrong image size.
  ExpectError([&] { segmenter.Segment(cv::Mat(480, 640, CV_8UC3), 1.0, 0); },
              (masks_ / "1.000000.png").string(), "64x48");
  ExpectError([&] { segmenter.Segment(image_, 2.0, 1); }, (masks_ / "2.000000.png").string(),
              "not a readable image");
  ExpectError([&] { segmenter.Segment(image_, 3.0, 2); }, (masks_ / "3.000000.png").string(),
              "colour");
  ExpectError([&] { segmenter.Segment(image_, 4.0, 3); }, "4.000000.png", "no mask file");
  ExpectError([&] { segmenter.Segment(cv::Mat(), 1.0, 0); }, "frame 0", "empty");

  std::ofstream(masks_ / "instances.txt") << "instance 1 person 0\ninstance 2 dog 99\n";
  ExpectError([&] { MaskFileSegmenter(masks_.string(), SegmentationOptions()); },
              (masks_ / "instances.txt").string() + ":2", "-1..79");
  std::ofstream(masks_ / "instances.txt") << "instance 1 person 0\ninstance 1 dog 16\n";
  ExpectError([&] { MaskFileSegmenter(masks_.string(), SegmentationOptions()); },
              (masks_ / "instances.txt").string() + ":2", "twice");
  std::ofstream(masks_ / "instances.txt") << "instance 0 person 0\n";
  ExpectError([&] { MaskFileSegmenter(masks_.string(), SegmentationOptions()); },
              (masks_ / "instances.txt").string() + ":1", "1..65535");
}

}  // namespace
}  // namespace drvslam
