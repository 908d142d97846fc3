// The whole stage on rendered frames with ground-truth masks (sequential, as System runs it):
// small share removes every person's features, a large share keeps a standing person's, map
// points on a person who starts moving are culled, the feature target rises after a crowded
// frame, and the debug output is written.
#include "drvslam/dynamic/dynamic_front_end.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/coco_classes.h"
#include "drvslam/core/error.h"
#include "drvslam/dynamic/dynamic_stats_json.h"
#include "drvslam/feature/orb_extractor.h"
#include "drvslam/map/map_point.h"
#include "plane_scene.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;
using test::Camera;
using test::Plane;

// Returns prepared segmentations by frame index.
class ScriptedSegmenter : public Segmenter {
 public:
  explicit ScriptedSegmenter(std::vector<Segmentation> frames) : frames_(std::move(frames)) {
    for (std::string_view name : CocoClassNames()) names_.emplace_back(name);
  }
  Segmentation Segment(const cv::Mat&, double timestamp, std::size_t index) override {
    Segmentation s = frames_.at(index);
    s.timestamp = timestamp;
    s.frame_index = index;
    return s;
  }
  std::string Name() const override { return "scripted"; }
  const std::vector<std::string>& ClassNames() const override { return names_; }

 private:
  std::vector<Segmentation> frames_;
  std::vector<std::string> names_;
};

struct Sequence {
  std::vector<test::Rendered> images;
  std::vector<cv::Mat> bgr;
  std::vector<Segmentation> masks;
};

// `near_x(f)`: x offset of a person at 1.2 m (large in the image) per frame, `far_x(f)`: of a
// person at 3 m. Either may be absent (no plane).
Sequence Render(int frames, bool with_near, const std::function<double(int)>& near_x,
                const std::function<double(int)>& far_x) {
  std::vector<Plane> scene = {{4.0, {-4, -3, 8, 6}, 1, 0.05},
                              {3.0, {-2.0, 0.4, 1.4, 0.5}, 2, 0.04}};
  scene.push_back({3.0, {0.6, -0.8, 0.45, 1.5}, 3, 0.03});
  if (with_near) scene.push_back({1.2, {-0.75, -0.6, 0.5, 1.2}, 4, 0.02});
  Sequence sequence;
  for (int f = 0; f < frames; ++f) {
    Camera camera;
    camera.center = {0.008 * f, 0.002 * f, 0.0};
    std::vector<cv::Point2d> offsets = {{0, 0}, {0, 0}, {far_x(f), 0}};
    if (with_near) offsets.push_back({near_x(f), 0});
    sequence.images.push_back(test::Render(scene, camera, offsets));
    cv::Mat bgr;
    cv::cvtColor(sequence.images.back().gray, bgr, cv::COLOR_GRAY2BGR);
    sequence.bgr.push_back(bgr);
    Segmentation segmentation;
    segmentation.image_size = bgr.size();
    segmentation.instances = test::InstancesOf(
        sequence.images.back(), with_near ? std::vector<int>{2, 3} : std::vector<int>{2});
    sequence.masks.push_back(segmentation);
  }
  return sequence;
}

class DynamicFrontEndTest : public ::testing::Test {
 protected:
  DynamicFrontEndTest() {
    CameraOptions camera;
    camera.fx = camera.fy = 525.0;
    camera.cx = 319.5;
    camera.cy = 239.5;
    geometry_ = std::make_shared<SensorGeometry>(camera, ScalePyramid(8, 1.2), 3.0);
  }

  Frame Extract(const Sequence& sequence, int f, int target = 0) {
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    extractor_.Extract(sequence.images[f].gray, cv::Mat(), target, &keypoints, &descriptors);
    return Frame(f, 0.033 * f,
                 std::make_shared<const FrameFeatures>(geometry_, std::move(keypoints), descriptors,
                                                       sequence.images[f].depth));
  }

  static int CountOn(const Frame& frame, const cv::Mat& labels, int label) {
    int count = 0;
    for (const cv::KeyPoint& kp : frame.Features().Keypoints()) {
      count += labels.at<int>(cvRound(kp.pt.y), cvRound(kp.pt.x)) == label;
    }
    return count;
  }

  std::shared_ptr<const SensorGeometry> geometry_;
  OrbExtractor extractor_{OrbExtractorOptions()};
  Map map_;
};

