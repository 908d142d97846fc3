// Real-camera effects of the generator, each measured alone: motion blur, rolling shutter,
// depth misregistration and calibration error (lens distortion: lens_distortion_test.cc).
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "drvslam/core/settings.h"
#include "drvslam/core/settings_file.h"
#include "drvslam/tools/synth/depth_shift.h"
#include "drvslam/tools/synth/shutter_renderer.h"
#include "drvslam/tools/synth/synth_generator.h"
#include "drvslam/tools/synth/synth_sequence.h"
#include "raster_test_scene.h"
#include "real_camera_test_util.h"
#include "test_folder.h"

namespace drvslam::synth {
namespace {

using testing::AddFacingRect;
using testing::ReadFileBytes;
using testing::SmallOptions;
using testing::TestCamera;
using testing::TestFolder;
using testing::TwoTextures;
using testing::Unlit;

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
