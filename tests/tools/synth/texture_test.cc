#include "drvslam/tools/synth/texture.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "drvslam/tools/synth/photo_library.h"
#include "drvslam/tools/synth/texture_painter.h"
#include "test_folder.h"
#include "test_support/missing_data.h"

namespace drvslam::synth {
namespace {

using testing::TestFolder;
using testing::WriteFileText;

double Contrast(const cv::Mat& image) {
  cv::Mat grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  cv::Scalar mean, stddev;
  cv::meanStdDev(grey, mean, stddev);
  return stddev[0];
}

TEST(TextureTest, PaintingIsDeterministicAndSeedDependent) {
  const PhotoLibrary none;
  for (const TextureStyle style :
       {TextureStyle::kCollage, TextureStyle::kProcedural, TextureStyle::kCloth,
        TextureStyle::kSkin, TextureStyle::kKeyboard, TextureStyle::kLabel, TextureStyle::kPlaster,
        TextureStyle::kWood, TextureStyle::kDesk}) {
    TextureRequest request;
    request.width_m = 0.6;
    request.height_m = 0.4;
    request.texels_per_metre = 200.0;
    request.style = style;
    request.seed = 11;
    request.colour = {60, 140, 200};
    request.face_rect = cv::Rect2d(0.2, 0.2, 0.3, 0.6);
    const cv::Mat a = PaintTexture(request, none);
    const cv::Mat b = PaintTexture(request, none);
    ASSERT_EQ(a.size(), cv::Size(120, 80)) << static_cast<int>(style);
    EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0) << static_cast<int>(style);
    request.seed = 12;
    EXPECT_GT(cv::norm(a, PaintTexture(request, none), cv::NORM_L1), 0.0);
    // Never flat: detail is what features are made of.
    EXPECT_GT(Contrast(a), 12.0) << static_cast<int>(style);
  }
}

TEST(TextureTest, LargeSurfacesAreCappedAndToned) {
  TextureRequest request;
  request.width_m = 10.0;
  request.height_m = 2.5;
  request.texels_per_metre = 320.0;
  request.max_side = 1000;
  EXPECT_EQ(request.PixelSize(), cv::Size(1000, 250));
  request.width_m = 0.6;
  request.height_m = 0.6;
  request.style = TextureStyle::kProcedural;
  const cv::Mat full = PaintTexture(request, PhotoLibrary());
  request.saturation = 0.0;
  request.brightness = 0.5;
  const cv::Mat toned = PaintTexture(request, PhotoLibrary());
  std::vector<cv::Mat> channels;
  cv::split(toned, channels);
  EXPECT_LE(cv::norm(channels[0], channels[2], cv::NORM_INF), 1.0);  // grey
  cv::Mat grey;
  cv::cvtColor(full, grey, cv::COLOR_BGR2GRAY);
  EXPECT_NEAR(cv::mean(toned)[0], 0.5 * cv::mean(grey)[0], 2.0);
}

TEST(TextureTest, ProceduralWallIsRichInOrbFeatures) {
  TextureRequest request;
  request.width_m = 2.0;
  request.height_m = 1.5;
  request.texels_per_metre = 320.0;
  request.style = TextureStyle::kCollage;
  request.seed = 3;
  const cv::Mat wall = PaintTexture(request, PhotoLibrary());
  cv::Mat grey;
  cv::cvtColor(wall, grey, cv::COLOR_BGR2GRAY);
  std::vector<cv::KeyPoint> keypoints;
  cv::ORB::create(1000)->detect(grey, keypoints);
  EXPECT_GE(keypoints.size(), 900u);
}

TEST(TextureTest, MipmapsAndSampling) {
  cv::Mat image(64, 32, CV_8UC3, cv::Scalar(10, 20, 30));
  image.at<cv::Vec3b>(5, 7) = cv::Vec3b(200, 100, 50);
  const Texture texture(image);
  EXPECT_EQ(texture.Width(), 32);
  EXPECT_EQ(texture.Height(), 64);
  EXPECT_EQ(texture.LevelCount(), 4);  // 32x64, 16x32, 8x16, 4x8
  EXPECT_FALSE(texture.HasTransparency());
  float bgr[3];
  // At a texel centre, level 0 returns the texel.
  texture.Sample((7 + 0.5f) / 32, (5 + 0.5f) / 64, 0.0f, bgr);
  EXPECT_NEAR(bgr[0], 200.0f, 1e-3);
  EXPECT_NEAR(bgr[2], 50.0f, 1e-3);
  // Far away (coarsest level) the lone texel is averaged away.
  texture.Sample((7 + 0.5f) / 32, (5 + 0.5f) / 64, 10.0f, bgr);
  EXPECT_LT(bgr[0], 40.0f);
  cv::Mat rgba(8, 8, CV_8UC4, cv::Scalar(1, 2, 3, 255));
  rgba.at<cv::Vec4b>(0, 0)[3] = 0;
  const Texture cutout(rgba);
  EXPECT_TRUE(cutout.HasTransparency());
  EXPECT_FALSE(cutout.Opaque(0.01f, 0.01f));
  EXPECT_TRUE(cutout.Opaque(0.5f, 0.5f));
  EXPECT_THROW(static_cast<void>(Texture(cv::Mat())), Error);
  EXPECT_THROW(Texture(cv::Mat(4, 4, CV_32FC1)), Error);
}

TEST(PhotoLibraryTest, FolderErrorsNameTheProblem) {
  TestFolder folder("photos");
  try {
    PhotoLibrary::FromFolder(folder.Path());
    ADD_FAILURE() << "an empty folder was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no images"), std::string::npos) << e.what();
  }
  EXPECT_THROW(PhotoLibrary::FromFolder(folder / "missing"), Error);
  WriteFileText(folder / "broken.jpg", "not a jpeg");
  try {
    PhotoLibrary::FromFolder(folder.Path());
    ADD_FAILURE() << "an undecodable image was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.jpg"), std::string::npos) << e.what();
  }
  std::filesystem::remove(folder / "broken.jpg");
  cv::imwrite(folder / "b.png", cv::Mat(40, 50, CV_8UC3, cv::Scalar(1, 2, 3)));
  cv::imwrite(folder / "a.png", cv::Mat(60, 40, CV_8UC1, cv::Scalar(9)));
  const PhotoLibrary library = PhotoLibrary::FromFolder(folder.Path());
  ASSERT_EQ(library.Size(), 2);
  EXPECT_EQ(library.Names()[0], "a.png");
  EXPECT_EQ(library.Photo(0).type(), CV_8UC3);
  EXPECT_EQ(library.Source(), folder.Path());
  EXPECT_TRUE(PhotoLibrary::OpenCvSamples(folder / "missing").Empty());
}

TEST(PhotoLibraryTest, OpenCvSamplesWhenInstalled) {
  const PhotoLibrary library = PhotoLibrary::OpenCvSamples(DRVSLAM_OPENCV_DATA_DIR);
  if (library.Empty())
    DRVSLAM_MISSING_TEST_DATA() << "no opencv-doc photos in " << DRVSLAM_OPENCV_DATA_DIR;
  EXPECT_GE(library.Size(), 10);
  for (const std::string& name : library.Names()) {
    EXPECT_NE(name, "messi5.jpg");  // people stay off the walls
    EXPECT_NE(name, "lena.jpg");
  }
}

}  // namespace
}  // namespace drvslam::synth
