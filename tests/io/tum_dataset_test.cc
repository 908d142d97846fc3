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

namespace drvslam {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 64;
constexpr int kHeight = 48;
constexpr char kRgbHeader[] = "# color images\n# file: 'sequence.bag'\n# timestamp filename\n";
constexpr char kDepthHeader[] = "# depth maps\n# file: 'sequence.bag'\n# timestamp filename\n";

// A colour image that differs per frame and per channel, so a swap or a mix-up shows.
cv::Mat MakeColour(int frame, int width = kWidth, int height = kHeight) {
  cv::Mat image(height, width, CV_8UC3);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      image.at<cv::Vec3b>(r, c) =
          cv::Vec3b(static_cast<uchar>(c * 3 + frame), static_cast<uchar>(r * 5),
                    static_cast<uchar>(200 - frame * 7));
    }
  }
  return image;
}

// Raw 16-bit depth with holes (0), the largest value and a spread in between.
cv::Mat MakeRawDepth(int frame, int width = kWidth, int height = kHeight) {
  cv::Mat raw(height, width, CV_16UC1);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      raw.at<std::uint16_t>(r, c) = static_cast<std::uint16_t>(1000 + 311 * r + 7 * c + frame);
    }
  }
  raw.at<std::uint16_t>(0, 0) = 0;
  raw.at<std::uint16_t>(1, 1) = 0;
  raw.at<std::uint16_t>(2, 2) = 5000;
  raw.at<std::uint16_t>(3, 3) = 65535;
  raw.at<std::uint16_t>(4, 4) = 1;
  return raw;
}

std::string Stamp(double t) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6f", t);
  return text;
}

double MaxAbsDifference(const cv::Mat& a, const cv::Mat& b) { return cv::norm(a, b, cv::NORM_INF); }

class TumDatasetTest : public testing::ScratchFolderTest {
 protected:
  TumDatasetTest() : ScratchFolderTest({"rgb", "depth"}) {}

  std::string Folder() const { return dir_.string(); }
  std::string PathOf(const std::string& relative) const { return (dir_ / relative).string(); }

  void WriteText(const std::string& relative, const std::string& body) {
    std::ofstream(PathOf(relative), std::ios::binary) << body;
  }
  void WriteImage(const std::string& relative, const cv::Mat& image) {
    ASSERT_TRUE(cv::imwrite(PathOf(relative), image)) << relative;
  }

  static double RgbStamp(int frame) { return 1305031102.175304 + 0.033 * frame; }
  static double DepthStamp(int frame) { return RgbStamp(frame) + 0.004; }
  static std::string RgbName(int frame) { return "rgb/" + Stamp(RgbStamp(frame)) + ".png"; }
  static std::string DepthName(int frame) { return "depth/" + Stamp(DepthStamp(frame)) + ".png"; }

  // A sequence of `frames` frames in the TUM layout: images, rgb.txt and depth.txt.
  void MakeSequence(int frames) {
    std::string rgb_list = kRgbHeader, depth_list = kDepthHeader;
    for (int k = 0; k < frames; ++k) {
      WriteImage(RgbName(k), MakeColour(k));
      WriteImage(DepthName(k), MakeRawDepth(k));
      rgb_list += Stamp(RgbStamp(k)) + " " + RgbName(k) + "\n";
      depth_list += Stamp(DepthStamp(k)) + " " + DepthName(k) + "\n";
    }
    WriteText("rgb.txt", rgb_list);
    WriteText("depth.txt", depth_list);
  }

