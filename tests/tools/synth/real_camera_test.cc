// Real-camera effects of the generator, each measured alone: motion blur, rolling shutter,
// depth misregistration, calibration error and lens distortion.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "drvslam/core/settings.h"
#include "drvslam/core/settings_file.h"
#include "drvslam/tools/synth/depth_shift.h"
#include "drvslam/tools/synth/lens_distortion.h"
#include "drvslam/tools/synth/shutter_renderer.h"
#include "drvslam/tools/synth/synth_generator.h"
#include "drvslam/tools/synth/synth_sequence.h"
#include "raster_test_scene.h"
#include "test_folder.h"

namespace drvslam::synth {
namespace {

using testing::AddFacingRect;
using testing::ReadFileBytes;
using testing::SolidTextures;
using testing::TestCamera;
using testing::TestFolder;
using testing::Unlit;

// Texture 0 dark grey, texture 1 white.
std::vector<Texture> TwoTextures() {
  return SolidTextures({cv::Scalar(20, 20, 20), cv::Scalar(230, 230, 230)});
}

// A dark wall at z = 4 behind everything.
TriangleList Wall() {
  TriangleList wall;
  AddFacingRect({0, 0, 4.0}, 20.0, 20.0, 0, 0, &wall);
  return wall;
}

// Sum of squared Sobel gradients of the grey image.
double GradientEnergy(const cv::Mat& bgr) {
  cv::Mat grey, gx, gy;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  cv::Sobel(grey, gx, CV_32F, 1, 0);
  cv::Sobel(grey, gy, CV_32F, 0, 1);
  return cv::sum(gx.mul(gx) + gy.mul(gy))[0];
}

// Left edge (first column of `id`) on each row; -1 where the row has none.
std::vector<int> LeftEdges(const cv::Mat& ids, int id) {
  std::vector<int> edges(ids.rows, -1);
  for (int y = 0; y < ids.rows; ++y) {
    for (int x = 0; x < ids.cols; ++x) {
      if (ids.at<uint16_t>(y, x) == id) {
        edges[y] = x;
        break;
      }
    }
  }
  return edges;
}

cv::Point2d Centroid(const cv::Mat& binary) {
  const cv::Moments m = cv::moments(binary, true);
  return {m.m10 / m.m00, m.m01 / m.m00};
}

SynthOptions SmallOptions(const std::string& scenario, int frames) {
  SynthOptions options;
  options.scenario = scenario;
  options.frames = frames;
  options.width = 320;
  options.height = 240;
  options.seed = 5;
  options.procedural_textures = true;
  options.sensor = SensorOptions::Clean();
  return options;
}

// --- Motion blur ---------------------------------------------------------------------------

// The wall and the scene at each exposure offset, rendered by a plain renderer into *plain and by
// one with `effects` into *with_effects.
void RenderPlainAndWith(const RealCameraOptions& effects, const ShutterRenderer::SceneAt& scene,
                        RenderBuffers* plain, RenderBuffers* with_effects) {
  const TriangleList wall = Wall();
  ShutterRenderer(TestCamera(), RealCameraOptions(), Unlit())
      .Render(wall, TwoTextures(), scene, plain);
  ShutterRenderer(TestCamera(), effects, Unlit()).Render(wall, TwoTextures(), scene, with_effects);
}

// A still camera and a `width` x `height` m rectangle (instance 1) at 2 m depth, moving right at
// `speed` m/s: at the exposure offset t it is centred speed * t m right of the optical axis.
ShutterRenderer::SceneAt MovingRectangle(double speed, double width, double height) {
  return [=](double offset, SE3* T_cw, TriangleList* out) {
    *T_cw = SE3();
    AddFacingRect({speed * offset, 0.0, 2.0}, width, height, 3, 1, out);
  };
}

TEST(RealCameraTest, BlurOfAStillSceneChangesNothing) {
  TriangleList movers;
  AddFacingRect({0.1, -0.05, 2.0}, 0.6, 0.4, 3, 1, &movers);
  const auto still = [&](double, SE3* T_cw, TriangleList* out) {
    *T_cw = SE3();
    out->insert(out->end(), movers.begin(), movers.end());
  };
  RealCameraOptions blur;
  blur.blur_exposure = 0.05;
  blur.blur_samples = 6;  // even: depth and masks then come from an extra centre render
  RenderBuffers a, b;
  RenderPlainAndWith(blur, still, &a, &b);
  EXPECT_EQ(cv::norm(a.bgr, b.bgr, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.depth, b.depth, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.instance, b.instance, cv::NORM_INF), 0.0);
}

TEST(RealCameraTest, BlurSmearsAMovingActorOverItsPathAndKeepsTheMaskAtTheCentre) {
  // A white rectangle moving right at 1 m/s at 2 m depth: 250 px/s on the image, so a 40 ms
  // exposure smears its edges over 10 px. The camera stands still.
  RealCameraOptions blur;
  blur.blur_exposure = 0.04;
  blur.blur_samples = 9;
  RenderBuffers a, b;
  RenderPlainAndWith(blur, MovingRectangle(1.0, 0.6, 0.4), &a, &b);
  // Masks and depth are those of the exposure's centre.
  EXPECT_EQ(cv::norm(a.instance, b.instance, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.depth, b.depth, cv::NORM_INF), 0.0);
  // Along the middle row, the left edge (x = 245.25 at the centre) ramps from dark to white
  // over 10 px centred on it: 9 grey steps.
  const int y = 240;
  int ramp_begin = -1, ramp_end = -1;
  for (int x = 100; x < 300; ++x) {
    const int value = b.bgr.at<cv::Vec3b>(y, x)[1];
    if (value > 25 && value < 225) {
      if (ramp_begin < 0) ramp_begin = x;
      ramp_end = x;
    }
  }
  EXPECT_EQ(ramp_begin, 241);
  EXPECT_EQ(ramp_end, 249);
  // Pixel 245 is covered by the four samples whose edge (245.25 + 250 px/s * offset) lies
  // left of it.
  EXPECT_NEAR(b.bgr.at<cv::Vec3b>(y, 245)[1], 20 + 210 * 4 / 9.0, 1.0);
  // Rows away from the rectangle are untouched.
  EXPECT_EQ(cv::norm(a.bgr.rowRange(0, 100), b.bgr.rowRange(0, 100), cv::NORM_INF), 0.0);
}

TEST(RealCameraTest, BlurLowersTheGradientEnergyOfAMovingCameraFrame) {
  SynthOptions options = SmallOptions("static_rpy", 40);
  const SynthSequence sharp(options);
  options.real_camera.blur_exposure = 0.03;
  const SynthSequence blurred(options);
  // The hand-shaken static camera still moves a little; the rotating one a lot.
  SynthOptions still_options = SmallOptions("static_static", 40);
  const SynthSequence still_sharp(still_options);
  still_options.real_camera.blur_exposure = 0.03;
  const SynthSequence still_blurred(still_options);
  const int f = 30;
  const double moving_ratio =
      GradientEnergy(blurred.Render(f).bgr) / GradientEnergy(sharp.Render(f).bgr);
  const double still_ratio =
      GradientEnergy(still_blurred.Render(f).bgr) / GradientEnergy(still_sharp.Render(f).bgr);
  RecordProperty("moving_gradient_ratio", std::to_string(moving_ratio));
  RecordProperty("still_gradient_ratio", std::to_string(still_ratio));
  EXPECT_LT(moving_ratio, 0.85);
  EXPECT_GT(still_ratio, 0.97);
  EXPECT_LT(still_ratio, 1.0 + 1e-9);
  // Blur does not move the frame: depth and masks are the timestamp's.
  EXPECT_EQ(cv::norm(blurred.Render(f).instance, sharp.Render(f).instance, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(blurred.Render(f).depth, sharp.Render(f).depth, cv::NORM_INF), 0.0);
}

// --- Rolling shutter -----------------------------------------------------------------------

TEST(RealCameraTest, RollingShutterRowTimesAreCentredOnTheMiddleOfTheImage) {
  RealCameraOptions options;
  options.rolling_shutter_readout = 0.03;
  options.rolling_shutter_steps = 480;  // one band per row: exact row times
  const ShutterRenderer renderer(TestCamera(), options);
  for (const int row : {0, 100, 239, 240, 479}) {
    EXPECT_NEAR(renderer.RowOffset(row), ((row + 0.5) / 480.0 - 0.5) * 0.03, 1e-15) << row;
  }
  EXPECT_DOUBLE_EQ(renderer.RowOffset(0), -renderer.RowOffset(479));
  options.rolling_shutter_steps = 60;  // bands of 8 rows share their middle's time
  const ShutterRenderer banded(TestCamera(), options);
  EXPECT_DOUBLE_EQ(banded.RowOffset(0), (4.0 / 480.0 - 0.5) * 0.03);
  EXPECT_DOUBLE_EQ(banded.RowOffset(7), banded.RowOffset(0));
  EXPECT_DOUBLE_EQ(banded.RowOffset(8), (12.0 / 480.0 - 0.5) * 0.03);
  EXPECT_DOUBLE_EQ(banded.RowOffset(479), -banded.RowOffset(0));
}

TEST(RealCameraTest, RollingShutterShearsAMovingBarByTheReadout) {
  // A tall bar moving right at 2 m/s at 2 m depth: 500 px/s. Over a 40 ms readout its left
  // edge moves 20 px from the top row to the bottom one, and sits where the plain render puts
  // it in the middle of the image.
  RealCameraOptions options;
  options.rolling_shutter_readout = 0.04;
  options.rolling_shutter_steps = 480;
  const ShutterRenderer rolling(TestCamera(), options, Unlit());
  const ShutterRenderer::SceneAt moving = MovingRectangle(2.0, 0.4, 3.0);
  RenderBuffers a, b;
  RenderPlainAndWith(options, moving, &a, &b);
  const std::vector<int> still = LeftEdges(a.instance, 3), sheared = LeftEdges(b.instance, 3);
  // Continuous edge: 270.25 + 500 px/s * row offset; the first pixel centre right of it.
  for (const int row : {0, 60, 120, 239, 240, 300, 479}) {
    const double edge = 270.25 + 500.0 * rolling.RowOffset(row);
    EXPECT_EQ(sheared[row], static_cast<int>(std::ceil(edge - 1e-9))) << row;
    EXPECT_EQ(still[row], 271) << row;
  }
  EXPECT_EQ(sheared[479] - sheared[0], 20);
  // Colour follows the mask: the edge pixel is white, the one left of it dark.
  EXPECT_EQ(b.bgr.at<cv::Vec3b>(0, sheared[0])[0], 230);
  EXPECT_EQ(b.bgr.at<cv::Vec3b>(0, sheared[0] - 1)[0], 20);
  // Depth follows the rows too (a Kinect v1)...
  EXPECT_EQ(b.depth.at<float>(0, sheared[0]), 2.0f);
  EXPECT_EQ(b.depth.at<float>(0, sheared[0] - 1), 4.0f);
  // ...unless the depth sensor has a global shutter (a RealSense): then depth is the
  // timestamp's on every row, and misregisters against the sheared colour and mask.
  options.depth_global_shutter = true;
  const ShutterRenderer global(TestCamera(), options, Unlit());
  RenderBuffers c;
  global.Render(Wall(), TwoTextures(), moving, &c);
  EXPECT_EQ(cv::norm(c.depth, a.depth, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(c.instance, b.instance, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(c.bgr, b.bgr, cv::NORM_INF), 0.0);
}

TEST(RealCameraTest, RollingShutterBandsEqualRendersAtTheirTimes) {
  SynthOptions options = SmallOptions("walking_xyz", 60);
  options.real_camera.rolling_shutter_readout = 0.03;
  options.real_camera.rolling_shutter_steps = 12;
  const SynthSequence sequence(options);
  const int f = 45;
  const RenderBuffers rolling = sequence.Render(f, /*apply_sensor=*/false);
  const Rasterizer rasterizer(sequence.Camera());
  for (const int band : {0, 5, 11}) {
    const int row_begin = band * 20, row_end = row_begin + 20;
    const double offset = sequence.Shutter().RowOffset(row_begin);
    EXPECT_DOUBLE_EQ(offset, ((row_begin + 10.0) / 240.0 - 0.5) * 0.03);
    TriangleList movers;
    sequence.AppendMoversAt(f, offset, &movers);
    RenderBuffers exact;
    rasterizer.Render({&sequence.Scene().triangles, &movers}, sequence.Textures(),
                      sequence.PoseAt(f, offset).Inverse(), &exact);
    const cv::Range rows(row_begin, row_end);
    EXPECT_EQ(cv::norm(rolling.bgr.rowRange(rows), exact.bgr.rowRange(rows), cv::NORM_INF), 0.0)
        << band;
    EXPECT_EQ(
        cv::norm(rolling.instance.rowRange(rows), exact.instance.rowRange(rows), cv::NORM_INF), 0.0)
        << band;
    EXPECT_EQ(cv::norm(rolling.depth.rowRange(rows), exact.depth.rowRange(rows), cv::NORM_INF), 0.0)
        << band;
  }
  // And the top band differs from the render at the timestamp: the camera moved meanwhile.
  const RenderBuffers plain = SynthSequence(SmallOptions("walking_xyz", 60)).Render(f, false);
  EXPECT_GT(cv::norm(rolling.depth.rowRange(0, 20), plain.depth.rowRange(0, 20), cv::NORM_INF),
            1e-4);
}

TEST(RealCameraTest, ActorsBetweenFramesMoveLinearly) {
  const SynthSequence sequence(SmallOptions("walking_xyz", 30));
  TriangleList at_frame, exact, halfway, next;
  sequence.Actors().AppendTriangles(10, &exact);
  sequence.Actors().AppendTrianglesAt(10.0, &at_frame);
  sequence.Actors().AppendTriangles(11, &next);
  sequence.Actors().AppendTrianglesAt(10.5, &halfway);
  ASSERT_EQ(at_frame.size(), exact.size());
  ASSERT_EQ(halfway.size(), exact.size());
  ASSERT_GT(exact.size(), 0u);
  double moved = 0.0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(at_frame[i].p[c], exact[i].p[c]);
      EXPECT_LT((halfway[i].p[c] - 0.5 * (exact[i].p[c] + next[i].p[c])).norm(), 1e-12);
      moved = std::max(moved, (next[i].p[c] - exact[i].p[c]).norm());
    }
  }
  EXPECT_GT(moved, 1e-3);  // they do walk
  // Past the last frame the last motion continues.
  TriangleList last, before_last, beyond;
  sequence.Actors().AppendTriangles(29, &last);
  sequence.Actors().AppendTriangles(28, &before_last);
  sequence.Actors().AppendTrianglesAt(29.5, &beyond);
  EXPECT_LT((beyond[0].p[0] - (last[0].p[0] + 0.5 * (last[0].p[0] - before_last[0].p[0]))).norm(),
            1e-12);
}

TEST(RealCameraTest, CameraSpeedRunsThePathFaster) {
  SynthOptions options = SmallOptions("static_rpy", 40);
  const SynthSequence normal(options);
  options.camera_speed = 2.0;
  const SynthSequence fast(options);
  for (const int f : {1, 7, 19}) {
    EXPECT_LT((fast.Pose(f).Translation() - normal.Pose(2 * f).Translation()).norm(), 1e-12);
    EXPECT_LT((fast.Pose(f).Rotation() - normal.Pose(2 * f).Rotation()).norm(), 1e-12);
    EXPECT_EQ(fast.Stamp(f), normal.Stamp(f));  // time itself runs as before
  }
  // Sub-frame poses follow the fast path too.
  EXPECT_LT((fast.PoseAt(5, 0.01).Translation() - normal.PoseAt(10, 0.02).Translation()).norm(),
            1e-12);
}

// --- Depth misregistration -----------------------------------------------------------------

TEST(RealCameraTest, DepthShiftMovesADepthEdgeByTheSetPixels) {
  RenderBuffers buffers;
  buffers.depth.create(40, 60, CV_32FC1);
  buffers.incidence.create(40, 60, CV_32FC1);
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 60; ++x) {
      // A slanted plane (depth grows 1 mm a pixel) with a box in front from x = 30 on.
      buffers.depth.at<float>(y, x) = x < 30 ? 2.0f + 0.001f * x : 1.0f;
      buffers.incidence.at<float>(y, x) = x < 30 ? 0.5f : 1.0f;
    }
  }
  RenderBuffers shifted = buffers;
  ShiftDepth(2.0, 1.0, &shifted);
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 60; ++x) {
      const float expected = (x < 2 || y < 1) ? 0.0f : buffers.depth.at<float>(y - 1, x - 2);
      ASSERT_EQ(shifted.depth.at<float>(y, x), expected) << x << "," << y;
    }
  }
  EXPECT_EQ(shifted.incidence.at<float>(10, 31), 0.5f);  // moved with depth
  EXPECT_EQ(shifted.incidence.at<float>(10, 32), 1.0f);

  // Half a pixel: the plane is interpolated, the edge stays sharp, moved by a whole pixel.
  RenderBuffers half = buffers;
  ShiftDepth(0.5, 0.0, &half);
  EXPECT_NEAR(half.depth.at<float>(5, 10), 2.0f + 0.001f * 9.5f, 1e-6);
  EXPECT_EQ(half.depth.at<float>(5, 30), buffers.depth.at<float>(5, 29));
  EXPECT_EQ(half.depth.at<float>(5, 31), 1.0f);
  for (int x = 0; x < 60; ++x) {
    const float z = half.depth.at<float>(5, x);
    EXPECT_TRUE(z == 0.0f || z == 1.0f || (z >= 2.0f && z < 2.03f)) << x << ": " << z;
  }
}

