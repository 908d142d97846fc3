// Lens distortion in the generator: the model is OpenCV's, the distortion map and the renders
// put points where cv::projectPoints does, and a distorted sequence states its coefficients.
#include "drvslam/tools/synth/lens_distortion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "drvslam/core/settings.h"
#include "drvslam/core/settings_file.h"
#include "drvslam/tools/synth/shutter_renderer.h"
#include "drvslam/tools/synth/synth_generator.h"
#include "drvslam/tools/synth/synth_sequence.h"
#include "raster_test_scene.h"
#include "real_camera_test_util.h"
#include "test_folder.h"

namespace drvslam::synth {
namespace {

using testing::AddFacingRect;
using testing::SmallOptions;
using testing::TestCamera;
using testing::TestFolder;
using testing::TwoTextures;
using testing::Unlit;

cv::Point2d MaskCentroid(const cv::Mat& binary) {
  const cv::Moments m = cv::moments(binary, true);
  return {m.m10 / m.m00, m.m01 / m.m00};
}

// `camera`'s distortion coefficients as cv::projectPoints takes them: k1, k2, p1, p2, k3.
cv::Mat OpenCvCoefficients(const CameraOptions& camera) {
  return (cv::Mat_<double>(1, 5) << camera.k1, camera.k2, camera.p1, camera.p2, camera.k3);
}

// `camera`'s intrinsic matrix as cv::projectPoints takes it.
cv::Mat OpenCvCameraMatrix(const CameraOptions& camera) {
  return (cv::Mat_<double>(3, 3) << camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
}

TEST(RealCameraTest, DistortionModelIsOpenCvsAndInvertsExactly) {
  RealCameraOptions options;
  options.SetDistortion("fr1");
  // TestCamera() with the fr1 lens: the options ask for no calibration error.
  const CameraOptions camera = StatedCamera(TestCamera(), options);
  const LensDistortion lens = LensDistortion::Of(camera);
  const cv::Mat K = (cv::Mat_<double>(3, 3) << 1, 0, 0, 0, 1, 0, 0, 0, 1);
  const cv::Mat coefficients = OpenCvCoefficients(camera);
  std::vector<cv::Point3d> points;
  for (double x = -0.6; x <= 0.6; x += 0.15) {
    for (double y = -0.45; y <= 0.45; y += 0.15) points.emplace_back(x, y, 1.0);
  }
  std::vector<cv::Point2d> projected;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, coefficients, projected);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d d = lens.Distort({points[i].x, points[i].y});
    EXPECT_NEAR(d.x(), projected[i].x, 1e-12);
    EXPECT_NEAR(d.y(), projected[i].y, 1e-12);
    Eigen::Vector2d back;
    ASSERT_TRUE(lens.Undistort(d, &back));
    EXPECT_NEAR(back.x(), points[i].x, 1e-10);
    EXPECT_NEAR(back.y(), points[i].y, 1e-10);
  }
  // A model that folds over inside the image is refused, naming the flag.
  CameraOptions folding = TestCamera();
  folding.k1 = -2.0;
  try {
    const DistortionMap map(folding);
    FAIL() << "a folding model was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("--distortion"), std::string::npos);
  }
}

TEST(RealCameraTest, DistortionMapSendsEveryPixelAlongItsRay) {
  RealCameraOptions options;
  options.SetDistortion("fr1");
  // TestCamera() with the fr1 lens: the options ask for no calibration error.
  const CameraOptions camera = StatedCamera(TestCamera(), options);
  const DistortionMap map(camera);
  const CameraOptions& canvas = map.Canvas();
  EXPECT_DOUBLE_EQ(canvas.fx, camera.fx);
  EXPECT_FALSE(canvas.HasDistortion());
  // The ray through each canvas position, projected with OpenCV's model, is the sensor pixel.
  std::vector<cv::Point3d> rays;
  std::vector<cv::Point2d> pixels;
  for (int y = 0; y < camera.height; y += 7) {
    for (int x = 0; x < camera.width; x += 7) {
      rays.emplace_back((map.CanvasX(x, y) - canvas.cx) / canvas.fx,
                        (map.CanvasY(x, y) - canvas.cy) / canvas.fy, 1.0);
      pixels.emplace_back(x, y);
    }
  }
  const cv::Mat K = OpenCvCameraMatrix(camera);
  const cv::Mat coefficients = OpenCvCoefficients(camera);
  std::vector<cv::Point2d> projected;
  cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, coefficients, projected);
  double worst = 0.0, moved = 0.0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    worst = std::max(worst, cv::norm(projected[i] - pixels[i]));
    const cv::Point2d pinhole(camera.fx * rays[i].x + camera.cx, camera.fy * rays[i].y + camera.cy);
    moved = std::max(moved, cv::norm(pinhole - pixels[i]));
  }
  EXPECT_LT(worst, 1e-3);  // float storage of the map
  EXPECT_GT(moved, 10.0);
  // The canvas holds every position and its bilinear neighbours, with a pixel of margin.
  for (int y = 0; y < camera.height; ++y) {
    for (const int x : {0, camera.width - 1}) {
      EXPECT_GE(map.CanvasX(x, y), 1.0f);
      EXPECT_LT(map.CanvasX(x, y), canvas.width - 1.0f);
      EXPECT_GE(map.CanvasY(x, y), 1.0f);
      EXPECT_LT(map.CanvasY(x, y), canvas.height - 1.0f);
    }
  }
}

