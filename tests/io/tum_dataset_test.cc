// TumDataset reading a TUM RGB-D folder, and its options (its errors: tum_dataset_errors_test.cc).
#include "drvslam/io/tum_dataset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/io/frame_fault.h"
#include "test_support/scratch_folder.h"
#include "tum_dataset_fixture.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

using testing::TumDatasetTest;

TEST_F(TumDatasetTest, ReadsFramesAndConvertsDepthToMetresExactly) {
  MakeSequence(3);
  const TumDataset dataset(Folder());
  ASSERT_EQ(dataset.Size(), 3u);
  EXPECT_EQ(dataset.Folder(), Folder());
  EXPECT_FALSE(dataset.HasGroundTruth());
  EXPECT_TRUE(dataset.GroundTruth().empty());
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE("frame " + std::to_string(k));
    EXPECT_DOUBLE_EQ(dataset.Timestamp(k), RgbStamp(k));
    const RgbdFrame frame = dataset.Read(k);
    EXPECT_EQ(frame.index, static_cast<std::size_t>(k));
    EXPECT_DOUBLE_EQ(frame.timestamp, RgbStamp(k));
    EXPECT_DOUBLE_EQ(frame.depth_timestamp, DepthStamp(k));
    EXPECT_EQ(frame.rgb_path, PathOf(RgbName(k)));
    EXPECT_EQ(frame.depth_path, PathOf(DepthName(k)));
    ASSERT_EQ(frame.bgr.type(), CV_8UC3);
    ASSERT_EQ(frame.depth.type(), CV_32FC1);
    ASSERT_EQ(frame.bgr.size(), cv::Size(kWidth, kHeight));
    ASSERT_EQ(frame.depth.size(), cv::Size(kWidth, kHeight));
    EXPECT_EQ(MaxAbsDifference(frame.bgr, MakeColour(k)), 0.0);

    const cv::Mat raw = MakeRawDepth(k);
    int mismatches = 0;
    for (int r = 0; r < kHeight; ++r) {
      for (int c = 0; c < kWidth; ++c) {
        const float expected = static_cast<float>(raw.at<std::uint16_t>(r, c) / 5000.0);
        if (frame.depth.at<float>(r, c) != expected) ++mismatches;
      }
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_EQ(frame.depth.at<float>(0, 0), 0.0f);
    EXPECT_EQ(frame.depth.at<float>(1, 1), 0.0f);
    EXPECT_EQ(frame.depth.at<float>(2, 2), 1.0f);
    EXPECT_EQ(frame.depth.at<float>(3, 3), static_cast<float>(65535 / 5000.0));
    EXPECT_EQ(frame.depth.at<float>(4, 4), static_cast<float>(1 / 5000.0));
  }
}

TEST_F(TumDatasetTest, DepthMapFactorScalesRawValues) {
  MakeSequence(1);
  TumDatasetOptions options;
  options.depth_map_factor = 1000.0;
  const RgbdFrame frame = TumDataset(Folder(), options).Read(0);
  EXPECT_EQ(frame.depth.at<float>(2, 2), 5.0f);
  EXPECT_EQ(frame.depth.at<float>(0, 0), 0.0f);
  EXPECT_EQ(frame.depth.at<float>(5, 9), static_cast<float>((1000 + 311 * 5 + 7 * 9) / 1000.0));
}

TEST_F(TumDatasetTest, PairsColourAndDepthLikeAssociatePy) {
  // Colour at 1.00 1.10 1.20 1.30 1.40; depth at 1.005 1.13 1.195 1.21 1.50 1.395.
  // 1.10-1.13 is outside 0.02; 1.20 takes 1.195 (closer than 1.21); 1.30 has no depth;
  // depth 1.50 has no colour.
  const std::vector<double> rgb = {1.00, 1.10, 1.20, 1.30, 1.40};
  const std::vector<double> depth = {1.005, 1.13, 1.195, 1.21, 1.395, 1.50};
  std::string rgb_list = kRgbHeader, depth_list = kDepthHeader;
  for (double t : rgb) rgb_list += Stamp(t) + " rgb/" + Stamp(t) + ".png\n";
  for (double t : depth) depth_list += Stamp(t) + " depth/" + Stamp(t) + ".png\n";
  WriteText("rgb.txt", rgb_list);
  WriteText("depth.txt", depth_list);

  const TumDataset dataset(Folder());
  ASSERT_EQ(dataset.Size(), 3u);
  EXPECT_DOUBLE_EQ(dataset.Timestamp(0), 1.00);
  EXPECT_DOUBLE_EQ(dataset.Timestamp(1), 1.20);
  EXPECT_DOUBLE_EQ(dataset.Timestamp(2), 1.40);
  // Read() fails on the missing images, but names the paired files.
  ExpectError([&] { dataset.Read(1); }, {PathOf("rgb/1.200000.png")});

  // A wider window pairs 1.10 with 1.13 as well.
  TumDatasetOptions wide;
  wide.max_difference = 0.05;
  const TumDataset wider(Folder(), wide);
  ASSERT_EQ(wider.Size(), 4u);
  EXPECT_DOUBLE_EQ(wider.Timestamp(1), 1.10);
}