TEST(RealCameraTest, DepthShiftInASequenceMovesDepthOnlyAndMasksStayWithColour) {
  SynthOptions options = SmallOptions("walking_xyz", 20);
  const SynthSequence plain(options);
  options.real_camera.depth_shift_x = -2.0;
  options.real_camera.depth_shift_y = 1.0;
  const SynthSequence shifted(options);
  const RenderBuffers a = plain.Render(12), b = shifted.Render(12);
  EXPECT_EQ(cv::norm(a.bgr, b.bgr, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.instance, b.instance, cv::NORM_INF), 0.0);
  // depth'(x, y) = depth(x + 2, y - 1)
  const cv::Rect inside(0, 1, 318, 239);
  const cv::Rect source(2, 0, 318, 239);
  EXPECT_EQ(cv::norm(b.depth(inside), a.depth(source), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::countNonZero(b.depth.row(0)), 0);
  EXPECT_EQ(cv::countNonZero(b.depth.colRange(318, 320)), 0);
}

// --- Calibration error ---------------------------------------------------------------------

TEST(RealCameraTest, IntrinsicsErrorIsWhatSettingsStateAndLeavesImagesAlone) {
  TestFolder exact("intrinsics_exact"), wrong("intrinsics_wrong");
  SynthOptions options = SmallOptions("static_xyz", 3);
  GenerateSequence(options, exact.Path());
  options.real_camera.intrinsics_error = 0.03;
  options.real_camera.principal_point_error_x = 2.5;
  options.real_camera.principal_point_error_y = -1.0;
  GenerateSequence(options, wrong.Path());
  const CameraOptions truth = options.Camera();
  const Settings stated = LoadSettings(SettingsFile(wrong / "settings.yaml"));
  EXPECT_DOUBLE_EQ(stated.camera.fx, truth.fx * 1.03);
  EXPECT_DOUBLE_EQ(stated.camera.fy, truth.fy * 1.03);
  EXPECT_DOUBLE_EQ(stated.camera.bf, truth.bf * 1.03);
  EXPECT_DOUBLE_EQ(stated.camera.cx, truth.cx + 2.5);
  EXPECT_DOUBLE_EQ(stated.camera.cy, truth.cy - 1.0);
  const SettingsFile file(wrong / "settings.yaml");
  EXPECT_DOUBLE_EQ(file.GetDouble("Synth.TrueFx", 0.0), truth.fx);
  EXPECT_DOUBLE_EQ(file.GetDouble("Synth.TrueCy", 0.0), truth.cy);
  EXPECT_DOUBLE_EQ(file.GetDouble("Synth.RealIntrinsicsError", 0.0), 0.03);
  EXPECT_EQ(file.GetString("Synth.RealTimestampRow", ""), "middle");
  // The images are the same: only the calibration the file states is wrong.
  const std::string stamp = "1305031102.208637.png";  // the second frame
  EXPECT_EQ(ReadFileBytes(exact / ("rgb/" + stamp)), ReadFileBytes(wrong / ("rgb/" + stamp)));
  EXPECT_EQ(ReadFileBytes(exact / ("depth/" + stamp)), ReadFileBytes(wrong / ("depth/" + stamp)));
  EXPECT_FALSE(ReadFileBytes(exact / ("rgb/" + stamp)).empty());
  // Without effects the file carries no real-camera keys at all.
  EXPECT_FALSE(SettingsFile(exact / "settings.yaml").Has("Synth.TrueFx"));
  EXPECT_EQ(ReadFileBytes(exact / "settings.yaml").find("Real"), std::string::npos);
}

// --- Lens distortion -----------------------------------------------------------------------

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
    const cv::Point2d at = Centroid(mask);
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
    const cv::Point2d colour_at = Centroid(white) + cv::Point2d(around.x, around.y);
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

// --- All together --------------------------------------------------------------------------

TEST(RealCameraTest, HandheldPresetWritesEveryEffectAndStaysDeterministic) {
  TestFolder first("handheld_a"), second("handheld_b");
  SynthOptions options = SmallOptions("walking_rpy", 3);
  options.real_camera = HandheldCamera();
  GenerateSequence(options, first.Path());
  GenerateSequence(options, second.Path());
  for (const char* file : {"rgb/1305031102.208637.png", "depth/1305031102.208637.png",
                           "masks/1305031102.208637.png", "settings.yaml", "groundtruth.txt"}) {
    EXPECT_EQ(ReadFileBytes(first / file), ReadFileBytes(second / file)) << file;
  }
  const SettingsFile file(first / "settings.yaml");
  EXPECT_DOUBLE_EQ(file.GetDouble("Synth.RealBlurExposure", 0), 0.015);
  EXPECT_DOUBLE_EQ(file.GetDouble("Synth.RealRollingShutterReadout", 0), 0.025);
  EXPECT_DOUBLE_EQ(file.GetDouble("Synth.RealDepthShiftX", 0), 1.5);
  EXPECT_DOUBLE_EQ(file.GetDouble("Synth.RealDepthShiftY", 0), 1.0);
  EXPECT_EQ(file.GetInt("Synth.RealDepthGlobalShutter", 0), 1);
  EXPECT_DOUBLE_EQ(file.GetDouble("Camera.k1", 0), 0.262383);
  EXPECT_DOUBLE_EQ(file.GetDouble("Camera.fx", 0), file.GetDouble("Synth.TrueFx", 0) * 1.03);
}

TEST(RealCameraTest, BadOptionsNameTheirFlag) {
  const struct {
    RealCameraOptions options;
    const char* flag;
  } cases[] = {
      {[] {
         RealCameraOptions o;
         o.blur_exposure = -0.01;
         return o;
       }(),
       "--blur-exposure"},
      {[] {
         RealCameraOptions o;
         o.rolling_shutter_readout = 0.5;
         return o;
       }(),
       "--rolling-shutter"},
      {[] {
         RealCameraOptions o;
         o.blur_samples = 1;
         return o;
       }(),
       "--blur-samples"},
      {[] {
         RealCameraOptions o;
         o.intrinsics_error = std::nan("");
         return o;
       }(),
       "--intrinsics-error"},
  };
  for (const auto& c : cases) {
    try {
      c.options.Check();
      ADD_FAILURE() << c.flag << " accepted";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(c.flag), std::string::npos) << error.what();
    }
  }
  RealCameraOptions options;
  EXPECT_THROW(options.SetDistortion("0.1,x"), Error);
  EXPECT_THROW(options.SetDistortion("1,2,3,4,5,6"), Error);
  EXPECT_THROW(options.SetDistortion("fr9"), Error);
  options.SetDistortion("0.25");
  EXPECT_EQ(options.k1, 0.25);
  EXPECT_EQ(options.k2, 0.0);
}

}  // namespace
}  // namespace drvslam::synth