  // `action` must throw an Error whose message contains every one of `needles`.
  static void ExpectError(const std::function<void()>& action,
                          const std::vector<std::string>& needles) {
    try {
      action();
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      const std::string message = e.what();
      for (const std::string& needle : needles) {
        EXPECT_NE(message.find(needle), std::string::npos) << message << "\n  lacks: " << needle;
      }
    }
  }
  void ExpectOpenError(const std::vector<std::string>& needles,
                       const TumDatasetOptions& options = {}) {
    ExpectError([&] { TumDataset dataset(Folder(), options); }, needles);
  }
  void ExpectReadError(std::size_t index, const std::vector<std::string>& needles,
                       const TumDatasetOptions& options = {}) {
    const TumDataset dataset(Folder(), options);  // opening must succeed: images load lazily
    ExpectError([&] { dataset.Read(index); }, needles);
  }
  // As ExpectReadError, and the error is a FrameError of kind `fault` for file `path`.
  void ExpectFrameError(std::size_t index, FrameFault fault, const std::string& path,
                        const std::vector<std::string>& needles,
                        const TumDatasetOptions& options = {}) {
    ExpectReadError(index, needles, options);
    const TumDataset dataset(Folder(), options);
    try {
      dataset.Read(index);
    } catch (const FrameError& e) {
      EXPECT_EQ(FrameFaultName(e.Fault()), std::string(FrameFaultName(fault))) << e.what();
      EXPECT_EQ(e.Path(), path);
      return;
    } catch (const Error& e) {
      ADD_FAILURE() << "not a FrameError: " << e.what();
    }
  }
};

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

// --- bad folders and lists ----------------------------------------------------------------------

TEST_F(TumDatasetTest, MissingFolderIsAnError) {
  const std::string missing = PathOf("no_such_sequence");
  ExpectError([&] { TumDataset dataset(missing); }, {missing, "does not exist"});
}

TEST_F(TumDatasetTest, AFileInsteadOfAFolderIsAnError) {
  WriteText("plain.txt", "x");
  ExpectError([&] { TumDataset dataset(PathOf("plain.txt")); },
              {PathOf("plain.txt"), "not a folder"});
}

TEST_F(TumDatasetTest, MissingRgbListIsAnError) {
  MakeSequence(2);
  fs::remove(PathOf("rgb.txt"));
  ExpectOpenError({PathOf("rgb.txt"), "does not exist"});
}

TEST_F(TumDatasetTest, MissingDepthListIsAnError) {
  MakeSequence(2);
  fs::remove(PathOf("depth.txt"));
  ExpectOpenError({PathOf("depth.txt"), "does not exist"});
}

TEST_F(TumDatasetTest, ListLineWithWrongFieldCountIsAnError) {
  MakeSequence(2);
  WriteText("rgb.txt", std::string(kRgbHeader) + Stamp(RgbStamp(0)) + " " + RgbName(0) + "\n" +
                           Stamp(RgbStamp(1)) + " " + RgbName(1) + " extra\n");
  ExpectOpenError({PathOf("rgb.txt") + ":5:", "expected 2 fields", "found 3"});
  WriteText("rgb.txt", Stamp(RgbStamp(0)) + "\n");
  ExpectOpenError({PathOf("rgb.txt") + ":1:", "found 1"});
}

TEST_F(TumDatasetTest, ListTimestampThatIsNotANumberIsAnError) {
  MakeSequence(2);
  WriteText("depth.txt", std::string(kDepthHeader) + "12.5x " + DepthName(0) + "\n");
  ExpectOpenError({PathOf("depth.txt") + ":4:", "'12.5x' is not a number"});
}

TEST_F(TumDatasetTest, ListTimestampThatIsNaNIsAnError) {
  MakeSequence(2);
  WriteText("rgb.txt", "\n1.0 rgb/a.png\nnan rgb/b.png\n");
  ExpectOpenError({PathOf("rgb.txt") + ":3:", "not finite"});
}