TEST_F(DynamicFrontEndTest, SmallShareRemovesEveryPersonsFeatures) {
  // One person standing still at 3 m: a small share, so its features go although it is static.
  const Sequence sequence = Render(4, false, nullptr, [](int) { return 0.0; });
  DynamicFrontEndConfig config;
  config.segmenter = std::make_shared<ScriptedSegmenter>(sequence.masks);
  config.sequential = true;
  DynamicFrontEnd stage(config, 1000, map_, nullptr);
  for (int f = 0; f < 4; ++f) {
    EXPECT_EQ(stage.BeginFrame(0.033 * f, sequence.bgr[f]), 1000);
    const Frame full = Extract(sequence, f);
    const int on_person = CountOn(full, sequence.images[f].labels, 3);
    ASSERT_GT(on_person, 10);
    const Frame kept = stage.Filter(Frame(full), sequence.bgr[f], sequence.images[f].depth);
    EXPECT_EQ(CountOn(kept, sequence.images[f].labels, 3), 0) << "frame " << f;
    EXPECT_EQ(kept.Id(), full.Id());
    const DynamicFrameReport& report = stage.LastReport();
    EXPECT_FALSE(report.large_share);
    EXPECT_GE(report.removed_on_objects, on_person);
    // Only a thin dilated margin of background goes with the person.
    EXPECT_LE(report.removed_on_objects, on_person + 40) << "frame " << f;
    EXPECT_EQ(static_cast<int>(kept.Size()),
              report.features_extracted - report.removed_on_objects - report.removed_unlabelled);
    ASSERT_EQ(report.objects.size(), 1u);
    if (f > 0) {
      EXPECT_FALSE(report.objects[0].moving) << "frame " << f;
      EXPECT_EQ(report.removed_unlabelled, 0) << "frame " << f;
    }
  }
  EXPECT_EQ(stage.Stats().ids_issued, 1u);
}

TEST_F(DynamicFrontEndTest, LargeShareKeepsAStandingPersonAndCullsItsPointsWhenItMoves) {
  // A near person stands for 4 frames, then walks; a far person walks throughout.
  const auto near_x = [](int f) { return f < 4 ? 0.0 : 0.03 * (f - 3); };
  const auto far_x = [](int f) { return -0.04 * f; };
  const Sequence sequence = Render(8, true, near_x, far_x);
  DynamicFrontEndConfig config;
  config.segmenter = std::make_shared<ScriptedSegmenter>(sequence.masks);
  config.sequential = true;
  StageTimings timings;
  DynamicFrontEnd stage(config, 1000, map_, &timings);
  std::vector<std::shared_ptr<MapPoint>> near_points;
  long next_point = 0;
  for (int f = 0; f < 8; ++f) {
    const int target = stage.BeginFrame(0.033 * f, sequence.bgr[f]);
    if (f > 0) {
      EXPECT_GT(target, 1000) << "the previous frame was crowded";
    }
    const Frame full = Extract(sequence, f, target);
    Frame kept = stage.Filter(Frame(full), sequence.bgr[f], sequence.images[f].depth);
    const DynamicFrameReport& report = stage.LastReport();
    ASSERT_EQ(report.objects.size(), 2u);
    EXPECT_TRUE(report.large_share) << "share " << report.share;
    const int near_kept = CountOn(kept, sequence.images[f].labels, 4);
    if (f >= 1 && f <= 3) {
      EXPECT_FALSE(report.objects[1].moving) << "frame " << f;
      EXPECT_GT(near_kept, 20) << "a standing person keeps its features (frame " << f << ")";
      EXPECT_TRUE(report.objects[0].moving) << "frame " << f;
      EXPECT_EQ(CountOn(kept, sequence.images[f].labels, 3), 0) << "frame " << f;
      // Tracking would match these to map points: file them.
      for (std::size_t i = 0; i < kept.Size(); ++i) {
        const cv::Point2f& p = kept.Features().Keypoints()[i].pt;
        if (sequence.images[f].labels.at<int>(cvRound(p.y), cvRound(p.x)) != 4) continue;
        auto point = std::make_shared<MapPoint>(next_point++, Eigen::Vector3d(0, 0, 1.2), nullptr);
        map_.AddMapPoint(point);
        kept.map_points[i] = point;
        near_points.push_back(point);
      }
      stage.AfterTracking(kept);
    }
    if (f >= 5) {
      EXPECT_TRUE(report.objects[1].moving) << "frame " << f;
      EXPECT_EQ(near_kept, 0) << "frame " << f;
    }
  }
  ASSERT_FALSE(near_points.empty());
  for (const auto& point : near_points) EXPECT_TRUE(point->IsBad());
  EXPECT_EQ(map_.MapPointCount(), 0u);
  EXPECT_EQ(stage.Stats().map_points_culled, near_points.size());
  const auto summaries = timings.Summaries();
  EXPECT_EQ(summaries.at("motion_consistency").count, 8u);
  EXPECT_EQ(summaries.at("removal").count, 8u);
  EXPECT_EQ(summaries.at("segmentation_wait").count, 8u);
  EXPECT_EQ(summaries.at("segmentation").count, 8u);
  const nlohmann::json json = DynamicStatsJson(stage.Stats());
  EXPECT_EQ(json["frames"], 8);
  EXPECT_EQ(json["frames_large_share"], 8);
  EXPECT_EQ(DynamicSegmentationJson(stage.Stats())["segmented"], 8);
}

