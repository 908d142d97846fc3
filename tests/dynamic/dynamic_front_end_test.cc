// The whole stage on rendered frames with ground-truth masks (sequential, as System runs it):
// small share removes every person's features, a large share keeps a standing person's, map
// points on a person who starts moving are culled, the feature target rises after a crowded
// frame, and the debug output is written. Without a segmenter, a blurred frame carries the
// regions found before it and is flagged as unchecked, and regions reach further around a
// walker than beside a segmenter. Realtime waits and the flow helper
// thread are in dynamic_front_end_realtime_test.cc.
#include "drvslam/dynamic/dynamic_front_end.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/dynamic/dynamic_stats_json.h"
#include "drvslam/map/map_point.h"
#include "dynamic_front_end_fixture.h"
#include "test_support/temp_folder.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;
using test::DynamicFrontEndTest;
using test::Render;
using test::ScriptedSegmenter;
using test::Sequence;

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
  const fs::path dir = drvslam::testing::UniqueTempFolder("drvslam_dynamic_debug");
  DynamicFrontEndConfig config;
  config.segmenter = std::make_shared<ScriptedSegmenter>(sequence.masks);
  config.sequential = true;
  config.debug_dir = dir.string();
  {
    DynamicFrontEnd stage(config, 1000, map_, nullptr);
    for (int f = 0; f < 3; ++f) {
      RunFrame(stage, sequence, f);
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

// Without a segmenter the regions reach Dynamic.regionReachWithoutSegmenter metres around their
// moving points (a near walker is covered, not just sampled); beside a segmenter
// Dynamic.regionReach applies instead, and neither value touches the other's case.
TEST_F(DynamicFrontEndTest, TheRegionReachDependsOnWhetherASegmenterRuns) {
  // The near person (1.2 m, about 220 px wide) walks; the far one stands.
  const Sequence sequence = Render(
      5, true, [](int f) { return 0.04 * f; }, [](int) { return 0.0; });
  // A segmenter that names only the far person leaves the near one to geometry.
  std::vector<Segmentation> far_only = sequence.masks;
  for (int f = 0; f < 5; ++f) far_only[f].instances = test::InstancesOf(sequence.images[f], {2});
  // Features kept on the near person over frames 1-4.
  const auto kept_on_near = [&](bool with_segmenter, double reach, double reach_alone) {
    DynamicFrontEndConfig config;
    config.sequential = true;
    if (with_segmenter) config.segmenter = std::make_shared<ScriptedSegmenter>(far_only);
    config.options.region_reach = reach;
    config.options.region_reach_without_segmenter = reach_alone;
    Map map;
    DynamicFrontEnd stage(config, 1000, map, nullptr);
    std::vector<int> kept_per_frame;
    for (int f = 0; f < 5; ++f) {
      stage.BeginFrame(0.033 * f, sequence.bgr[f]);
      const Frame kept =
          stage.Filter(Extract(sequence, f), sequence.bgr[f], sequence.images[f].depth);
      if (f > 0) kept_per_frame.push_back(CountOn(kept, sequence.images[f].labels, 4));
    }
    return kept_per_frame;
  };
  const std::vector<int> pixels_only = kept_on_near(false, 0.0, 0.0);
  const std::vector<int> reached = kept_on_near(false, 0.0, 0.3);
  int sum_pixels_only = 0, sum_reached = 0;
  for (int k = 0; k < 4; ++k) {
    EXPECT_LE(reached[k], pixels_only[k]) << "frame " << k + 1;
    sum_pixels_only += pixels_only[k];
    sum_reached += reached[k];
  }
  EXPECT_LE(sum_reached * 2, sum_pixels_only) << sum_reached << " of " << sum_pixels_only;
  // Dynamic.regionReach is not the one used without a segmenter ...
  EXPECT_EQ(kept_on_near(false, 0.3, 0.0), pixels_only);
  // ... and beside one it is, while
  // Dynamic.regionReachWithoutSegmenter is not.
  const std::vector<int> beside_pixels_only = kept_on_near(true, 0.0, 0.0);
  EXPECT_NE(kept_on_near(true, 0.3, 0.0), beside_pixels_only);
  EXPECT_EQ(kept_on_near(true, 0.0, 0.3), beside_pixels_only);
}

TEST_F(DynamicFrontEndTest, WithoutASegmenterABlurredFrameCarriesItsMoversAndIsUnchecked) {
  // Geometry alone finds the walking "person" in frames 1-3; frame 4 is blurred, so its own
  // evidence is not believed: the region is carried onto it, and the frame is flagged as one
  // whose movers nothing could look for (no keyframe should be made of it). With a segmenter
  // the masks say where the movers are, and no frame is flagged.
  Sequence sequence = Render(5, false, nullptr, [](int f) { return -0.05 * f; });
  cv::GaussianBlur(sequence.bgr[4], sequence.bgr[4], cv::Size(), 3.0);
  for (const bool with_segmenter : {false, true}) {
    DynamicFrontEndConfig config;
    config.sequential = true;
    if (with_segmenter) config.segmenter = std::make_shared<ScriptedSegmenter>(sequence.masks);
    DynamicFrontEnd stage(config, 1000, map_, nullptr);
    for (int f = 0; f < 5; ++f) {
      stage.BeginFrame(0.033 * f, sequence.bgr[f]);
      const Frame full = Extract(sequence, f);
      const Frame kept = stage.Filter(Frame(full), sequence.bgr[f], sequence.images[f].depth);
      const DynamicFrameReport& report = stage.LastReport();
      if (f < 4) {
        EXPECT_FALSE(report.sharpness.blurred) << "frame " << f;
        EXPECT_FALSE(stage.MoversUnchecked()) << "frame " << f;
        continue;
      }
      EXPECT_TRUE(report.sharpness.blurred);
      EXPECT_EQ(stage.MoversUnchecked(), !with_segmenter);
      if (with_segmenter) continue;
      EXPECT_EQ(report.unlabelled_evidence.verdict, UnlabelledVerdict::kBlurred);
      EXPECT_GT(report.unlabelled_carried, 0);
      const int before = CountOn(full, sequence.images[f].labels, 3);
      EXPECT_LE(CountOn(kept, sequence.images[f].labels, 3), before / 3);
    }
  }
}

TEST_F(DynamicFrontEndTest, NoFeaturesAreExtractedOnObjectsBelievedMoving) {
  // A walking person at 3 m: once judged moving, the skip mask covers it where it is now (its
  // own masks, sequential) and the extractor finds nothing there; with the option off, no mask.
  const Sequence sequence = Render(6, false, nullptr, [](int f) { return -0.05 * f; });
  for (const bool skip : {true, false}) {
    DynamicFrontEndConfig config;
    config.segmenter = std::make_shared<ScriptedSegmenter>(sequence.masks);
    config.sequential = true;
    config.options.skip_moving_extraction = skip;
    DynamicFrontEnd stage(config, 1000, map_, nullptr);
    int masked_frames = 0;
    for (int f = 0; f < 6; ++f) {
      stage.BeginFrame(0.033 * f, sequence.bgr[f]);
      const cv::Mat mask = stage.MovingSkipMask();
      if (!skip) {
        EXPECT_TRUE(mask.empty()) << "frame " << f;
      }
      if (!mask.empty()) {
        ++masked_frames;
        ASSERT_EQ(mask.size(), sequence.bgr[f].size());
        const cv::Mat person = sequence.images[f].labels == 3;
        cv::Mat covered;
        cv::bitwise_and(mask, person, covered);
        EXPECT_GE(cv::countNonZero(covered), cv::countNonZero(person) * 95 / 100) << "frame " << f;
        EXPECT_GT(CountOn(Extract(sequence, f), sequence.images[f].labels, 3), 20);
        EXPECT_EQ(CountOn(Extract(sequence, f, 0, mask), sequence.images[f].labels, 3), 0);
        EXPECT_GT(stage.LastReport().skip_share, 0.0);
      }
      stage.Filter(Extract(sequence, f), sequence.bgr[f], sequence.images[f].depth);
    }
    if (skip) {
      EXPECT_GE(masked_frames, 3);
      EXPECT_EQ(stage.Stats().frames_skip_mask, static_cast<std::size_t>(masked_frames));
    }
  }
}

TEST_F(DynamicFrontEndTest, AWalkingPersonKeepsItsIdThroughAThreeFrameDetectionGap) {
  // The network misses the walking person on frames 3, 4 and 5.
  const int frames = 9;
  Sequence sequence = Render(frames, false, nullptr, [](int f) { return 0.04 * f; });
  for (int f = 3; f <= 5; ++f) sequence.masks[f].instances.clear();
  for (const int memory : {5, 0}) {
    SCOPED_TRACE("Dynamic.objectMemoryFrames " + std::to_string(memory));
    DynamicFrontEndConfig config;
    config.segmenter = std::make_shared<ScriptedSegmenter>(sequence.masks);
    config.sequential = true;
    config.options.object_memory_frames = memory;
    DynamicFrontEnd stage(config, 1000, map_, nullptr);
    std::vector<int> ids(frames, -1);
    std::vector<bool> moving(frames, false);
    for (int f = 0; f < frames; ++f) {
      RunFrame(stage, sequence, f);
      const DynamicFrameReport& report = stage.LastReport();
      ASSERT_EQ(report.instances.size(), f >= 3 && f <= 5 ? 0u : 1u) << "frame " << f;
      if (report.instances.empty()) continue;
      ids[f] = report.instances[0].track_id;
      moving[f] = report.objects[0].moving;
    }
    EXPECT_TRUE(moving[2]);
    EXPECT_TRUE(moving[6]);
    if (memory > 0) {
      EXPECT_EQ(ids[6], ids[2]);
      EXPECT_EQ(stage.Stats().ids_issued, 1u);
    } else {
      EXPECT_NE(ids[6], ids[2]);
      EXPECT_EQ(stage.Stats().ids_issued, 2u);
    }
    EXPECT_EQ(ids[8], ids[6]);
  }
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