TEST(RealCameraTest, DistortedRenderPutsKnownPointsWhereProjectPointsDoes) {
  RealCameraOptions options;
  options.SetDistortion("fr1");
  // TestCamera() with the fr1 lens: the options ask for no calibration error.
  const CameraOptions camera = StatedCamera(TestCamera(), options);
  // 2 cm white squares at 2 m over the whole view, corners included (where fr1 moves points by
  // more than 10 px), each with its own instance id.
  std::vector<cv::Point3d> centres;
  TriangleList squares;
  for (int i = -3; i <= 3; ++i) {
    for (int j = -2; j <= 2; ++j) {
      const cv::Point3d c(i * 0.38, j * 0.4, 2.0);
      AddFacingRect({c.x, c.y, c.z}, 0.02, 0.02, static_cast<int>(centres.size()) + 1, 1, &squares);
      centres.push_back(c);
    }
  }
  const ShutterRenderer renderer(camera, options, Unlit());
  const auto still = [&](double, SE3* T_cw, TriangleList*) { *T_cw = SE3(); };
  RenderBuffers out;
  renderer.Render(squares, TwoTextures(), still, &out);
  const cv::Mat K = OpenCvCameraMatrix(camera);
  const cv::Mat coefficients = OpenCvCoefficients(camera);
  std::vector<cv::Point2d> projected;
  cv::projectPoints(centres, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, coefficients, projected);
  double largest_shift = 0.0;
  for (std::size_t k = 0; k < centres.size(); ++k) {
    const cv::Mat mask = out.instance == static_cast<int>(k + 1);
    ASSERT_GT(cv::countNonZero(mask), 10) << k;
    const cv::Point2d at = MaskCentroid(mask);
    // Within a pixel: the square's edges are quantized twice, to the canvas pixel centres and
    // to the nearest canvas pixel of each sensor pixel.
    EXPECT_NEAR(at.x, projected[k].x, 1.0) << k;
    EXPECT_NEAR(at.y, projected[k].y, 1.0) << k;
    const cv::Point2d pinhole(camera.fx * centres[k].x / 2.0 + camera.cx,
                              camera.fy * centres[k].y / 2.0 + camera.cy);
    largest_shift = std::max(largest_shift, cv::norm(projected[k] - pinhole));
    // Colour and depth agree with the mask.
    cv::Mat grey, white;
    cv::cvtColor(out.bgr, grey, cv::COLOR_BGR2GRAY);
    const cv::Rect around(static_cast<int>(at.x) - 10, static_cast<int>(at.y) - 10, 21, 21);
    white = grey(around) > 125;
    const cv::Point2d colour_at = MaskCentroid(white) + cv::Point2d(around.x, around.y);
    EXPECT_NEAR(colour_at.x, at.x, 0.5) << k;
    EXPECT_NEAR(colour_at.y, at.y, 0.5) << k;
    cv::Mat disagree;
    cv::bitwise_xor(white, mask(around), disagree);
    EXPECT_LE(cv::countNonZero(disagree), cv::countNonZero(mask(around)) / 2) << k;
    double lo = 0.0, hi = 0.0;
    cv::minMaxLoc(out.depth, &lo, &hi, nullptr, nullptr, mask);
    EXPECT_FLOAT_EQ(static_cast<float>(lo), 2.0f);
    EXPECT_FLOAT_EQ(static_cast<float>(hi), 2.0f);
  }
  EXPECT_GT(largest_shift, 10.0);  // the test would notice a missing distortion
}