TEST_F(TumDatasetTest, RepeatedListTimestampIsDroppedAndDescribed) {
  MakeSequence(3);
  WriteText("rgb.txt", Stamp(RgbStamp(0)) + " " + RgbName(0) + "\n" + Stamp(RgbStamp(0)) +
                           " rgb/again.png\n" + Stamp(RgbStamp(1)) + " " + RgbName(1) + "\n");
  const TumDataset dataset(Folder());
  ASSERT_EQ(dataset.Size(), 2u);
  EXPECT_DOUBLE_EQ(dataset.Timestamp(1), RgbStamp(1));
  ASSERT_EQ(dataset.DroppedEntries().size(), 1u);
  const FrameError& dropped = dataset.DroppedEntries()[0];
  EXPECT_EQ(dropped.Fault(), FrameFault::kTimestampNotIncreasing);
  EXPECT_EQ(dropped.Path(), PathOf("rgb/again.png"));
  const std::string message = dropped.what();
  EXPECT_NE(message.find(PathOf("rgb.txt") + ":2:"), std::string::npos) << message;
  EXPECT_NE(message.find("does not increase"), std::string::npos) << message;
  EXPECT_NE(message.find("line 1"), std::string::npos) << message;
}

TEST_F(TumDatasetTest, DecreasingListTimestampIsDroppedAgainstTheLastKeptEntry) {
  MakeSequence(3);
  // 1.5 goes back behind 2.0; 1.8 is still behind the last kept 2.0, so it goes too.
  WriteText("depth.txt", "# depth\n" + Stamp(DepthStamp(0)) + " " + DepthName(0) + "\n\n" +
                             Stamp(DepthStamp(0) - 0.5) + " depth/b.png\n" +
                             Stamp(DepthStamp(0) - 0.2) + " depth/c.png\n" + Stamp(DepthStamp(2)) +
                             " " + DepthName(2) + "\n");
  const TumDataset dataset(Folder());
  ASSERT_EQ(dataset.DroppedEntries().size(), 2u);
  EXPECT_NE(std::string(dataset.DroppedEntries()[0].what()).find(PathOf("depth.txt") + ":4:"),
            std::string::npos);
  EXPECT_NE(std::string(dataset.DroppedEntries()[1].what()).find("line 2"), std::string::npos)
      << dataset.DroppedEntries()[1].what();
  // Colour frame 2 pairs with depth 2; frame 0 with depth 0; frame 1 has no depth close enough.
  ASSERT_EQ(dataset.Size(), 2u);
  EXPECT_EQ(dataset.Read(1).depth_path, PathOf(DepthName(2)));
}
TEST_F(TumDatasetTest, EmptyListIsAnError) {
  MakeSequence(2);
  WriteText("rgb.txt", kRgbHeader);
  ExpectOpenError({PathOf("rgb.txt"), "lists no images"});
  WriteText("rgb.txt", "");
  ExpectOpenError({PathOf("rgb.txt"), "lists no images"});
}

TEST_F(TumDatasetTest, ListsThatNeverAssociateAreAnError) {
  MakeSequence(2);
  WriteText("depth.txt", "5.0 depth/a.png\n6.0 depth/b.png\n");
  ExpectOpenError({PathOf("rgb.txt"), PathOf("depth.txt"), "no colour/depth pair"});
}

TEST_F(TumDatasetTest, AssociationLineWithWrongFieldCountIsAnError) {
  MakeSequence(1);
  WriteText("associations.txt", "1.0 rgb/a.png 1.0\n");
  ExpectOpenError({PathOf("associations.txt") + ":1:", "expected 4 fields", "found 3"});
}

TEST_F(TumDatasetTest, AssociationTimestampThatIsNotANumberIsAnError) {
  MakeSequence(1);
  WriteText("associations.txt", "1.0 rgb/a.png 1.0 depth/a.png\n2.0 rgb/b.png t depth/b.png\n");
  ExpectOpenError({PathOf("associations.txt") + ":2:", "'t' is not a number"});
}