TEST_F(DynamicFrontEndTest, WritesDebugPicturesAndObjectRows) {
  const Sequence sequence = Render(3, false, nullptr, [](int f) { return 0.04 * f; });
  const fs::path dir = fs::temp_directory_path() /
                       ("drvslam_dynamic_debug_" +
                        std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::remove_all(dir);
  DynamicFrontEndConfig config;
  config.segmenter = std::make_shared<ScriptedSegmenter>(sequence.masks);
  config.sequential = true;
  config.debug_dir = dir.string();
  {
    DynamicFrontEnd stage(config, 1000, map_, nullptr);
    for (int f = 0; f < 3; ++f) {
      stage.BeginFrame(0.033 * f, sequence.bgr[f]);
      stage.Filter(Extract(sequence, f), sequence.bgr[f], sequence.images[f].depth);
    }
  }
  for (int f = 0; f < 3; ++f) {
    EXPECT_TRUE(fs::exists(dir / ("frame_00000" + std::to_string(f) + ".png")));
  }
  std::ifstream csv(dir / "objects.csv");
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_EQ(lines, 1 + 3);  // header + one person per frame
  fs::remove_all(dir);
}

TEST_F(DynamicFrontEndTest, WithoutASegmenterMovingThingsAreFoundByGeometry) {
  // Nobody names the walking "person": its moving points form an unlabelled region. The
  // rendered scene fits its model tightly, so the region goes at once (no frame of waiting).
  const Sequence sequence = Render(5, false, nullptr, [](int f) { return -0.05 * f; });
  DynamicFrontEndConfig config;
  config.sequential = true;
  DynamicFrontEnd stage(config, 1000, map_, nullptr);
  for (int f = 0; f < 5; ++f) {
    stage.BeginFrame(0.033 * f, sequence.bgr[f]);
    const Frame full = Extract(sequence, f);
    const Frame kept = stage.Filter(Frame(full), sequence.bgr[f], sequence.images[f].depth);
    if (f == 0) continue;
    const DynamicFrameReport& report = stage.LastReport();
    EXPECT_TRUE(report.unlabelled_weighed);
    EXPECT_EQ(report.unlabelled_evidence.verdict, UnlabelledVerdict::kTrusted) << "frame " << f;
    EXPECT_EQ(report.unlabelled_pending, 0) << "frame " << f;
    const int before = CountOn(full, sequence.images[f].labels, 3);
    const int after = CountOn(kept, sequence.images[f].labels, 3);
    EXPECT_LE(after, before / 3) << "frame " << f << ": " << after << " of " << before;
    EXPECT_FALSE(stage.LastReport().unlabelled.empty());
  }
  EXPECT_EQ(stage.Stats().segmenter, "none");
  EXPECT_FALSE(stage.Stats().segmentation.has_value());
}

TEST_F(DynamicFrontEndTest, TheFeatureFloorKeepsBackUnlabelledRemovalsFirst) {
  // A walking person no detector names, and a floor above what removal leaves.
  const Sequence sequence = Render(4, false, nullptr, [](int f) { return -0.05 * f; });
  DynamicFrontEndConfig config;
  config.sequential = true;
  config.options.unlabelled_frames = 1;
  DynamicFrontEnd plain(config, 1000, map_, nullptr);
  config.options.min_kept_features = 100000;
  DynamicFrontEnd floored(config, 1000, map_, nullptr);
  for (int f = 0; f < 4; ++f) {
    plain.BeginFrame(0.033 * f, sequence.bgr[f]);
    floored.BeginFrame(0.033 * f, sequence.bgr[f]);
    const Frame full = Extract(sequence, f);
    const Frame without = plain.Filter(Frame(full), sequence.bgr[f], sequence.images[f].depth);
    const Frame with = floored.Filter(Frame(full), sequence.bgr[f], sequence.images[f].depth);
    EXPECT_EQ(with.Size(), full.Size()) << "frame " << f;
    EXPECT_EQ(floored.LastReport().kept_back, plain.LastReport().removed_unlabelled);
    EXPECT_EQ(floored.LastReport().removed_unlabelled, 0);
  }
  EXPECT_GT(plain.Stats().removed_unlabelled, 50u);
  EXPECT_EQ(floored.Stats().features_kept_back, plain.Stats().removed_unlabelled);
  EXPECT_EQ(floored.Stats().frames_floor, 3u);
  const nlohmann::json json = DynamicStatsJson(floored.Stats());
  EXPECT_EQ(json["features"]["kept_back"], plain.Stats().removed_unlabelled);
  EXPECT_EQ(json["frames_floor"], 3);
  EXPECT_TRUE(json["unlabelled"]["frames_suppressed"].contains("camera"));
}

TEST_F(DynamicFrontEndTest, CallOrderIsChecked) {
  DynamicFrontEndConfig config;
  config.sequential = true;
  DynamicFrontEnd stage(config, 1000, map_, nullptr);
  const Sequence sequence = Render(1, false, nullptr, [](int) { return 0.0; });
  EXPECT_THROW(stage.Filter(Extract(sequence, 0), sequence.bgr[0], sequence.images[0].depth),
               Error);
  stage.BeginFrame(0.0, sequence.bgr[0]);
  EXPECT_THROW(stage.BeginFrame(0.0, sequence.bgr[0]), Error);
}

}  // namespace
}  // namespace drvslam
