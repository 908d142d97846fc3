// The network backs off when tracking skips frames (semantic/segmentation_pacer.h): which frames
// go to the network around a skip, and that a steady or jittery camera holds nothing.
#include "drvslam/semantic/segmentation_pacer.h"

#include <gtest/gtest.h>

#include <vector>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

constexpr double kPeriod = 0.04;  // a 25 Hz camera: frame times are exact in binary-ish steps

// Feeds frames at the given indices (in camera periods) and returns which were submitted.
std::vector<bool> Feed(SegmentationPacer& pacer, const std::vector<int>& indices,
                       std::optional<double> pass_ms) {
  std::vector<bool> submitted;
  for (const int index : indices) submitted.push_back(pacer.ShouldSubmit(index * kPeriod, pass_ms));
  return submitted;
}

TEST(SegmentationPacer, ASteadyCameraHoldsNothing) {
  SegmentationPacer pacer(1.0);
  std::vector<int> indices;
  for (int i = 0; i < 100; ++i) indices.push_back(i);
  for (const bool submitted : Feed(pacer, indices, 100.0)) EXPECT_TRUE(submitted);
  EXPECT_EQ(pacer.Stats().backoffs, 0u);
  EXPECT_EQ(pacer.Stats().frames_held, 0u);
}

TEST(SegmentationPacer, AfterASkipTheNetworkRestsOneOfItsPasses) {
  SegmentationPacer pacer(1.0);
  // Frame 10 is skipped; frame 11 shows it. With 100 ms passes, frames 11, 12 and 13 (up to
  // 80 ms after 11) are held and frame 14 (120 ms after) goes to the network again.
  const std::vector<bool> submitted =
      Feed(pacer, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14, 15}, 100.0);
  const std::vector<bool> expected = {true, true, true,  true,  true,  true, true, true,
                                      true, true, false, false, false, true, true};
  EXPECT_EQ(submitted, expected);
  EXPECT_EQ(pacer.Stats().backoffs, 1u);
  EXPECT_EQ(pacer.Stats().frames_held, 3u);
}

TEST(SegmentationPacer, TheRestScalesWithBackoffPasses) {
  SegmentationPacer twice(2.0);
  // 180 ms after frame 11: frames 11-15 held, 16 (200 ms after) submitted.
  EXPECT_EQ(Feed(twice, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14, 15, 16}, 90.0),
            (std::vector<bool>{true, true, true, true, true, true, true, true, true, true, false,
                               false, false, false, false, true}));
}

TEST(SegmentationPacer, NoNewRestDuringARestOrThePassAfterIt) {
  SegmentationPacer pacer(1.0);
  // Frame 13 is skipped too, inside the pass after the rest that frame 11 started (the rest
  // ends at 0.54 s, the free pass at 0.64 s): frame 14 (0.56 s) goes to the network.
  EXPECT_EQ(Feed(pacer, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 14, 15, 16, 17}, 100.0),
            (std::vector<bool>{true, true, true, true, true, true, true, true, true, true, false,
                               false, true, true, true, true}));
  EXPECT_EQ(pacer.Stats().backoffs, 1u);
  EXPECT_EQ(pacer.Stats().frames_held, 2u);
}

TEST(SegmentationPacer, TrackingThatKeepsSkippingStillLeavesTheNetworkFrames) {
  SegmentationPacer pacer(1.0);
  // Two of every four frames skipped for 12 s, with 100 ms passes: rests and free passes
  // alternate, and about half of the frames that arrive go to the network.
  int submitted = 0;
  int arrived = 0;
  for (int i = 0; i < 300; ++i) {
    if (i % 4 >= 2) continue;
    ++arrived;
    if (pacer.ShouldSubmit(i * kPeriod, 100.0)) ++submitted;
  }
  EXPECT_EQ(arrived, 150);
  EXPECT_EQ(submitted, 78);
  EXPECT_EQ(pacer.Stats().backoffs, 36u);
}

TEST(SegmentationPacer, NothingIsHeldBeforeThePassTimeOrThePeriodIsKnown) {
  SegmentationPacer no_pass(1.0);
  for (const bool submitted : Feed(no_pass, {0, 1, 2, 3, 4, 5, 7, 8, 10}, std::nullopt)) {
    EXPECT_TRUE(submitted);
  }
  SegmentationPacer early(1.0);
  // Three gaps are too few to know the camera's period: the long gap at frame 5 is not judged.
  for (const bool submitted : Feed(early, {0, 1, 2, 5, 6}, 100.0)) EXPECT_TRUE(submitted);
  EXPECT_EQ(early.Stats().backoffs, 0u);
}

TEST(SegmentationPacer, JitterWithoutSkipsHoldsNothing) {
  SegmentationPacer pacer(1.0);
  // Each frame up to 12 % of a period early or late (a fixed pseudo-random sequence): gaps
  // between 0.76 and 1.24 periods.
  unsigned state = 12345u;
  for (int i = 0; i < 300; ++i) {
    state = state * 1103515245u + 12345u;
    const double jitter = (static_cast<double>((state >> 8) % 1001) / 1000.0 - 0.5) * 0.24;
    EXPECT_TRUE(pacer.ShouldSubmit((i + jitter) * kPeriod, 100.0)) << "frame " << i;
  }
  EXPECT_EQ(pacer.Stats().frames_held, 0u);
}

TEST(SegmentationPacer, AThirdOfTheFramesSkippedStillShowsAsSkips) {
  SegmentationPacer pacer(1.0);
  // Every third frame skipped: half of the gaps are two periods, the lower quartile is one.
  int held = 0;
  for (int i = 0; i < 90; ++i) {
    if (i % 3 == 2) continue;
    if (!pacer.ShouldSubmit(i * kPeriod, 30.0)) ++held;
  }
  // 29 skips are followed by a frame; the first two come before four gaps are known. Each one
  // judged holds the frame that shows it (the 30 ms rest ends before the next frame).
  EXPECT_EQ(pacer.Stats().backoffs, 27u);
  EXPECT_EQ(held, 27);
}

TEST(SegmentationPacer, ANonPositiveBackoffIsRefused) {
  EXPECT_THROW(SegmentationPacer(0.0), Error);
  EXPECT_THROW(SegmentationPacer(-1.0), Error);
}

}  // namespace
}  // namespace drvslam