TEST_F(TumDatasetTest, PairedDepthStampsAndPathsFollowTheAssociation) {
  WriteImage("rgb/a.png", MakeColour(0));
  WriteImage("rgb/b.png", MakeColour(1));
  WriteImage("depth/x.png", MakeRawDepth(0));
  WriteImage("depth/y.png", MakeRawDepth(1));
  WriteImage("depth/z.png", MakeRawDepth(2));
  WriteText("rgb.txt", "10.000 rgb/a.png\n10.100 rgb/b.png\n");
  WriteText("depth.txt", "9.990 depth/x.png\n10.095 depth/y.png\n10.105 depth/z.png\n");
  const TumDataset dataset(Folder());
  ASSERT_EQ(dataset.Size(), 2u);
  const RgbdFrame second = dataset.Read(1);
  EXPECT_DOUBLE_EQ(second.depth_timestamp, 10.095);
  EXPECT_EQ(second.depth_path, PathOf("depth/y.png"));
  EXPECT_EQ(MaxAbsDifference(second.bgr, MakeColour(1)), 0.0);
  EXPECT_EQ(second.depth.at<float>(2, 2), 1.0f);
  EXPECT_EQ(second.depth.at<float>(5, 5),
            static_cast<float>(MakeRawDepth(1).at<std::uint16_t>(5, 5) / 5000.0));
}

TEST_F(TumDatasetTest, LoadsGroundTruth) {
  MakeSequence(2);
  WriteText("groundtruth.txt",
            "# ground truth trajectory\n# timestamp tx ty tz qx qy qz qw\n"
            "1305031102.1700 1.3563 0.6305 1.6380 0.6132 0.5962 -0.3311 -0.3986\n"
            "1305031102.1800 1.3543 0.6306 1.6360 0.6129 0.5966 -0.3316 -0.3980\n"
            "1305031102.1900 1.3500 0.6310 1.6300 0.6129 0.5966 -0.3316 -0.3980\n");
  const TumDataset dataset(Folder());
  ASSERT_TRUE(dataset.HasGroundTruth());
  ASSERT_EQ(dataset.GroundTruth().size(), 3u);
  EXPECT_DOUBLE_EQ(dataset.GroundTruth()[0].timestamp, 1305031102.17);
  EXPECT_DOUBLE_EQ(dataset.GroundTruth()[1].T_wc.Translation().x(), 1.3543);
  EXPECT_DOUBLE_EQ(dataset.GroundTruth()[2].T_wc.Translation().z(), 1.63);
}

TEST_F(TumDatasetTest, AssociationsFileTakesPrecedence) {
  MakeSequence(3);
  // Pair colour 0 with depth 2 and colour 2 with depth 0 on purpose; skip frame 1.
  WriteText("associations.txt", "# t_rgb rgb t_depth depth\n" + Stamp(RgbStamp(0)) + " " +
                                    RgbName(0) + " " + Stamp(DepthStamp(2)) + " " + DepthName(2) +
                                    "\n\n" + Stamp(RgbStamp(2)) + " " + RgbName(2) + " " +
                                    Stamp(DepthStamp(0)) + " " + DepthName(0) + "\n");
  const TumDataset dataset(Folder());
  ASSERT_EQ(dataset.Size(), 2u);
  const RgbdFrame first = dataset.Read(0);
  EXPECT_DOUBLE_EQ(first.timestamp, RgbStamp(0));
  EXPECT_DOUBLE_EQ(first.depth_timestamp, DepthStamp(2));
  EXPECT_EQ(first.depth_path, PathOf(DepthName(2)));
  EXPECT_EQ(MaxAbsDifference(first.bgr, MakeColour(0)), 0.0);
  EXPECT_EQ(first.depth.at<float>(10, 10),
            static_cast<float>(MakeRawDepth(2).at<std::uint16_t>(10, 10) / 5000.0));
  EXPECT_DOUBLE_EQ(dataset.Read(1).depth_timestamp, DepthStamp(0));

  // The lists are not needed when associations.txt is there.
  fs::remove(PathOf("rgb.txt"));
  fs::remove(PathOf("depth.txt"));
  EXPECT_EQ(TumDataset(Folder()).Size(), 2u);
}

