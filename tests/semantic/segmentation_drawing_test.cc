#include "drvslam/semantic/segmentation_drawing.h"

#include <gtest/gtest.h>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

Segmentation Square() {
  Segmentation seg;
  seg.image_size = cv::Size(100, 80);
  Instance instance;
  instance.class_id = 0;
  instance.class_name = "person";
  instance.score = 0.9f;
  instance.box = cv::Rect(40, 30, 30, 40);
  instance.mask = cv::Mat::zeros(80, 100, CV_8UC1);
  instance.mask(cv::Rect(45, 35, 20, 30)).setTo(255);
  seg.instances.push_back(instance);
  return seg;
}

TEST(SegmentationDrawingTest, CutoutIsTheBoxWithTheMaskAsAlpha) {
  cv::Mat image(80, 100, CV_8UC3, cv::Scalar(10, 20, 30));
  image.at<cv::Vec3b>(50, 50) = cv::Vec3b(1, 2, 3);
  const Segmentation square = Square();
  const Instance& instance = square.instances[0];
  const cv::Mat cutout = MakeCutout(image, instance);
  ASSERT_EQ(cutout.type(), CV_8UC4);
  ASSERT_EQ(cutout.size(), cv::Size(30, 40));
  EXPECT_EQ(cutout.at<cv::Vec4b>(20, 10), cv::Vec4b(1, 2, 3, 255));  // image (50, 50)
  EXPECT_EQ(cutout.at<cv::Vec4b>(0, 0), cv::Vec4b(10, 20, 30, 0));
  std::vector<cv::Mat> planes;
  cv::split(cutout, planes);
  EXPECT_EQ(cv::countNonZero(planes[3]), 20 * 30);
  Instance empty = instance;
  empty.box = cv::Rect(200, 200, 5, 5);
  EXPECT_TRUE(MakeCutout(image, empty).empty());
}

TEST(SegmentationDrawingTest, OverlayTintsMasksAndLeavesTheRestAlone) {
  const cv::Mat image(80, 100, CV_8UC3, cv::Scalar(100, 100, 100));
  const cv::Mat overlay = DrawSegmentation(image, Square());
  ASSERT_EQ(overlay.size(), image.size());
  EXPECT_NE(overlay.at<cv::Vec3b>(50, 55), cv::Vec3b(100, 100, 100));  // inside the mask
  EXPECT_EQ(overlay.at<cv::Vec3b>(75, 5), cv::Vec3b(100, 100, 100));   // far from it
  Segmentation wrong = Square();
  wrong.instances[0].mask = cv::Mat::zeros(10, 10, CV_8UC1);
  EXPECT_THROW(DrawSegmentation(image, wrong), Error);
  EXPECT_NE(ClassColor(0), ClassColor(1));
}

}  // namespace
}  // namespace drvslam