TEST_F(TumDatasetTest, AssociationTimestampsThatDoNotIncreaseAreDropped) {
  MakeSequence(1);
  WriteText("associations.txt",
            "2.0 rgb/a.png 2.0 depth/a.png\n1.0 rgb/b.png 1.0 depth/b.png\n"
            "2.0 rgb/c.png 2.0 depth/c.png\n3.0 rgb/d.png 3.0 depth/d.png\n");
  const TumDataset dataset(Folder());
  ASSERT_EQ(dataset.Size(), 2u);
  EXPECT_DOUBLE_EQ(dataset.Timestamp(1), 3.0);
  ASSERT_EQ(dataset.DroppedEntries().size(), 2u);
  EXPECT_NE(
      std::string(dataset.DroppedEntries()[0].what()).find(PathOf("associations.txt") + ":2:"),
      std::string::npos);
  EXPECT_NE(
      std::string(dataset.DroppedEntries()[1].what()).find(PathOf("associations.txt") + ":3:"),
      std::string::npos);
}

TEST_F(TumDatasetTest, IncreasingListsDropNothing) {
  MakeSequence(3);
  EXPECT_TRUE(TumDataset(Folder()).DroppedEntries().empty());
}
TEST_F(TumDatasetTest, EmptyAssociationsFileIsAnError) {
  MakeSequence(1);
  WriteText("associations.txt", "# nothing here\n\n");
  ExpectOpenError({PathOf("associations.txt"), "lists no frames"});
}

TEST_F(TumDatasetTest, GroundTruthWithNaNIsAnError) {
  MakeSequence(1);
  WriteText("groundtruth.txt", "1.0 0 0 0 0 0 0 1\n2.0 0 nan 0 0 0 0 1\n");
  ExpectOpenError({PathOf("groundtruth.txt") + ":2:", "not finite"});
}

TEST_F(TumDatasetTest, GroundTruthWithABadRowIsAnError) {
  MakeSequence(1);
  WriteText("groundtruth.txt", "# gt\n1.0 0 0 0 0 0 1\n");
  ExpectOpenError({PathOf("groundtruth.txt") + ":2:", "expected 8 values"});
}

// --- bad images ---------------------------------------------------------------------------------

TEST_F(TumDatasetTest, MissingColourImageIsAnError) {
  MakeSequence(2);
  fs::remove(PathOf(RgbName(1)));
  ExpectFrameError(1, FrameFault::kMissingFile, PathOf(RgbName(1)),
                   {PathOf(RgbName(1)), "does not exist"});
}

TEST_F(TumDatasetTest, MissingDepthImageIsAnError) {
  MakeSequence(2);
  fs::remove(PathOf(DepthName(0)));
  ExpectFrameError(0, FrameFault::kMissingFile, PathOf(DepthName(0)),
                   {PathOf(DepthName(0)), "does not exist"});
}

TEST_F(TumDatasetTest, CorruptColourImageIsAnError) {
  MakeSequence(2);
  WriteText(RgbName(1), "\x89PNG\r\n\x1a\n this is not image data");
  ExpectFrameError(1, FrameFault::kCorruptImage, PathOf(RgbName(1)),
                   {PathOf(RgbName(1)), "cannot decode"});
}

TEST_F(TumDatasetTest, TruncatedDepthImageIsAnError) {
  MakeSequence(1);
  const std::string path = PathOf(DepthName(0));
  fs::resize_file(path, fs::file_size(path) / 2);
  ExpectFrameError(0, FrameFault::kCorruptImage, path, {path, "cannot decode"});
}

TEST_F(TumDatasetTest, EmptyImageFileIsAnError) {
  MakeSequence(1);
  WriteText(RgbName(0), "");
  ExpectFrameError(0, FrameFault::kEmptyFile, PathOf(RgbName(0)),
                   {PathOf(RgbName(0)), "empty file"});
}