TEST_F(TumDatasetTest, AbsolutePathsInListsAreKept) {
  WriteImage("rgb/a.png", MakeColour(0));
  WriteImage("depth/a.png", MakeRawDepth(0));
  WriteText("associations.txt",
            "1.0 " + PathOf("rgb/a.png") + " 1.001 " + PathOf("depth/a.png") + "\n");
  const RgbdFrame frame = TumDataset(Folder()).Read(0);
  EXPECT_EQ(frame.rgb_path, PathOf("rgb/a.png"));
  EXPECT_EQ(frame.depth_path, PathOf("depth/a.png"));
}

TEST_F(TumDatasetTest, ReadingIsStatelessAndRepeatable) {
  MakeSequence(3);
  const TumDataset dataset(Folder());
  RgbdFrame once = dataset.Read(1);
  const RgbdFrame later = dataset.Read(2);
  const RgbdFrame again = dataset.Read(1);
  EXPECT_EQ(MaxAbsDifference(once.bgr, again.bgr), 0.0);
  EXPECT_EQ(MaxAbsDifference(once.depth, again.depth), 0.0);
  EXPECT_EQ(once.timestamp, again.timestamp);
  // Each call returns its own buffers: changing one frame leaves the next read untouched.
  EXPECT_NE(once.bgr.data, again.bgr.data);
  once.bgr.setTo(cv::Scalar::all(0));
  EXPECT_EQ(MaxAbsDifference(dataset.Read(1).bgr, MakeColour(1)), 0.0);
  EXPECT_GT(MaxAbsDifference(later.bgr, again.bgr), 0.0);
  // A copy reads the same frames.
  const TumDataset copy = dataset;
  EXPECT_EQ(MaxAbsDifference(copy.Read(2).depth, later.depth), 0.0);
}

TEST_F(TumDatasetTest, GrayAndBgraColourBecomeBgr) {
  MakeSequence(2);
  cv::Mat gray(kHeight, kWidth, CV_8UC1);
  for (int r = 0; r < kHeight; ++r) {
    for (int c = 0; c < kWidth; ++c) gray.at<uchar>(r, c) = static_cast<uchar>(r + 2 * c);
  }
  WriteImage(RgbName(0), gray);
  cv::Mat bgra(kHeight, kWidth, CV_8UC4, cv::Scalar(10, 20, 30, 128));
  WriteImage(RgbName(1), bgra);

  const TumDataset dataset(Folder());
  const RgbdFrame from_gray = dataset.Read(0);
  ASSERT_EQ(from_gray.bgr.type(), CV_8UC3);
  EXPECT_EQ(from_gray.bgr.at<cv::Vec3b>(7, 9), cv::Vec3b(25, 25, 25));
  const RgbdFrame from_bgra = dataset.Read(1);
  ASSERT_EQ(from_bgra.bgr.type(), CV_8UC3);
  EXPECT_EQ(from_bgra.bgr.at<cv::Vec3b>(3, 4), cv::Vec3b(10, 20, 30));
}

TEST_F(TumDatasetTest, RgbOrderOptionSwapsChannels) {
  MakeSequence(1);
  WriteImage(RgbName(0), cv::Mat(kHeight, kWidth, CV_8UC3, cv::Scalar(10, 20, 30)));
  TumDatasetOptions options;
  options.rgb_is_rgb_order = true;
  EXPECT_EQ(TumDataset(Folder(), options).Read(0).bgr.at<cv::Vec3b>(5, 5), cv::Vec3b(30, 20, 10));
  EXPECT_EQ(TumDataset(Folder()).Read(0).bgr.at<cv::Vec3b>(5, 5), cv::Vec3b(10, 20, 30));
}

