#include "drvslam/core/settings.h"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>

#include "drvslam/core/error.h"
#include "test_support/error_message.h"
#include "test_support/scratch_folder.h"

namespace drvslam {
namespace {

class SettingsTest : public testing::ScratchFolderTest {
 protected:
  std::string Write(const std::string& body) {
    const std::string path = (dir_ / "settings.yaml").string();
    std::ofstream(path) << "%YAML:1.0\n" << body;
    return path;
  }

  // Loading must fail with a message that contains every one of `needles`.
  void ExpectError(const std::string& body, std::initializer_list<std::string> needles) {
    SCOPED_TRACE("settings:\n" + body);
    const std::string path = Write(body);
    const std::string message = testing::ErrorMessageOf([&] { LoadSettings(path); });
    EXPECT_NE(message.find(path), std::string::npos) << message;
    for (const std::string& needle : needles) {
      EXPECT_NE(message.find(needle), std::string::npos) << message << " lacks " << needle;
    }
  }
};

// The camera's fx, fy, cx, cy, k1, k2, p1, p2, k3 as a TUM calibration page lists them.
void ExpectCalibration(const CameraOptions& camera, const std::array<double, 9>& published) {
  const std::array<double, 9> loaded = {camera.fx, camera.fy, camera.cx, camera.cy, camera.k1,
                                        camera.k2, camera.p1, camera.p2, camera.k3};
  for (std::size_t i = 0; i < loaded.size(); ++i) EXPECT_DOUBLE_EQ(loaded[i], published[i]) << i;
}

TEST_F(SettingsTest, ShippedTumConfigsCarryThePublishedCalibrations) {
  const std::string configs = std::string(DRVSLAM_SOURCE_DIR) + "/configs/";
  const Settings fr1 = LoadSettings(configs + "TUM1.yaml");
  ExpectCalibration(fr1.camera, {517.306408, 516.469215, 318.643040, 255.313989, 0.262383,
                                 -0.953104, -0.005358, 0.002628, 1.163314});
  const Settings fr2 = LoadSettings(configs + "TUM2.yaml");
  ExpectCalibration(fr2.camera, {520.908620, 521.007327, 325.141442, 249.701764, 0.231222,
                                 -0.784899, -0.003257, -0.000105, 0.917205});
  const Settings fr3 = LoadSettings(configs + "TUM3.yaml");
  EXPECT_DOUBLE_EQ(fr3.camera.fx, 535.4);
  EXPECT_DOUBLE_EQ(fr3.camera.fy, 539.2);
  EXPECT_DOUBLE_EQ(fr3.camera.cx, 320.1);
  EXPECT_DOUBLE_EQ(fr3.camera.cy, 247.6);
  EXPECT_FALSE(fr3.camera.HasDistortion());
  for (const Settings* s : {&fr1, &fr2, &fr3}) {
    EXPECT_DOUBLE_EQ(s->depth.depth_map_factor, 5000.0);
    EXPECT_EQ(s->orb.n_features, 1000);
    EXPECT_EQ(s->orb.n_levels, 8);
  }
}

TEST_F(SettingsTest, AbsentKeysKeepDefaults) {
  const Settings s = LoadSettings(Write("Camera.fx: 600.0\n"));
  EXPECT_DOUBLE_EQ(s.camera.fx, 600.0);
  EXPECT_DOUBLE_EQ(s.camera.fy, CameraOptions().fy);
  EXPECT_EQ(s.orb.n_features, OrbExtractorOptions().n_features);
  EXPECT_DOUBLE_EQ(s.depth.depth_map_factor, 5000.0);
}

TEST_F(SettingsTest, IntegersAreAcceptedWhereRealsAreExpected) {
  const Settings s = LoadSettings(Write("Camera.fx: 500\nDepthMapFactor: 1000\n"));
  EXPECT_DOUBLE_EQ(s.camera.fx, 500.0);
  EXPECT_DOUBLE_EQ(s.depth.depth_map_factor, 1000.0);
}

TEST_F(SettingsTest, UnknownKeysAreReportedAsUnread) {
  const std::string path = Write("Camera.fx: 500.0\nViewer.PointSize: 2\nSomething.else: 1\n");
  SettingsFile file(path);
  LoadSettings(file);
  const std::vector<std::string> unread = file.UnreadKeys();
  ASSERT_EQ(unread.size(), 2u);
  EXPECT_EQ(unread[0], "Viewer.PointSize");
  EXPECT_EQ(unread[1], "Something.else");
}

TEST_F(SettingsTest, WriteThenLoadRoundTrips) {
  Settings original;
  original.camera.fx = 517.306408;
  original.camera.k1 = 0.262383;
  original.camera.rgb = false;
  original.depth.depth_map_factor = 1000.0;
  original.orb.n_features = 1500;
  original.orb.scale_factor = 1.25;
  const std::string path = (dir_ / "written.yaml").string();
  WriteSettings(original, path, "Scenario.name: \"walking_xyz\"\n");
  const Settings loaded = LoadSettings(path);
  EXPECT_DOUBLE_EQ(loaded.camera.fx, original.camera.fx);
  EXPECT_DOUBLE_EQ(loaded.camera.k1, original.camera.k1);
  EXPECT_FALSE(loaded.camera.rgb);
  EXPECT_DOUBLE_EQ(loaded.depth.depth_map_factor, 1000.0);
  EXPECT_EQ(loaded.orb.n_features, 1500);
  EXPECT_DOUBLE_EQ(loaded.orb.scale_factor, 1.25);
  SettingsFile file(path);
  EXPECT_EQ(file.GetString("Scenario.name", ""), "walking_xyz");
}

TEST_F(SettingsTest, BadValuesNameTheKeyAndValue) {
  ExpectError("Camera.fx: -3.0\n", {"Camera.fx", "-3"});
  ExpectError("Camera.fy: 0\n", {"Camera.fy", "0"});
  ExpectError("Camera.width: 0\n", {"Camera.width"});
  ExpectError("DepthMapFactor: -1.0\n", {"DepthMapFactor", "-1"});
  ExpectError("ThDepth: 0.0\n", {"ThDepth"});
  ExpectError("ORBextractor.nFeatures: 0\n", {"ORBextractor.nFeatures", "0"});
  ExpectError("ORBextractor.scaleFactor: 1.0\n", {"ORBextractor.scaleFactor", "1"});
  ExpectError("ORBextractor.nLevels: 0\n", {"ORBextractor.nLevels"});
  ExpectError("ORBextractor.iniThFAST: 5\nORBextractor.minThFAST: 9\n",
              {"ORBextractor.minThFAST", "9"});
  ExpectError("Camera.bf: .nan\n", {"Camera.bf"});
}

TEST_F(SettingsTest, WrongTypesNameTheKey) {
  ExpectError("Camera.fx: \"wide\"\n", {"Camera.fx", "number"});
  ExpectError("ORBextractor.nFeatures: 1000.5\n", {"ORBextractor.nFeatures", "integer"});
  ExpectError("Camera.RGB: 3\n", {"Camera.RGB", "boolean"});
}

TEST_F(SettingsTest, MissingOrCorruptFilesNameThePath) {
  const std::string missing = (dir_ / "nope.yaml").string();
  try {
    LoadSettings(missing);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
  const std::string corrupt = (dir_ / "corrupt.yaml").string();
  std::ofstream(corrupt) << "%YAML:1.0\nCamera.fx: [1, 2\n  : :\n";
  try {
    LoadSettings(corrupt);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(corrupt), std::string::npos) << e.what();
  }
}

TEST(CameraTest, ProjectAndBackprojectAreInverse) {
  const PinholeCamera camera{CameraOptions{}};
  const Eigen::Vector3d p(0.4, -0.3, 2.5);
  const Eigen::Vector2d pixel = camera.Project(p);
  EXPECT_NEAR(pixel.x(), 535.4 * 0.4 / 2.5 + 320.1, 1e-12);
  EXPECT_NEAR(pixel.y(), 539.2 * -0.3 / 2.5 + 247.6, 1e-12);
  EXPECT_LT((camera.Backproject(pixel, 2.5) - p).norm(), 1e-12);
}

TEST(CameraTest, PixelVelocityIsTheProjectionsDerivative) {
  const PinholeCamera camera{CameraOptions{}};
  const Eigen::Vector3d p(0.4, -0.3, 2.5);
  const Eigen::Vector3d velocity(0.2, 0.1, -0.5);
  const double h = 1e-6;
  const Eigen::Vector2d central =
      (camera.Project(p + h * velocity) - camera.Project(p - h * velocity)) / (2 * h);
  const Eigen::Vector2d analytic = camera.PixelVelocity(p, velocity);
  EXPECT_NEAR(analytic.x(), central.x(), 1e-5);
  EXPECT_NEAR(analytic.y(), central.y(), 1e-5);
  // Straight along the ray the pixel stays put.
  EXPECT_LT(camera.PixelVelocity(p, 3.0 * p).norm(), 1e-12);
}

TEST(CameraTest, UndistortInvertsOpenCvDistortion) {
  CameraOptions options;
  options.k1 = 0.262383;
  options.k2 = -0.953104;
  options.p1 = -0.005358;
  options.p2 = 0.002628;
  options.k3 = 1.163314;
  const PinholeCamera camera(options);
  // Distort known normalized points with the Brown model, then undistort them back.
  std::vector<cv::Point2f> distorted, ideal;
  for (double x = -0.4; x <= 0.4; x += 0.2) {
    for (double y = -0.3; y <= 0.3; y += 0.15) {
      const double r2 = x * x + y * y;
      const double radial = 1 + options.k1 * r2 + options.k2 * r2 * r2 + options.k3 * r2 * r2 * r2;
      const double xd = x * radial + 2 * options.p1 * x * y + options.p2 * (r2 + 2 * x * x);
      const double yd = y * radial + options.p1 * (r2 + 2 * y * y) + 2 * options.p2 * x * y;
      distorted.emplace_back(options.fx * xd + options.cx, options.fy * yd + options.cy);
      ideal.emplace_back(options.fx * x + options.cx, options.fy * y + options.cy);
    }
  }
  const std::vector<cv::Point2f> undistorted = camera.Undistort(distorted);
  ASSERT_EQ(undistorted.size(), ideal.size());
  for (std::size_t i = 0; i < ideal.size(); ++i) {
    EXPECT_NEAR(undistorted[i].x, ideal[i].x, 0.05);
    EXPECT_NEAR(undistorted[i].y, ideal[i].y, 0.05);
  }
}

}  // namespace
}  // namespace drvslam
