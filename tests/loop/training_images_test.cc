// Which images and frames vocabulary training reads, and how.
#include "drvslam/tools/vocab/training_images.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "test_support/missing_data.h"
#include "vocabulary_test_util.h"

namespace drvslam {
namespace {

TEST(TrainingImagesTest, FoldersListTheirImagesSortedAndCutAtMaxImages) {
  const std::string folder = test::ScratchFolder("listing");
  const cv::Mat image(50, 80, CV_8UC3, cv::Scalar(10, 20, 30));
  for (const char* name : {"b.png", "a.jpg", "c.PNG"}) {
    cv::imwrite(folder + "/" + name, image);
  }
  test::WriteText(folder + "/notes.txt", "not an image");
  TrainingImageOptions options;
  std::vector<TrainingImageSource> sources = ListTrainingImages({folder}, options);
  ASSERT_EQ(sources.size(), 3u);
  EXPECT_EQ(sources[0].path, folder + "/a.jpg");
  EXPECT_EQ(sources[1].path, folder + "/b.png");
  EXPECT_EQ(sources[2].path, folder + "/c.PNG");
  EXPECT_EQ(sources[0].frame, -1);
  EXPECT_EQ(sources[0].Name(), folder + "/a.jpg");
  options.max_images = 2;
  EXPECT_EQ(ListTrainingImages({folder, folder}, options).size(), 2u);
  options.max_images = 0;
  EXPECT_EQ(ListTrainingImages({folder, folder + "/a.jpg"}, options).size(), 4u);
}

TEST(TrainingImagesTest, ImagesAreGrayAndShrunkToMaxSide) {
  const std::string folder = test::ScratchFolder("shrink");
  cv::imwrite(folder + "/big.png", cv::Mat(300, 1200, CV_8UC3, cv::Scalar(0, 0, 255)));
  TrainingImageOptions options;
  options.max_side = 600;
  std::vector<cv::Mat> seen;
  ForEachTrainingImage(
      ListTrainingImages({folder}, options), options,
      [&](std::size_t, const TrainingImageSource&, const cv::Mat& gray) { seen.push_back(gray); });
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].type(), CV_8UC1);
  EXPECT_EQ(seen[0].cols, 600);
  EXPECT_EQ(seen[0].rows, 150);
  EXPECT_NEAR(seen[0].at<uint8_t>(75, 300), 76, 1);  // pure red in gray
}

TEST(TrainingImagesTest, VideosGiveEveryNthFrame) {
  const std::string video = std::string(DRVSLAM_OPENCV_DATA_DIR) + "/vtest.avi";
  if (!std::filesystem::is_regular_file(video)) DRVSLAM_MISSING_TEST_DATA() << video << " missing";
  TrainingImageOptions options;
  options.video_step = 200;
  const std::vector<TrainingImageSource> sources = ListTrainingImages({video}, options);
  ASSERT_GE(sources.size(), 3u);
  EXPECT_EQ(sources[1].frame, 200);
  EXPECT_EQ(sources[1].Name(), video + "#200");
  std::vector<cv::Mat> frames;
  ForEachTrainingImage(sources, options,
                       [&](std::size_t, const TrainingImageSource&, const cv::Mat& gray) {
                         frames.push_back(gray.clone());
                       });
  ASSERT_EQ(frames.size(), sources.size());
  // Different frames of a moving scene differ.
  EXPECT_GT(cv::norm(frames[0], frames[2], cv::NORM_L1), 0.0);
}

TEST(TrainingImagesTest, BadInputsNameThePath) {
  const std::string folder = test::ScratchFolder("bad_inputs");
  TrainingImageOptions options;
  const auto expect_error = [&](const std::string& input, const std::string& fragment) {
    try {
      ListTrainingImages({input}, options);
      ADD_FAILURE() << "no error for " << input;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(input + ": " + fragment), std::string::npos) << e.what();
    }
  };
  expect_error(folder + "/missing.png", "no such file or folder");
  expect_error(folder, "folder holds no image file");
  test::WriteText(folder + "/data.csv", "1,2");
  expect_error(folder + "/data.csv", "neither an image");
  test::WriteText(folder + "/broken.avi", "not a video");
  expect_error(folder + "/broken.avi", "cannot open video");
  test::WriteText(folder + "/broken.png", "not a png");
  try {
    ForEachTrainingImage(ListTrainingImages({folder + "/broken.png"}, options), options,
                         [](std::size_t, const TrainingImageSource&, const cv::Mat&) {});
    ADD_FAILURE() << "no error for a broken image";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.png: cannot decode image"), std::string::npos);
  }
  options.video_step = 0;
  EXPECT_THROW(ListTrainingImages({folder}, options), Error);
}

}  // namespace
}  // namespace drvslam