TEST_F(TumDatasetTest, FloatDepthIsTakenAsMetres) {
  MakeSequence(1);
  cv::Mat metres(kHeight, kWidth, CV_32FC1, cv::Scalar(1.25));
  metres.at<float>(0, 0) = std::numeric_limits<float>::quiet_NaN();
  metres.at<float>(0, 1) = std::numeric_limits<float>::infinity();
  metres.at<float>(0, 2) = -1.0f;
  metres.at<float>(0, 3) = 0.0f;
  metres.at<float>(0, 4) = 3.0625f;
  WriteImage("depth/float.tiff", metres);
  WriteText("depth.txt", Stamp(DepthStamp(0)) + " depth/float.tiff\n");
  const RgbdFrame frame = TumDataset(Folder()).Read(0);
  ASSERT_EQ(frame.depth.type(), CV_32FC1);
  EXPECT_EQ(frame.depth.at<float>(0, 0), 0.0f);
  EXPECT_EQ(frame.depth.at<float>(0, 1), 0.0f);
  EXPECT_EQ(frame.depth.at<float>(0, 2), 0.0f);
  EXPECT_EQ(frame.depth.at<float>(0, 3), 0.0f);
  EXPECT_EQ(frame.depth.at<float>(0, 4), 3.0625f);
  EXPECT_EQ(frame.depth.at<float>(20, 30), 1.25f);
}

TEST_F(TumDatasetTest, ExpectedSizeIsAccepted) {
  MakeSequence(2);
  TumDatasetOptions options;
  options.expected_width = kWidth;
  options.expected_height = kHeight;
  EXPECT_EQ(TumDataset(Folder(), options).Read(1).bgr.size(), cv::Size(kWidth, kHeight));
}

TEST_F(TumDatasetTest, ReadsABonnStyleFolder) {
  // The Bonn RGB-D Dynamic dataset: same layout, five-decimal stamps, its own headers.
  const std::vector<std::string> rgb = {"1548266469.72370", "1548266469.75713", "1548266469.79050"};
  const std::vector<std::string> depth = {"1548266469.72360", "1548266469.75700",
                                          "1548266469.79044"};
  std::string rgb_list = "# color images\n# file: 'rgbd_bonn_dataset'\n# timestamp filename\n";
  std::string depth_list = "# depth maps\n# file: 'rgbd_bonn_dataset'\n# timestamp filename\n";
  for (std::size_t k = 0; k < rgb.size(); ++k) {
    WriteImage("rgb/" + rgb[k] + ".png", MakeColour(static_cast<int>(k)));
    WriteImage("depth/" + depth[k] + ".png", MakeRawDepth(static_cast<int>(k)));
    rgb_list += rgb[k] + " rgb/" + rgb[k] + ".png\n";
    depth_list += depth[k] + " depth/" + depth[k] + ".png\n";
  }
  WriteText("rgb.txt", rgb_list);
  WriteText("depth.txt", depth_list);
  WriteText("groundtruth.txt",
            "# timestamp tx ty tz qx qy qz qw\n"
            "1548266469.7170 0.0 0.0 0.0 0.0 0.0 0.0 1.0\n"
            "1548266469.7270 0.001 0.0 0.0 0.0 0.0 0.0 1.0\n");
  const TumDataset dataset(Folder());
  ASSERT_EQ(dataset.Size(), 3u);
  EXPECT_DOUBLE_EQ(dataset.Timestamp(2), 1548266469.79050);
  EXPECT_EQ(dataset.GroundTruth().size(), 2u);
  const RgbdFrame frame = dataset.Read(2);
  EXPECT_DOUBLE_EQ(frame.depth_timestamp, 1548266469.79044);
  EXPECT_EQ(MaxAbsDifference(frame.bgr, MakeColour(2)), 0.0);
}

// --- options ------------------------------------------------------------------------------------

TEST(TumDatasetOptionsTest, DefaultsPassTheCheck) { EXPECT_NO_THROW(TumDatasetOptions().Check()); }

TEST(TumDatasetOptionsTest, EachBadOptionIsNamed) {
  const auto expect_named = [](const TumDatasetOptions& options, const std::string& name) {
    try {
      options.Check();
      ADD_FAILURE() << "no error for " << name;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  TumDatasetOptions options;
  options.depth_map_factor = 0.0;
  expect_named(options, "depth_map_factor");
  options.depth_map_factor = std::nan("");
  expect_named(options, "depth_map_factor");
  options = {};
  options.expected_width = -640;
  options.expected_height = 480;
  expect_named(options, "expected_width");
  options = {};
  options.expected_width = 640;
  options.expected_height = -1;
  expect_named(options, "expected_height");
  options = {};
  options.expected_width = 640;
  expect_named(options, "expected_height");
  options = {};
  options.max_difference = -0.02;
  expect_named(options, "max_difference");
  options.max_difference = std::numeric_limits<double>::infinity();
  expect_named(options, "max_difference");
}

TEST_F(TumDatasetTest, OpeningChecksTheOptions) {
  MakeSequence(1);
  TumDatasetOptions options;
  options.max_difference = 0.0;
  ExpectOpenError({"max_difference"}, options);
}

}  // namespace
}  // namespace drvslam
