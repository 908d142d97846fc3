#include "drvslam/tools/synth/rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <opencv2/core/utility.hpp>

#include "drvslam/core/camera.h"
#include "drvslam/core/error.h"
#include "drvslam/tools/synth/random.h"
#include "drvslam/tools/synth/room_layout.h"
#include "raster_test_scene.h"

namespace drvslam::synth {
namespace {

using testing::AddFacingRect;
using testing::SolidTextures;
using testing::TestCamera;
using testing::Unlit;

std::vector<Texture> PlainTextures() { return SolidTextures({cv::Scalar(40, 80, 120)}); }

int CountId(const cv::Mat& ids, int id) { return cv::countNonZero(ids == id); }

TEST(RasterizerTest, FrontoParallelRectangleHasExactAreaAndDepth) {
  const Rasterizer rasterizer(TestCamera(), Unlit());
  TriangleList triangles;
  AddFacingRect({0, 0, 2.0}, 0.8, 0.6, 5, 0, &triangles);
  RenderBuffers out;
  rasterizer.Render({&triangles}, PlainTextures(), SE3(), &out);
  // u spans [220.25, 420.25] and v [165.25, 315.25]: 200 x 150 pixel centres.
  EXPECT_EQ(CountId(out.instance, 5), 200 * 150);
  EXPECT_EQ(out.instance.at<uint16_t>(165, 220), 0);
  EXPECT_EQ(out.instance.at<uint16_t>(166, 221), 5);
  EXPECT_EQ(out.instance.at<uint16_t>(315, 420), 5);
  EXPECT_EQ(out.instance.at<uint16_t>(316, 420), 0);
  // Depth is z, not the ray length, even in the corner.
  EXPECT_FLOAT_EQ(out.depth.at<float>(166, 221), 2.0f);
  EXPECT_FLOAT_EQ(out.depth.at<float>(240, 320), 2.0f);
  EXPECT_EQ(out.depth.at<float>(10, 10), 0.0f);
  const cv::Vec3b colour = out.bgr.at<cv::Vec3b>(240, 320);
  EXPECT_EQ(colour, cv::Vec3b(40, 80, 120));
  EXPECT_NEAR(out.incidence.at<float>(240, 320), 1.0f, 1e-6);
}

TEST(RasterizerTest, KnownPointProjectsToExpectedPixel) {
  const CameraOptions camera = TestCamera();
  const Rasterizer rasterizer(camera, Unlit());
  const PinholeCamera pinhole(camera);
  // A camera somewhere in a room, a 3 cm square marker facing it around a known point.
  const SE3 T_wc = LookAt({0.4, -1.9, 1.5}, {0.1, 0.6, 0.8});
  const SE3 T_cw = T_wc.Inverse();
  const Eigen::Vector3d marker(0.31, 0.17, 0.93);
  const Eigen::Vector3d marker_c = T_cw * marker;
  TriangleList triangles;
  AddFacingRect(marker_c, 0.03, 0.03, 9, 0, &triangles);
  TransformTriangles(T_wc, &triangles);  // into the world
  RenderBuffers out;
  rasterizer.Render({&triangles}, PlainTextures(), T_cw, &out);
  const Eigen::Vector2d expected = pinhole.Project(marker_c);
  double sum_x = 0, sum_y = 0;
  int count = 0;
  for (int y = 0; y < out.instance.rows; ++y) {
    for (int x = 0; x < out.instance.cols; ++x) {
      if (out.instance.at<uint16_t>(y, x) != 9) continue;
      sum_x += x;
      sum_y += y;
      ++count;
    }
  }
  ASSERT_GT(count, 20);
  EXPECT_NEAR(sum_x / count, expected.x(), 0.5);
  EXPECT_NEAR(sum_y / count, expected.y(), 0.5);
  const int px = static_cast<int>(std::lround(expected.x()));
  const int py = static_cast<int>(std::lround(expected.y()));
  EXPECT_EQ(out.instance.at<uint16_t>(py, px), 9);
  EXPECT_NEAR(out.depth.at<float>(py, px), marker_c.z(), 1e-5);
}

TEST(RasterizerTest, SlantedPlaneDepthIsTheRayPlaneIntersection) {
  const CameraOptions camera = TestCamera();
  const Rasterizer rasterizer(camera, Unlit());
  // A floor 0.9 m below the camera (camera y points down), reaching behind it: near clipping
  // must cut it without changing the depth of what is left.
  TriangleList triangles;
  SurfaceTag tag;
  AddQuad({-5, 0.9, -3}, {5, 0.9, -3}, {5, 0.9, 20}, {-5, 0.9, 20}, UvRect(), tag, &triangles);
  RenderBuffers out;
  rasterizer.Render({&triangles}, PlainTextures(), SE3(), &out);
  int checked = 0;
  for (int y = 250; y < 480; y += 23) {
    for (int x = 0; x < 640; x += 37) {
      const double ray_y = (y - camera.cy) / camera.fy;
      const double z = 0.9 / ray_y;
      const double x_floor = (x - camera.cx) / camera.fx * z;
      if (z > 20.0 * 0.99 || std::abs(x_floor) > 4.99) continue;  // beyond the quad
      ASSERT_GT(out.depth.at<float>(y, x), 0.0f) << x << "," << y;
      EXPECT_NEAR(out.depth.at<float>(y, x), z, 1e-6 * z) << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
  // Above the horizon nothing.
  EXPECT_EQ(out.depth.at<float>(200, 320), 0.0f);
}

TEST(RasterizerTest, NearerSurfaceWinsAndBackFacesAreCulled) {
  const Rasterizer rasterizer(TestCamera(), Unlit());
  TriangleList triangles;
  AddFacingRect({0, 0, 3.0}, 2.0, 2.0, 1, 0, &triangles);
  AddFacingRect({0.2, 0, 1.5}, 0.2, 0.2, 2, 0, &triangles);
  // Facing away (corners mirrored): culled unless double-sided.
  TriangleList away;
  SurfaceTag tag;
  tag.instance_id = 3;
  AddQuad({0.1, 0.1, 1.0}, {-0.1, 0.1, 1.0}, {-0.1, -0.1, 1.0}, {0.1, -0.1, 1.0}, UvRect(), tag,
          &away);
  RenderBuffers out;
  rasterizer.Render({&triangles, &away}, PlainTextures(), SE3(), &out);
  const int cx = 320, cy = 240;
  EXPECT_EQ(out.instance.at<uint16_t>(cy, cx + 67), 2);
  EXPECT_FLOAT_EQ(out.depth.at<float>(cy, cx + 67), 1.5f);
  EXPECT_EQ(out.instance.at<uint16_t>(cy, cx), 1);
  EXPECT_EQ(CountId(out.instance, 3), 0);
  for (Triangle& t : away) t.double_sided = true;
  rasterizer.Render({&triangles, &away}, PlainTextures(), SE3(), &out);
  EXPECT_EQ(out.instance.at<uint16_t>(cy, cx), 3);
  EXPECT_FLOAT_EQ(out.depth.at<float>(cy, cx), 1.0f);
}

TEST(RasterizerTest, TransparentTexelsAreNotDrawn) {
  const Rasterizer rasterizer(TestCamera(), Unlit());
  // Left half transparent, right half opaque white.
  cv::Mat cutout(64, 64, CV_8UC4, cv::Scalar(255, 255, 255, 255));
  cutout(cv::Rect(0, 0, 32, 64)).setTo(cv::Scalar(0, 0, 0, 0));
  std::vector<Texture> textures = PlainTextures();
  textures.emplace_back(cutout);
  ASSERT_TRUE(textures[1].HasTransparency());
  TriangleList triangles;
  AddFacingRect({0, 0, 2.0}, 0.8, 0.8, 4, 1, &triangles);
  RenderBuffers out;
  rasterizer.Render({&triangles}, textures, SE3(), &out);
  // The opaque half spans u in [320.25, 420.25]: 100 x 200 pixel centres.
  EXPECT_NEAR(CountId(out.instance, 4), 100 * 200, 200);
  EXPECT_EQ(out.instance.at<uint16_t>(240, 300), 0);
  EXPECT_EQ(out.depth.at<float>(240, 300), 0.0f);
  EXPECT_EQ(out.instance.at<uint16_t>(240, 340), 4);
}

TEST(RasterizerTest, TextureIsSampledPerspectiveCorrectly) {
  const Rasterizer rasterizer(TestCamera(), Unlit());
  // Black left half, white right half, on a plane slanted in depth: the boundary must land
  // where the plane's midline projects, not halfway across the image of the quad.
  cv::Mat halves(64, 64, CV_8UC3, cv::Scalar(0, 0, 0));
  halves(cv::Rect(32, 0, 32, 64)).setTo(cv::Scalar(255, 255, 255));
  std::vector<Texture> textures;
  textures.emplace_back(halves);
  TriangleList triangles;
  SurfaceTag tag;
  // From x = -1 at z = 1.5 to x = 1 at z = 4.5; the midline x = 0 is at z = 3.
  AddQuad({-1, 0.5, 1.5}, {1, 0.5, 4.5}, {1, -0.5, 4.5}, {-1, -0.5, 1.5}, UvRect(), tag,
          &triangles);
  RenderBuffers out;
  rasterizer.Render({&triangles}, textures, SE3(), &out);
  // The midline projects to u = cx. Columns left of it are black, right of it white.
  EXPECT_LT(out.bgr.at<cv::Vec3b>(240, 316)[0], 40);
  EXPECT_GT(out.bgr.at<cv::Vec3b>(240, 324)[0], 215);
}

TEST(RasterizerTest, OutputDoesNotDependOnThreadCount) {
  const Rasterizer rasterizer(TestCamera());
  Random rng(7);
  TriangleList triangles;
  for (int k = 0; k < 300; ++k) {
    Triangle t;
    const Eigen::Vector3d centre(rng.Uniform(-2, 2), rng.Uniform(-1.5, 1.5), rng.Uniform(-0.5, 6));
    for (int c = 0; c < 3; ++c) {
      t.p[c] = centre + Eigen::Vector3d(rng.Uniform(-0.8, 0.8), rng.Uniform(-0.8, 0.8),
                                        rng.Uniform(-0.8, 0.8));
      t.uv[c] =
          Eigen::Vector2f(static_cast<float>(rng.Uniform()), static_cast<float>(rng.Uniform()));
    }
    t.instance_id = k;
    t.double_sided = k % 2 == 0;
    triangles.push_back(t);
  }
  cv::Mat noise(128, 128, CV_8UC3);
  cv::randu(noise, 0, 255);
  std::vector<Texture> textures;
  textures.emplace_back(noise);
  const int threads = cv::getNumThreads();
  RenderBuffers one, many;
  cv::setNumThreads(1);
  rasterizer.Render({&triangles}, textures, SE3(), &one);
  cv::setNumThreads(4);
  rasterizer.Render({&triangles}, textures, SE3(), &many);
  cv::setNumThreads(threads);
  EXPECT_EQ(cv::norm(one.bgr, many.bgr, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(one.depth, many.depth, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(one.instance, many.instance, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::countNonZero(one.depth), 10000);
}

TEST(RasterizerTest, RejectsUnknownTexture) {
  const Rasterizer rasterizer(TestCamera());
  TriangleList triangles;
  AddFacingRect({0, 0, 2.0}, 0.8, 0.6, 5, 3, &triangles);
  RenderBuffers out;
  EXPECT_THROW(rasterizer.Render({&triangles}, PlainTextures(), SE3(), &out), Error);
}

}  // namespace
}  // namespace drvslam::synth