TEST(RealCameraTest, DistortedSequenceStatesItsCoefficientsAndKeepsMasksWithColour) {
  TestFolder folder("distorted");
  SynthOptions options = SmallOptions("walking_xyz", 3);
  options.real_camera.SetDistortion("0.2,-0.1,0.001,-0.002,0.05");
  GenerateSequence(options, folder.Path());
  const Settings settings = LoadSettings(SettingsFile(folder / "settings.yaml"));
  EXPECT_DOUBLE_EQ(settings.camera.k1, 0.2);
  EXPECT_DOUBLE_EQ(settings.camera.k2, -0.1);
  EXPECT_DOUBLE_EQ(settings.camera.p1, 0.001);
  EXPECT_DOUBLE_EQ(settings.camera.p2, -0.002);
  EXPECT_DOUBLE_EQ(settings.camera.k3, 0.05);
  EXPECT_DOUBLE_EQ(settings.camera.fx, options.Camera().fx);  // no calibration error asked
  // Masks, colour and depth of a distorted frame come from one canvas pixel per sensor pixel:
  // the frame's masks equal the undistorted masks remapped by nearest neighbour.
  const SynthSequence distorted(options);
  SynthOptions pinhole_options = options;
  pinhole_options.real_camera = RealCameraOptions();
  const SynthSequence pinhole(pinhole_options);
  const RenderBuffers d = distorted.Render(1, false);
  const DistortionMap map(options.Camera());
  const Rasterizer canvas_rasterizer(map.Canvas());
  TriangleList movers;
  pinhole.Actors().AppendTriangles(1, &movers);
  RenderBuffers canvas;
  canvas_rasterizer.Render({&pinhole.Scene().triangles, &movers}, pinhole.Textures(),
                           pinhole.Pose(1).Inverse(), &canvas);
  int mismatches = 0;
  for (int y = 0; y < 240; ++y) {
    for (int x = 0; x < 320; ++x) {
      const int u = static_cast<int>(std::lround(map.CanvasX(x, y)));
      const int v = static_cast<int>(std::lround(map.CanvasY(x, y)));
      mismatches += d.instance.at<uint16_t>(y, x) != canvas.instance.at<uint16_t>(v, u);
      mismatches += d.depth.at<float>(y, x) != canvas.depth.at<float>(v, u);
    }
  }
  EXPECT_EQ(mismatches, 0);
  // A global-shutter depth sensor behind a rolling colour shutter gives the same depth image.
  SynthOptions rolling_options = options;
  rolling_options.real_camera.rolling_shutter_readout = 0.03;
  rolling_options.real_camera.depth_global_shutter = true;
  const RenderBuffers rolling = SynthSequence(rolling_options).Render(1, false);
  EXPECT_EQ(cv::norm(rolling.depth, d.depth, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(rolling.instance, d.instance, cv::NORM_L1), 0.0);  // the masks do shear
  // The distortion changes the image (k1 = 0.2 moves the corners by several pixels).
  EXPECT_GT(cv::norm(d.instance, pinhole.Render(1, false).instance, cv::NORM_L1), 0.0);
}
}  // namespace
}  // namespace drvslam::synth
