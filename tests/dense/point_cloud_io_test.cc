#include "drvslam/dense/point_cloud_io.h"

#include <gtest/gtest.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/io/PointCloudIO.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "drvslam/core/error.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

std::string TempPath(const std::string& name) {
  return (testing::ProcessTempFolder() / name).string();
}

DenseCloud SampleCloud() {
  DenseCloud cloud;
  for (int i = 0; i < 500; ++i) {
    DensePoint p;
    p.position = {0.01f * i - 1.3f, std::sin(0.1f * i), 2.0f + 1e-3f * i};
    p.r = static_cast<uint8_t>(i % 256);
    p.g = static_cast<uint8_t>((3 * i) % 256);
    p.b = static_cast<uint8_t>(255 - i % 256);
    p.label = static_cast<int16_t>(i % 7 == 0 ? -1 : i % 80);
    cloud.push_back(p);
  }
  return cloud;
}

void ExpectOpen3dReadsBack(const std::string& path, const DenseCloud& cloud) {
  open3d::geometry::PointCloud read;
  ASSERT_TRUE(open3d::io::ReadPointCloud(path, read)) << path;
  ASSERT_EQ(read.points_.size(), cloud.size());
  ASSERT_EQ(read.colors_.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    // Floats widen to doubles exactly; colours come back as k / 255.
    ASSERT_EQ(read.points_[i].x(), static_cast<double>(cloud[i].position.x())) << i;
    ASSERT_EQ(read.points_[i].y(), static_cast<double>(cloud[i].position.y())) << i;
    ASSERT_EQ(read.points_[i].z(), static_cast<double>(cloud[i].position.z())) << i;
    ASSERT_EQ(std::lround(read.colors_[i].x() * 255.0), cloud[i].r) << i;
    ASSERT_EQ(std::lround(read.colors_[i].y() * 255.0), cloud[i].g) << i;
    ASSERT_EQ(std::lround(read.colors_[i].z() * 255.0), cloud[i].b) << i;
  }
}

TEST(PointCloudIo, Open3dReadsThePlyBackIdentical) {
  const std::string path = TempPath("drvslam_dense_test.ply");
  const DenseCloud cloud = SampleCloud();
  WritePlyCloud(path, cloud);
  ExpectOpen3dReadsBack(path, cloud);
}

TEST(PointCloudIo, Open3dReadsThePcdBackIdentical) {
  const std::string path = TempPath("drvslam_dense_test.pcd");
  const DenseCloud cloud = SampleCloud();
  WritePcdCloud(path, cloud);
  ExpectOpen3dReadsBack(path, cloud);
}

TEST(PointCloudIo, OurReaderKeepsLabels) {
  const std::string path = TempPath("drvslam_dense_labels.ply");
  const DenseCloud cloud = SampleCloud();
  WritePlyCloud(path, cloud);
  const DenseCloud read = ReadPlyCloud(path);
  ASSERT_EQ(read.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    ASSERT_EQ(read[i].position, cloud[i].position);
    ASSERT_EQ(read[i].label, cloud[i].label);
    ASSERT_EQ(read[i].r, cloud[i].r);
    ASSERT_EQ(read[i].b, cloud[i].b);
  }
}

TEST(PointCloudIo, EmptyCloudsRoundTrip) {
  const std::string path = TempPath("drvslam_dense_empty.ply");
  WritePlyCloud(path, {});
  EXPECT_TRUE(ReadPlyCloud(path).empty());
  open3d::geometry::PointCloud read;
  open3d::io::ReadPointCloud(path, read);
  EXPECT_TRUE(read.points_.empty());
}

TEST(PointCloudIo, BadFilesAreErrorsNamingTheFile) {
  const std::string truncated = TempPath("drvslam_dense_truncated.ply");
  WritePlyCloud(truncated, SampleCloud());
  std::filesystem::resize_file(truncated, std::filesystem::file_size(truncated) - 5);
  try {
    ReadPlyCloud(truncated);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(truncated), std::string::npos);
  }
  const std::string ascii = TempPath("drvslam_dense_ascii.ply");
  std::ofstream(ascii) << "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n1 2 3\n";
  EXPECT_THROW(ReadPlyCloud(ascii), Error);
  const std::string not_ply = TempPath("drvslam_dense_not.ply");
  std::ofstream(not_ply) << "hello\n";
  EXPECT_THROW(ReadPlyCloud(not_ply), Error);
  EXPECT_THROW(ReadPlyCloud(TempPath("drvslam_dense_missing.ply")), Error);
  EXPECT_THROW(WritePlyCloud("/nonexistent_dir/x.ply", {}), Error);
}

}  // namespace
}  // namespace drvslam
