#include "drvslam/semantic/mask_propagator.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "drvslam/semantic/mask_source.h"
#include "drvslam/semantic/segmentation_stats_json.h"
#include "fake_segmenter.h"

namespace drvslam {
namespace {

// Smoothed noise: texture at a scale of a few pixels, like a cluttered room.
cv::Mat Texture(cv::Size size, int seed) {
  cv::Mat noise(size, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.5);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  cv::Mat bgr;
  cv::cvtColor(noise, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

cv::Mat Shifted(const cv::Mat& image, double dx, double dy) {
  cv::Mat out;
  cv::warpAffine(image, out, cv::Matx23d(1, 0, dx, 0, 1, dy), image.size(), cv::INTER_LINEAR,
                 cv::BORDER_REFLECT);
  return out;
}

cv::Mat Ellipse(cv::Size size, cv::Point centre, cv::Size axes) {
  cv::Mat mask = cv::Mat::zeros(size, CV_8UC1);
  cv::ellipse(mask, centre, axes, 0, 0, 360, cv::Scalar(255), cv::FILLED);
  return mask;
}

Segmentation OneInstance(const cv::Mat& mask) {
  Segmentation seg;
  seg.image_size = mask.size();
  Instance instance;
  instance.class_id = 0;
  instance.class_name = "person";
  instance.mask = mask;
  instance.box = cv::boundingRect(mask);
  seg.instances.push_back(instance);
  return seg;
}

class MaskPropagatorTest : public ::testing::TestWithParam<MaskPropagation> {
 protected:
  MaskPropagator Propagator() const {
    MaskPropagatorOptions options;
    options.method = GetParam();
    return MaskPropagator(options);
  }

  struct Overlap {
    double before = 0.0;  // IoU of the mask as it was with the truth
    double after = 0.0;   // IoU of the carried mask with the truth
  };
  // Both overlaps, also recorded as the test's properties iou_before and iou_after.
  static Overlap RecordOverlap(const cv::Mat& mask, const cv::Mat& carried, const cv::Mat& truth) {
    const Overlap overlap{MaskIoU(mask, truth), MaskIoU(carried, truth)};
    RecordProperty("iou_before", std::to_string(overlap.before));
    RecordProperty("iou_after", std::to_string(overlap.after));
    return overlap;
  }
};

TEST_P(MaskPropagatorTest, CameraShiftIsFollowed) {
  const cv::Size size(640, 480);
  const cv::Mat from = Texture(size, 1);
  const cv::Mat to = Shifted(from, 18, -12);
  const cv::Mat mask = Ellipse(size, {300, 240}, {80, 120});
  const cv::Mat truth = Ellipse(size, {318, 228}, {80, 120});
  const Segmentation moved = Propagator().Propagate(OneInstance(mask), from, to, 2.0, 7);
  ASSERT_EQ(moved.instances.size(), 1u);
  EXPECT_EQ(moved.frame_index, 7u);
  EXPECT_DOUBLE_EQ(moved.timestamp, 2.0);
  const auto [before, after] = RecordOverlap(mask, moved.instances[0].mask, truth);
  EXPECT_LT(before, 0.80);
  EXPECT_GT(after, 0.95);
  EXPECT_GT(after - before, 0.15);
  const cv::Rect box = moved.instances[0].box;
  EXPECT_NEAR(box.x, 238, 3);
  EXPECT_NEAR(box.y, 108, 3);
}

TEST_P(MaskPropagatorTest, MovingObjectOnAStaticBackgroundIsFollowed) {
  const cv::Size size(640, 480);
  const cv::Mat background = Texture(size, 2);
  const cv::Mat object = Texture(size, 3);
  const cv::Mat mask = Ellipse(size, {320, 250}, {60, 110});
  const cv::Mat truth = Ellipse(size, {334, 259}, {60, 110});
  cv::Mat from = background.clone();
  object.copyTo(from, mask);
  cv::Mat to = background.clone();
  Shifted(object, 14, 9).copyTo(to, truth);
  const Segmentation moved = Propagator().Propagate(OneInstance(mask), from, to, 0.0, 1);
  ASSERT_EQ(moved.instances.size(), 1u);
  const auto [before, after] = RecordOverlap(mask, moved.instances[0].mask, truth);
  EXPECT_LT(before, 0.80);
  EXPECT_GT(after, 0.90);
  EXPECT_GT(after - before, 0.12);
}

TEST_P(MaskPropagatorTest, TurningObjectIsFollowedBySimilarity) {
  // The object turns by 6 degrees about its centre and moves by (10, 6) pixels.
  const cv::Size size(640, 480);
  const cv::Mat background = Texture(size, 7);
  const cv::Mat object = Texture(size, 8);
  const cv::Mat mask = Ellipse(size, {300, 240}, {50, 120});
  cv::Mat motion = cv::getRotationMatrix2D(cv::Point2f(300, 240), 6.0, 1.0);
  motion.at<double>(0, 2) += 10;
  motion.at<double>(1, 2) += 6;
  cv::Mat moved_object;
  cv::Mat truth;
  cv::warpAffine(object, moved_object, motion, size, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  cv::warpAffine(mask, truth, motion, size, cv::INTER_LINEAR);
  truth = truth > 127;
  cv::Mat from = background.clone();
  object.copyTo(from, mask);
  cv::Mat to = background.clone();
  moved_object.copyTo(to, truth);
  const Segmentation moved = Propagator().Propagate(OneInstance(mask), from, to, 0.0, 1);
  ASSERT_EQ(moved.instances.size(), 1u);
  const auto [before, after] = RecordOverlap(mask, moved.instances[0].mask, truth);
  EXPECT_LT(before, 0.80);
  EXPECT_GT(after, 0.95);
}

INSTANTIATE_TEST_SUITE_P(Methods, MaskPropagatorTest,
                         ::testing::Values(MaskPropagation::kDenseFlow,
                                           MaskPropagation::kSparseFlow),
                         [](const auto& info) { return ToString(info.param); });

TEST(MaskPropagatorBasicsTest, NoneKeepsMasksAndBadInputsThrow) {
  const cv::Mat image = Texture({64, 48}, 4);
  const cv::Mat mask = Ellipse({64, 48}, {30, 20}, {10, 8});
  MaskPropagatorOptions options;
  options.method = MaskPropagation::kNone;
  const Segmentation same =
      MaskPropagator(options).Propagate(OneInstance(mask), image, Shifted(image, 5, 0), 1.0, 1);
  ASSERT_EQ(same.instances.size(), 1u);
  EXPECT_DOUBLE_EQ(MaskIoU(same.instances[0].mask, mask), 1.0);
  const MaskPropagator dense;
  EXPECT_THROW(dense.Propagate(OneInstance(mask), image, cv::Mat(), 0, 0), Error);
  EXPECT_THROW(dense.Propagate(OneInstance(mask), image, Texture({65, 48}, 4), 0, 0), Error);
  EXPECT_THROW(
      dense.Propagate(OneInstance(Ellipse({80, 60}, {30, 20}, {10, 8})), image, image, 0, 0),
      Error);
  EXPECT_DOUBLE_EQ(MaskIoU(cv::Mat::zeros(4, 4, CV_8UC1), cv::Mat::zeros(4, 4, CV_8UC1)), 0.0);
}

TEST(MaskSourceTest, RealtimeUsesTheNewestMasksCarriedForwardAndRecordsTheLag) {
  const cv::Mat texture = Texture({320, 240}, 5);
  const auto frame = [&](int i) { return Shifted(texture, 6.0 * i, 0); };
  const auto stamp = [](int i) { return 100.0 + i / 30.0; };
  auto fake = std::make_shared<testing::FakeSegmenter>();
  AsyncSegmenter segmenter(fake);
  MaskSource source(segmenter, MaskPropagator(), /*realtime=*/true);

  segmenter.Submit(0, stamp(0), frame(0));
  segmenter.Wait(0);
  EXPECT_EQ(source.MasksFor(0, stamp(0), frame(0)).instances.at(0).box, cv::Rect(80, 60, 160, 120));

  fake->Close();  // the network is now slow: frames 1 and 2 are not ready when tracked
  segmenter.Submit(1, stamp(1), frame(1));
  const Segmentation one = source.MasksFor(1, stamp(1), frame(1));
  segmenter.Submit(2, stamp(2), frame(2));
  const Segmentation two = source.MasksFor(2, stamp(2), frame(2));
  ASSERT_EQ(one.instances.size(), 1u);
  ASSERT_EQ(two.instances.size(), 1u);
  EXPECT_EQ(two.frame_index, 2u);
  EXPECT_NEAR(one.instances[0].box.x, 86, 2);
  EXPECT_NEAR(two.instances[0].box.x, 92, 2);
  EXPECT_NEAR(two.instances[0].box.y, 60, 2);
  fake->Open();

  segmenter.Submit(3, stamp(3), frame(3));
  segmenter.Wait(3);
  EXPECT_EQ(source.MasksFor(3, stamp(3), frame(3)).instances.at(0).class_id, 3);

  const SegmentationLatencyStats stats = source.Latency();
  EXPECT_EQ(stats.frames, 4u);
  EXPECT_EQ(stats.fresh, 2u);
  EXPECT_EQ(stats.propagated, 2u);
  EXPECT_EQ(stats.without_masks, 0u);
  EXPECT_DOUBLE_EQ(stats.lag_frames.max, 2.0);
  EXPECT_DOUBLE_EQ(stats.lag_frames.mean, 0.75);
  EXPECT_NEAR(stats.lag_ms.max, 2000.0 / 30.0, 1e-6);
  EXPECT_GT(stats.propagation_ms.median, 0.0);

  const nlohmann::json json = SegmentationStatsJson("fake", segmenter.Stats(), &stats);
  EXPECT_EQ(json["backend"], "fake");
  EXPECT_EQ(json["submitted"], 4);
  EXPECT_EQ(json["segmented"], 4);
  EXPECT_EQ(json["masks"]["propagated"], 2);
  EXPECT_DOUBLE_EQ(json["masks"]["lag_frames"]["max"].get<double>(), 2.0);
  EXPECT_TRUE(json["segment_ms"].contains("p95"));
}

TEST(MaskSourceTest, RealtimeBeforeAnyResultGivesNoMasksAndBlockingModeWaits) {
  auto fake = std::make_shared<testing::FakeSegmenter>();
  fake->Close();
  const cv::Mat image = Texture({64, 48}, 6);
  {
    AsyncSegmenter segmenter(fake);
    MaskSource realtime(segmenter, MaskPropagator(), true);
    segmenter.Submit(0, 0.0, image);
    const Segmentation none = realtime.MasksFor(0, 0.0, image);
    EXPECT_TRUE(none.instances.empty());
    EXPECT_EQ(none.image_size, image.size());
    EXPECT_EQ(realtime.Latency().without_masks, 1u);
    fake->Open();
  }
  AsyncSegmenter segmenter(fake);
  MaskSource blocking(segmenter, MaskPropagator(), false);
  segmenter.Submit(4, 0.0, image);
  EXPECT_EQ(blocking.MasksFor(4, 0.0, image).instances.at(0).class_id, 4);
  EXPECT_EQ(blocking.Latency().fresh, 1u);
}

}  // namespace
}  // namespace drvslam
