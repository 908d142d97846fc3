#include "drvslam/io/frame_rejections.h"

#include <gtest/gtest.h>

#include <string>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

FrameError Fault(FrameFault fault, const std::string& file) {
  return FrameError(fault, file, file + ": broken");
}

TEST(FrameRejectionsTest, CountsPerFaultAndKeepsExamplesInOrder) {
  FrameRejections rejections(5);
  rejections.RejectListEntry(Fault(FrameFault::kTimestampNotIncreasing, "rgb/0.png"));
  rejections.Reject(3, Fault(FrameFault::kMissingFile, "depth/3.png"));
  rejections.Accept();
  rejections.Reject(7, Fault(FrameFault::kMissingFile, "depth/7.png"));
  rejections.Reject(8, Fault(FrameFault::kCorruptImage, "rgb/8.png"));
  EXPECT_EQ(rejections.Count(), 4u);
  EXPECT_EQ(rejections.Accepted(), 1u);
  const auto counts = rejections.CountsByFault();
  ASSERT_EQ(counts.size(), 3u);
  EXPECT_EQ(counts.at("missing_file"), 2u);
  EXPECT_EQ(counts.at("corrupt_image"), 1u);
  EXPECT_EQ(counts.at("timestamp_not_increasing"), 1u);
  const auto examples = rejections.Examples();
  ASSERT_EQ(examples.size(), 4u);
  EXPECT_EQ(examples[0].index, RejectedFrame::kListEntry);
  EXPECT_EQ(examples[1].index, 3u);
  EXPECT_EQ(examples[1].path, "depth/3.png");
  EXPECT_EQ(examples[1].message, "depth/3.png: broken");
  EXPECT_EQ(examples[3].fault, FrameFault::kCorruptImage);
}

TEST(FrameRejectionsTest, MoreThanTheLimitInARowIsAnErrorNamingTheLastFile) {
  FrameRejections rejections(3);
  for (std::size_t i = 0; i < 3; ++i) {
    rejections.Reject(i, Fault(FrameFault::kEmptyFile, "rgb/" + std::to_string(i) + ".png"));
  }
  rejections.Accept();  // a good frame starts the count again
  for (std::size_t i = 4; i < 7; ++i) {
    EXPECT_NO_THROW(rejections.Reject(i, Fault(FrameFault::kWrongSize, "rgb/x.png")));
  }
  try {
    rejections.Reject(7, Fault(FrameFault::kWrongSize, "rgb/7.png"));
    ADD_FAILURE() << "no error after 4 in a row";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("4 frames in a row"), std::string::npos) << message;
    EXPECT_NE(message.find("rgb/7.png"), std::string::npos) << message;
  }
  EXPECT_EQ(rejections.Count(), 7u);
}

TEST(FrameRejectionsTest, ListEntriesNeverStopTheRun) {
  FrameRejections rejections(1);
  for (int i = 0; i < 10; ++i) {
    EXPECT_NO_THROW(rejections.RejectListEntry(Fault(FrameFault::kTimestampNotIncreasing, "a")));
  }
  EXPECT_NO_THROW(rejections.Reject(0, Fault(FrameFault::kMissingFile, "b")));
}

TEST(FrameRejectionsTest, ExamplesStayBoundedOverLongRuns) {
  FrameRejections rejections(2);
  for (std::size_t i = 0; i < 1000; ++i) {
    rejections.Reject(i, Fault(FrameFault::kCorruptImage, "rgb/" + std::to_string(i) + ".png"));
    rejections.Accept();
  }
  EXPECT_EQ(rejections.Count(), 1000u);
  ASSERT_EQ(rejections.Examples().size(), FrameRejections::kKeptExamples);
  EXPECT_EQ(rejections.Examples().back().index, FrameRejections::kKeptExamples - 1);
}

TEST(FrameRejectionsTest, FaultNamesAreDistinct) {
  const FrameFault all[] = {FrameFault::kMissingFile,  FrameFault::kEmptyFile,
                            FrameFault::kCorruptImage, FrameFault::kWrongSize,
                            FrameFault::kWrongType,    FrameFault::kTimestampNotIncreasing};
  for (const FrameFault a : all) {
    for (const FrameFault b : all) {
      if (a != b) {
        EXPECT_STRNE(FrameFaultName(a), FrameFaultName(b));
      }
    }
  }
  EXPECT_STREQ(FrameFaultName(FrameFault::kCorruptImage), "corrupt_image");
}

TEST(FrameRejectionsTest, ZeroLimitIsAnError) { EXPECT_THROW(FrameRejections(0), Error); }

}  // namespace
}  // namespace drvslam