TEST_F(TumDatasetTest, ColourImageSizeMustMatchTheFirstFrame) {
  MakeSequence(3);
  WriteImage(RgbName(2), MakeColour(2, 32, 24));
  WriteImage(DepthName(2), MakeRawDepth(2, 32, 24));
  // Reading frame 2 first gives the same answer: the first frame sets the size, not the first
  // frame read.
  ExpectReadError(2, {PathOf(RgbName(2)), "32x24", "64x48", PathOf(RgbName(0))});
  const TumDataset dataset(Folder());
  EXPECT_NO_THROW(dataset.Read(1));
  ExpectError([&] { dataset.Read(2); }, {PathOf(RgbName(2)), "32x24"});
}

TEST_F(TumDatasetTest, UnreadableFirstFrameFailsTheSizeCheckOfEveryFrame) {
  // Frame 0 sets the size: when it cannot be read no frame can be checked, and that is not frame
  // 1's fault (a plain Error naming frame 0's file, not a FrameError a run would skip).
  MakeSequence(2);
  WriteText(RgbName(0), "");
  const TumDataset dataset(Folder());
  try {
    dataset.Read(1);
    ADD_FAILURE() << "no error";
  } catch (const FrameError& e) {
    ADD_FAILURE() << "a FrameError: " << e.what();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(PathOf(RgbName(0))), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("expected_width"), std::string::npos) << e.what();
  }
}

TEST_F(TumDatasetTest, ColourImageSizeMustMatchTheExpectedSize) {
  MakeSequence(1);
  TumDatasetOptions options;
  options.expected_width = 640;
  options.expected_height = 480;
  ExpectFrameError(0, FrameFault::kWrongSize, PathOf(RgbName(0)),
                   {PathOf(RgbName(0)), "64x48", "640x480", "expected_width"}, options);
}

TEST_F(TumDatasetTest, DepthImageSizeMustMatchTheColourImage) {
  MakeSequence(2);
  WriteImage(DepthName(1), MakeRawDepth(1, kWidth, kHeight + 2));
  ExpectFrameError(1, FrameFault::kWrongSize, PathOf(DepthName(1)),
                   {PathOf(DepthName(1)), "64x50", "64x48"});
}

TEST_F(TumDatasetTest, SixteenBitColourIsAnError) {
  MakeSequence(1);
  WriteImage(RgbName(0), cv::Mat(kHeight, kWidth, CV_16UC3, cv::Scalar(1000, 2000, 3000)));
  ExpectFrameError(0, FrameFault::kWrongType, PathOf(RgbName(0)),
                   {PathOf(RgbName(0)), "16-bit unsigned 3-channel", "8-bit"});
}

TEST_F(TumDatasetTest, FloatColourIsAnError) {
  MakeSequence(1);
  const std::string name = "rgb/float.tiff";
  WriteImage(name, cv::Mat(kHeight, kWidth, CV_32FC3, cv::Scalar(0.1, 0.2, 0.3)));
  WriteText("rgb.txt", Stamp(RgbStamp(0)) + " " + name + "\n");
  ExpectReadError(0, {PathOf(name), "32-bit float 3-channel"});
}

TEST_F(TumDatasetTest, EightBitDepthIsAnError) {
  MakeSequence(1);
  WriteImage(DepthName(0), cv::Mat(kHeight, kWidth, CV_8UC1, cv::Scalar(100)));
  ExpectReadError(0, {PathOf(DepthName(0)), "8-bit unsigned 1-channel", "16-bit"});
}

TEST_F(TumDatasetTest, MultiChannelDepthIsAnError) {
  MakeSequence(1);
  WriteImage(DepthName(0), cv::Mat(kHeight, kWidth, CV_16UC3, cv::Scalar(1, 2, 3)));
  ExpectReadError(0, {PathOf(DepthName(0)), "16-bit unsigned 3-channel"});
}

TEST_F(TumDatasetTest, IndexOutOfRangeIsAnError) {
  MakeSequence(2);
  const TumDataset dataset(Folder());
  ExpectError([&] { dataset.Read(2); }, {Folder(), "index 2", "2 frames"});
  ExpectError([&] { dataset.Timestamp(7); }, {Folder(), "index 7"});
}

}  // namespace
}  // namespace drvslam
