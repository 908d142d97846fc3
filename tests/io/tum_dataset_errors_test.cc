// TumDataset on bad folders, lists and images: each fails with an Error (a FrameError for an
// image) that names the file and the fault.
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
#include "drvslam/io/tum_dataset.h"
#include "test_support/scratch_folder.h"
#include "tum_dataset_fixture.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

using testing::TumDatasetTest;

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
