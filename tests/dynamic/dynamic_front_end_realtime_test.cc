// The stage in realtime mode over a scripted network (likely keyframes wait for their own
// masks within a bound, the network backs off after skipped frames, late masks are carried by
// flow tracks, movers whose masks aged out stop keyframes for a while) and with its flow on the
// helper thread (same frames; no job outlives the stage).
#include <gtest/gtest.h>

#include <memory>
#include <utility>
#include <vector>

#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/map/map_point.h"
#include "dynamic_front_end_fixture.h"
#include "test_support/map_points.h"

namespace drvslam {
namespace {

using test::DynamicFrontEndTest;
using test::GatedSegmenter;
using test::HoldingSegmenter;
using test::OpenAtExit;
using test::Render;
using test::ScriptedSegmenter;
using test::Sequence;

// --realtime over `network`, carrying masks for `carry_frames` frames.
DynamicFrontEndConfig CarryConfig(std::shared_ptr<Segmenter> network, int carry_frames) {
  DynamicFrontEndConfig config;
  config.segmenter = std::move(network);
  config.realtime = true;
  config.segmentation.carry_frames = carry_frames;
  return config;
}

// The same, where the rendered person (more than 0.01 of the image) counts as a crowd
// (Dynamic.largeShare 0.01).
DynamicFrontEndConfig CrowdConfig(std::shared_ptr<Segmenter> network, int carry_frames) {
  DynamicFrontEndConfig config = CarryConfig(std::move(network), carry_frames);
  config.options.large_share = 0.01;
  return config;
}

TEST_F(DynamicFrontEndTest, RealtimeLikelyKeyFramesWaitForTheirOwnMasksOthersNever) {
  // A 100 ms network. Frame 1 is expected to become a keyframe, but frame 0 is ahead of it on
  // the network: a whole forward pass away, it does not wait. Frame 2 is expected too and the
  // network is idle when it comes: it waits (up to 1 s, 10 times its 100 ms pass) and gets its
  // own masks. Frame 3 is not expected: it never waits.
  // Frames 0, 1 and 3 are held on the network until released, so that they are still running
  // when frames 1 and 3 ask (a 300 ms pass against a ~30 ms frame made that likely before).
  const Sequence sequence = Render(4, false, nullptr, [](int f) { return -0.05 * f; });
  DynamicFrontEndConfig config = RealtimeConfig(sequence, 100, 1000.0);
  const auto network =
      std::make_shared<HoldingSegmenter>(sequence.masks, 100, std::set<std::size_t>{0, 1, 3});
  config.segmenter = network;
  DynamicFrontEnd stage(config, 1000, map_, nullptr);
  const OpenAtExit<HoldingSegmenter> release_at_exit(*network);
  const bool likely[] = {false, true, true, false};
  const bool own[] = {false, false, true, false};
  for (int f = 0; f < 4; ++f) {
    if (f == 2) {
      // Before frame 2 the network finishes frames 0 and 1 and goes idle (awaited: a 900 ms
      // sleep for two 300 ms passes stood for it before).
      network->Release(0);
      network->Release(1);
      ASSERT_TRUE(AwaitIdleNetwork(stage));
    }
    RunFrame(stage, sequence, f, likely[f]);
    EXPECT_EQ(stage.LastReport().own_masks, own[f]) << "frame " << f;
    stage.NoteKeyFrame(KeyFrameIf(likely[f], f));
  }
  const DynamicStats stats = stage.Stats();
  EXPECT_EQ(stats.keyframe_waits, 1u);
  EXPECT_EQ(stats.keyframe_waits_fresh, 1u);
  EXPECT_EQ(stats.keyframes, 2u);
  EXPECT_EQ(stats.keyframes_expected, 2u);
  EXPECT_EQ(stats.keyframes_own_masks, 1u);
}

TEST_F(DynamicFrontEndTest, RealtimeAFrameStartingAMapWaitsForItsOwnMasksWithinTheBound) {
  // Before the network's first pass there is no expected pass time, so a likely keyframe would
  // not wait; a frame that would start a map does, up to Segmentation.mapStartWaitMs. With a
  // 100 ms network and a 1 s bound it gets its own masks. With a 20 ms bound (the pass held on
  // the network until the test ends) it gives up after the bound; with 0 it never waits. It
  // waits in BeginFrame, before extraction (timed as map_start_wait).
  const Sequence sequence = Render(1, false, nullptr, [](int) { return 0.0; });
  for (const double bound_ms : {1000.0, 20.0, 0.0}) {
    const bool held = bound_ms < 100.0;
    DynamicFrontEndConfig config = RealtimeConfig(sequence, 100, 0.0);
    const auto network = std::make_shared<HoldingSegmenter>(
        sequence.masks, 100, held ? std::set<std::size_t>{0} : std::set<std::size_t>{});
    config.segmenter = network;
    config.segmentation.map_start_wait_ms = bound_ms;
    StageTimings timings;
    DynamicFrontEnd stage(config, 1000, map_, &timings);
    const OpenAtExit<HoldingSegmenter> release_at_exit(*network);
    stage.BeginFrame(0.0, sequence.bgr[0], /*keyframe_likely=*/true, /*starts_map=*/true);
    stage.Filter(Extract(sequence, 0), sequence.bgr[0], sequence.images[0].depth);
    EXPECT_EQ(stage.LastReport().own_masks, !held) << bound_ms;
    EXPECT_EQ(stage.LastReport().instances.size(), held ? 0u : 1u) << bound_ms;
    stage.NoteKeyFrame(KeyFrameIf(true, 0));
    const DynamicStats stats = stage.Stats();
    EXPECT_EQ(stats.map_starts, 1u);
    EXPECT_EQ(stats.map_starts_own_masks, held ? 0u : 1u);
    EXPECT_EQ(stats.keyframe_waits, 0u);  // the map start's wait is not a keyframe wait
    if (bound_ms == 20.0) {
      EXPECT_GE(timings.Summaries().at("map_start_wait").max_ms, 19.0);
    }
  }
}

TEST_F(DynamicFrontEndTest, RealtimeNetworkBacksOffWhenFramesAreSkipped) {
  // Frames 0-7 at 30 Hz, each segmented before the next comes; frame 8 is skipped, so frame 9
  // arrives two periods after frame 7 and is not handed to the network (it rests one pass).
  // With Segmentation.backoffPasses 0 every frame goes to the network.
  const Sequence sequence = Render(10, false, nullptr, [](int) { return 0.0; });
  for (const double backoff_passes : {1.0, 0.0}) {
    DynamicFrontEndConfig config = RealtimeConfig(sequence, 40, 0.0);
    config.segmentation.backoff_passes = backoff_passes;
    DynamicFrontEnd stage(config, 1000, map_, nullptr);
    for (const int f : {0, 1, 2, 3, 4, 5, 6, 7, 9}) {
      RunFrame(stage, sequence, f);
      ASSERT_TRUE(AwaitIdleNetwork(stage));
    }
    const DynamicStats stats = stage.Stats();
    if (backoff_passes > 0.0) {
      ASSERT_TRUE(stats.pacing.has_value());
      EXPECT_EQ(stats.pacing->backoffs, 1u);
      EXPECT_EQ(stats.pacing->frames_held, 1u);
      EXPECT_EQ(stats.segmentation->submitted, 8u);
      EXPECT_FALSE(stage.LastReport().own_masks);
    } else {
      EXPECT_FALSE(stats.pacing.has_value());
      EXPECT_EQ(stats.segmentation->submitted, 9u);
    }
  }
}

TEST_F(DynamicFrontEndTest, RealtimeKeyFrameWaitIsBounded) {
  // keyframeWaitMs 20 against a 600 ms network: the likely keyframe gives up and goes on.
  const Sequence sequence = Render(1, false, nullptr, [](int) { return 0.0; });
  StageTimings timings;
  DynamicFrontEnd stage(RealtimeConfig(sequence, 600, 20.0), 1000, map_, &timings);
  RunFrame(stage, sequence, 0, true);
  EXPECT_FALSE(stage.LastReport().own_masks);
  EXPECT_EQ(stage.Stats().keyframe_waits, 1u);
  EXPECT_EQ(stage.Stats().keyframe_waits_fresh, 0u);
  const TimingSummary wait = timings.Summaries().at("segmentation_wait");
  EXPECT_GE(wait.max_ms, 19.0);
  EXPECT_LT(wait.max_ms, 400.0);  // generous: far below the network's 600 ms
}

TEST_F(DynamicFrontEndTest, RealtimeKeyFrameDoesNotWaitForMasksDueAfterItsBound) {
  // A 1 s network and a 300 ms bound. Frame 0 is segmented first (its pass sets the estimate).
  // Frame 1 is a likely keyframe that the idle network is about to take, but its masks are
  // due a whole pass later: waiting 300 ms could not bring them, so it does not wait at all.
  // (A 300 ms network and a 20 ms bound before: a frame that did not wait had to take under
  // 19 ms, which a loaded machine's pauses of ~30 ms break. Measured 0.4-0.6 ms; the bound
  // below, 290 ms, is 500 times that.)
  const Sequence sequence = Render(2, false, nullptr, [](int) { return 0.0; });
  StageTimings timings;
  DynamicFrontEnd stage(RealtimeConfig(sequence, 1000, 300.0), 1000, map_, &timings);
  RunFrame(stage, sequence, 0, false);
  ASSERT_TRUE(AwaitIdleNetwork(stage));  // frame 0's pass is done (a 600 ms sleep before)
  RunFrame(stage, sequence, 1, true);
  EXPECT_FALSE(stage.LastReport().own_masks);
  EXPECT_EQ(stage.Stats().keyframe_waits, 0u);
  const TimingSummary wait = timings.Summaries().at("segmentation_wait");
  EXPECT_LT(wait.max_ms, 290.0);
}

TEST_F(DynamicFrontEndTest, RealtimeCarriesLaggingMasksOntoAWalkingPersonByItsTracks) {
  // Frame 0 is segmented; the network then stalls, so frames 1..6 get frame 0's masks carried
  // along the flow tracks (Segmentation.propagation objects, the default).
  const int frames = 7;
  const Sequence sequence = Render(frames, false, nullptr, [](int f) { return 0.04 * f; });
  auto segmenter = std::make_shared<GatedSegmenter>(sequence.masks);
  DynamicFrontEndConfig config;
  config.segmenter = segmenter;
  config.realtime = true;
  ASSERT_EQ(config.segmentation.propagation, MaskPropagation::kObjects);
  StageTimings timings;
  DynamicFrontEnd stage(config, 1000, map_, &timings);
  const OpenAtExit<GatedSegmenter> open_at_exit(*segmenter);
  int first_id = -1;
  for (int f = 0; f < frames; ++f) {
    BeginGatedFrame(stage, sequence, f);
    stage.Filter(Extract(sequence, f), sequence.bgr[f], sequence.images[f].depth);
    const DynamicFrameReport& report = stage.LastReport();
    ASSERT_EQ(report.instances.size(), 1u) << "frame " << f;
    const cv::Mat& truth = sequence.masks[f].instances[0].mask;
    EXPECT_GE(MaskIoU(report.instances[0].mask, truth), 0.9) << "frame " << f;
    if (f == 0) first_id = report.instances[0].track_id;
    EXPECT_EQ(report.instances[0].track_id, first_id) << "frame " << f;
    EXPECT_TRUE(report.objects[0].moving || f == 0) << "frame " << f;
  }
  // Left where it was, frame 0's mask would have slid off the person.
  EXPECT_LT(
      MaskIoU(sequence.masks[0].instances[0].mask, sequence.masks[frames - 1].instances[0].mask),
      0.7);
  const DynamicStats stats = stage.Stats();
  ASSERT_TRUE(stats.latency.has_value());
  EXPECT_EQ(stats.latency->fresh, 1u);
  EXPECT_EQ(stats.latency->propagated, static_cast<std::size_t>(frames - 1));
  EXPECT_EQ(stats.latency->lag_frames.max, frames - 1.0);
  EXPECT_EQ(timings.Summaries().at("segmentation_wait").count, static_cast<std::size_t>(frames));
}

TEST_F(DynamicFrontEndTest, RealtimeMasksOfMoversThatAgeOutVetoKeyFramesForABoundedTime) {
  // Frame 0 is segmented; the network then stalls. With Segmentation.carryFrames 2, frames 1-2
  // get frame 0's masks carried, frames 3-4 have none left while a person was in view (movers
  // unchecked: no keyframe), and from frame 5 on mapping may go on without masks. Masks of a
  // class that does not move (a chair) age out without stopping keyframes.
  const int frames = 7;
  const Sequence sequence = Render(frames, false, nullptr, [](int f) { return 0.04 * f; });
  for (const int class_id : {0, 56}) {
    std::vector<Segmentation> masks = sequence.masks;
    for (Segmentation& frame_masks : masks) {
      for (Instance& instance : frame_masks.instances) instance.class_id = class_id;
    }
    auto segmenter = std::make_shared<GatedSegmenter>(masks);
    DynamicFrontEnd stage(CarryConfig(segmenter, 2), 1000, map_, nullptr);
    const OpenAtExit<GatedSegmenter> open_at_exit(*segmenter);
    const bool person = class_id == 0;
    const bool unchecked[] = {false, false, false, person, person, false, false};
    for (int f = 0; f < frames; ++f) {
      BeginGatedFrame(stage, sequence, f);
      stage.Filter(Extract(sequence, f), sequence.bgr[f], sequence.images[f].depth);
      EXPECT_EQ(stage.LastReport().instances.size(), f <= 2 ? 1u : 0u)
          << "class " << class_id << ", frame " << f;
      EXPECT_EQ(stage.MoversUnchecked(), unchecked[f]) << "class " << class_id << ", frame " << f;
    }
    EXPECT_EQ(stage.Stats().frames_masks_expired, person ? 2u : 0u) << "class " << class_id;
  }
}

TEST_F(DynamicFrontEndTest, RealtimeMasksOfASlowNetworkAreCarriedUntilItStalls) {
  // Segmentation.carryFrames 2. Frame 0 has its own masks; frame 1's pass ends only after
  // frame 3 was tracked, so its masks come three frames late, later than carryFrames. They
  // are still carried (from frame 4 on): the network is slow, not stalled. Frame 0's masks are
  // carried two more frames and gone on the third (frame 3); frame 1's, which came at frame 4,
  // are carried to frame 6 and gone at frame 7. Masks older than carryFrames still keep
  // keyframes waiting: frames 3 and 4 (the bound of two in a row, no keyframe between).
  const int frames = 9;
  const Sequence sequence = Render(frames, false, nullptr, [](int f) { return 0.04 * f; });
  std::set<std::size_t> held;
  for (std::size_t f = 1; f < static_cast<std::size_t>(frames); ++f) held.insert(f);
  auto segmenter = std::make_shared<HoldingSegmenter>(sequence.masks, 0, held);
  DynamicFrontEnd stage(CarryConfig(segmenter, 2), 1000, map_, nullptr);
  const OpenAtExit<HoldingSegmenter> release_at_exit(*segmenter);
  std::vector<bool> has_masks;
  std::vector<bool> vetoed;
  for (int f = 0; f < frames; ++f) {
    BeginGatedFrame(stage, sequence, f);
    // Taken by the network before frame 2 comes, which would otherwise replace it.
    if (f == 1) {
      ASSERT_TRUE(segmenter->AwaitStarted(1));
    }
    stage.Filter(Extract(sequence, f), sequence.bgr[f], sequence.images[f].depth);
    has_masks.push_back(!stage.LastReport().instances.empty());
    vetoed.push_back(stage.MoversUnchecked());
    if (f == 3) {
      // Frame 1's pass ends; the network then takes frame 3, which stays held.
      segmenter->Release(1);
      for (int wait = 0; wait < 2000 && stage.Stats().segmentation->segmented < 2; ++wait) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
      ASSERT_EQ(stage.Stats().segmentation->segmented, 2u) << "frame 1's masks never came";
    }
  }
  EXPECT_EQ(has_masks,
            (std::vector<bool>{true, true, true, false, true, true, true, false, false}));
  EXPECT_EQ(vetoed,
            (std::vector<bool>{false, false, false, true, true, false, false, false, false}));
}

TEST_F(DynamicFrontEndTest, RealtimeCrowdSeenThroughCarriedMasksVetoesKeyFrames) {
  // Frame 0 is segmented; the network then stalls, so frames 1-4 see the person through frame
  // 0's masks carried (Segmentation.carryFrames 4). With Dynamic.largeShare below the person's
  // share of the image that is a crowd seen through carried masks: no keyframe from frames
  // 1-4. At the default share (the person covers less) keyframes go on; frame 5 has no masks
  // left and is vetoed for that reason, but only there: after the crowd's four vetoed frames
  // the shared bound (carryFrames in a row) lets frame 5 be a keyframe.
  const int frames = 6;
  const Sequence sequence = Render(frames, false, nullptr, [](int f) { return 0.04 * f; });
  for (const double large_share : {0.01, 0.3}) {
    auto segmenter = std::make_shared<GatedSegmenter>(sequence.masks);
    DynamicFrontEndConfig config = CarryConfig(segmenter, 4);
    config.options.large_share = large_share;
    DynamicFrontEnd stage(config, 1000, map_, nullptr);
    const OpenAtExit<GatedSegmenter> open_at_exit(*segmenter);
    const bool crowd = large_share < 0.1;
    for (int f = 0; f < frames; ++f) {
      BeginGatedFrame(stage, sequence, f);
      stage.Filter(Extract(sequence, f), sequence.bgr[f], sequence.images[f].depth);
      const DynamicFrameReport& report = stage.LastReport();
      const bool carried = f >= 1 && f <= 4;
      // The carried person covers more than 0.01 of the image and less than 0.3.
      if (carried) {
        ASSERT_GT(report.share, 0.01) << "frame " << f;
      }
      if (carried) {
        ASSERT_LT(report.share, 0.3) << "frame " << f;
      }
      const bool carried_crowd = crowd && carried;
      EXPECT_EQ(report.crowd_carried, carried_crowd) << "share " << large_share << ", frame " << f;
      EXPECT_EQ(stage.MoversUnchecked(), carried_crowd || (!crowd && f == 5))
          << "share " << large_share << ", frame " << f;
    }
    EXPECT_EQ(stage.Stats().frames_crowd_carried, crowd ? 4u : 0u) << "share " << large_share;
  }
}

TEST_F(DynamicFrontEndTest, TheCrowdAndAgedOutMasksShareOneBoundOnVetoedFrames) {
  // The network stalls after frame 0 (Segmentation.carryFrames 2, the person counting as a
  // crowd): frames 1-2 see the crowd through carried masks, and from frame 3 on its masks have
  // aged out. Both reasons count against one bound of two vetoed frames in a row, so the
  // change of reason at frame 3 does not start a new count: frame 3 may become a keyframe.
  // When it does, frame 4 is vetoed (aged out); from frame 5 on the network has stalled for
  // two frames more, and the person it last saw no longer holds keyframes back. Without
  // keyframes the veto stays off after frame 2. With a count per reason frames 1-4 were all
  // vetoed, and a network whose masks alternately came late and aged out could stop mapping
  // for a whole crowd.
  const int frames = 8;
  const Sequence sequence = Render(frames, false, nullptr, [](int f) { return 0.04 * f; });
  for (const bool keyframe_when_free : {true, false}) {
    auto segmenter = std::make_shared<GatedSegmenter>(sequence.masks);
    DynamicFrontEnd stage(CrowdConfig(segmenter, 2), 1000, map_, nullptr);
    const OpenAtExit<GatedSegmenter> open_at_exit(*segmenter);
    std::vector<bool> vetoed;
    for (int f = 0; f < frames; ++f) {
      BeginGatedFrame(stage, sequence, f);
      stage.Filter(Extract(sequence, f), sequence.bgr[f], sequence.images[f].depth);
      const DynamicFrameReport& report = stage.LastReport();
      if (f >= 1 && f <= 2) {
        ASSERT_FALSE(report.instances.empty()) << "frame " << f;
      }
      if (f >= 3) {
        ASSERT_TRUE(report.instances.empty()) << "frame " << f;
      }
      vetoed.push_back(stage.MoversUnchecked());
      stage.NoteKeyFrame(KeyFrameIf(keyframe_when_free && f > 0 && !vetoed.back(), f));
    }
    const std::vector<bool> expected =
        keyframe_when_free
            ? std::vector<bool>{false, true, true, false, true, false, false, false}
            : std::vector<bool>{false, true, true, false, false, false, false, false};
    EXPECT_EQ(vetoed, expected) << "keyframes when free: " << keyframe_when_free;
    const DynamicStats stats = stage.Stats();
    EXPECT_EQ(stats.frames_crowd_carried, 2u) << "keyframes when free: " << keyframe_when_free;
    EXPECT_EQ(stats.frames_masks_expired, keyframe_when_free ? 1u : 0u)
        << "keyframes when free: " << keyframe_when_free;
  }
}

TEST_F(DynamicFrontEndTest, ALongCarriedCrowdGetsOneKeyFramePerCarryFramesAndOne) {
  // The network keeps up one frame late: frame f is tracked through frame f-1's masks, so the
  // masks never age out. With Segmentation.carryFrames 2 and the person counting as a crowd,
  // frames 1-2 are vetoed and frame 3 may become a keyframe. When it does (NoteKeyFrame), the
  // count starts again: frames 4-5 are vetoed, 6 may be one. Without a keyframe the veto stays
  // off, so a network that never catches up does not stop mapping.
  const int frames = 7;
  const Sequence sequence = Render(frames, false, nullptr, [](int f) { return 0.04 * f; });
  for (const bool keyframe_when_free : {true, false}) {
    std::set<std::size_t> held;
    for (std::size_t f = 1; f < static_cast<std::size_t>(frames); ++f) held.insert(f);
    auto segmenter = std::make_shared<HoldingSegmenter>(sequence.masks, 0, held);
    DynamicFrontEnd stage(CrowdConfig(segmenter, 2), 1000, map_, nullptr);
    const OpenAtExit<HoldingSegmenter> release_at_exit(*segmenter);
    std::vector<bool> vetoed;
    for (int f = 0; f < frames; ++f) {
      BeginGatedFrame(stage, sequence, f);
      stage.Filter(Extract(sequence, f), sequence.bgr[f], sequence.images[f].depth);
      vetoed.push_back(stage.LastReport().crowd_carried);
      if (f > 0) {
        ASSERT_FALSE(stage.LastReport().own_masks) << "frame " << f;
      }
      stage.NoteKeyFrame(KeyFrameIf(keyframe_when_free && f > 0 && !vetoed.back(), f));
      // Frame f's masks arrive before frame f+1 is tracked.
      segmenter->Release(static_cast<std::size_t>(f));
      for (int wait = 0;
           wait < 2000 && stage.Stats().segmentation->segmented < static_cast<std::size_t>(f + 1);
           ++wait) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
      ASSERT_GE(stage.Stats().segmentation->segmented, static_cast<std::size_t>(f + 1))
          << "frame " << f << "'s masks never came";
    }
    const std::vector<bool> expected =
        keyframe_when_free ? std::vector<bool>{false, true, true, false, true, true, false}
                           : std::vector<bool>{false, true, true, false, false, false, false};
    EXPECT_EQ(vetoed, expected) << "keyframes when free: " << keyframe_when_free;
  }
}

TEST_F(DynamicFrontEndTest, AKeyFrameMadeWithoutItsMasksLosesItsPointsOnPeopleWhenTheyCome) {
  // Frame 0 is on the network (held) when frame 1 comes: frame 1 has no masks at all, keeps
  // the features of the person (standing still: no motion removes them either) and becomes a
  // keyframe with a map point on every feature. Its image
  // is kept for the network, so frame 2 is dropped instead of replacing it. Once frames 0 and 1
  // are segmented, frame 2's Filter culls the keyframe's points on the person (frame 1's own
  // mask) and only those.
  const Sequence sequence = Render(3, false, nullptr, [](int) { return 0.0; });
  auto network = std::make_shared<HoldingSegmenter>(sequence.masks, 0, std::set<std::size_t>{0});
  DynamicFrontEndConfig config;
  config.segmenter = network;
  config.realtime = true;
  DynamicFrontEnd stage(config, 1000, map_, nullptr);
  const OpenAtExit<HoldingSegmenter> release_at_exit(*network);
  RunFrame(stage, sequence, 0);
  ASSERT_TRUE(network->AwaitStarted(0));
  stage.BeginFrame(0.033, sequence.bgr[1]);
  const Frame tracked =
      stage.Filter(Extract(sequence, 1), sequence.bgr[1], sequence.images[1].depth);
  ASSERT_FALSE(stage.LastReport().own_masks);
  auto keyframe = std::make_shared<KeyFrame>(map_.NextKeyFrameId(), 1, 0.033, tracked.FeaturesPtr(),
                                             SE3(), std::vector<std::shared_ptr<MapPoint>>());
  const cv::Mat& person = sequence.masks[1].instances[0].mask;
  std::vector<std::shared_ptr<MapPoint>> on_person;
  std::vector<std::shared_ptr<MapPoint>> elsewhere;
  for (std::size_t i = 0; i < tracked.Size(); ++i) {
    auto point = test::AddPointSeenBy(map_, keyframe, i, Eigen::Vector3d(0, 0, 3));
    const cv::Point2f p = tracked.Features().Keypoints()[i].pt;
    const bool on = person.at<unsigned char>(static_cast<int>(p.y), static_cast<int>(p.x)) != 0;
    (on ? on_person : elsewhere).push_back(point);
  }
  ASSERT_GE(on_person.size(), 5u);
  ASSERT_GE(elsewhere.size(), 50u);
  stage.NoteKeyFrame(keyframe);

  stage.BeginFrame(0.066, sequence.bgr[2]);
  network->Release(0);
  ASSERT_TRUE(AwaitIdleNetwork(stage));
  stage.Filter(Extract(sequence, 2), sequence.bgr[2], sequence.images[2].depth);
  for (const auto& point : on_person) EXPECT_TRUE(point->IsBad());
  for (const auto& point : elsewhere) EXPECT_FALSE(point->IsBad());
  EXPECT_EQ(map_.MapPointCount(), elsewhere.size());
  const DynamicStats stats = stage.Stats();
  EXPECT_EQ(stats.keyframes_late_masks, 1u);
  EXPECT_EQ(stats.keyframes_late_missed, 0u);
  EXPECT_EQ(stats.late_points_culled, on_person.size());
  EXPECT_EQ(stats.segmentation->dropped, 1u);  // frame 2, not the keyframe
  EXPECT_EQ(stats.segmentation->segmented, 2u);
}

TEST_F(DynamicFrontEndTest, FlowOnTheHelperThreadGivesTheSameFrames) {
  // Threaded, waiting for each frame's masks: only where the flow is computed differs.
  const auto near_x = [](int f) { return f < 3 ? 0.0 : 0.03 * (f - 2); };
  const auto far_x = [](int f) { return -0.04 * f; };
  const int frames = 6;
  const Sequence sequence = Render(frames, true, near_x, far_x);
  std::vector<std::vector<cv::Point2f>> kept_by_run[2];
  std::vector<std::vector<bool>> moving_by_run[2];
  for (const bool helper : {false, true}) {
    DynamicFrontEndConfig config;
    config.segmenter = std::make_shared<ScriptedSegmenter>(sequence.masks);
    config.options.flow_thread = helper;
    StageTimings timings;
    Map map;
    DynamicFrontEnd stage(config, 1000, map, &timings);
    for (int f = 0; f < frames; ++f) {
      const int target = stage.BeginFrame(0.033 * f, sequence.bgr[f]);
      const Frame kept =
          stage.Filter(Extract(sequence, f, target), sequence.bgr[f], sequence.images[f].depth);
      std::vector<cv::Point2f> points;
      for (const cv::KeyPoint& kp : kept.Features().Keypoints()) points.push_back(kp.pt);
      kept_by_run[helper].push_back(points);
      std::vector<bool> moving;
      for (const auto& object : stage.LastReport().objects) moving.push_back(object.moving);
      moving_by_run[helper].push_back(moving);
    }
    const auto summaries = timings.Summaries();
    EXPECT_EQ(summaries.count("flow"), helper ? 1u : 0u);
    if (helper) {
      EXPECT_EQ(summaries.at("flow").count, static_cast<std::size_t>(frames));
    }
    EXPECT_EQ(summaries.at("motion_consistency").count, static_cast<std::size_t>(frames));
  }
  for (int f = 0; f < frames; ++f) {
    EXPECT_EQ(kept_by_run[0][f], kept_by_run[1][f]) << "frame " << f;
    EXPECT_EQ(moving_by_run[0][f], moving_by_run[1][f]) << "frame " << f;
  }
  // Both people were found moving by the end: the flow really was used.
  EXPECT_EQ(moving_by_run[1][frames - 1], (std::vector<bool>{true, true}));
}

TEST_F(DynamicFrontEndTest, AFrameAbandonedAfterBeginFrameLeavesNoFlowJobBehind) {
  // The caller fails between BeginFrame and Filter (extraction threw, say): the stage is
  // destroyed with the frame's flow job offered or running, and must wait for it.
  const Sequence sequence = Render(2, false, nullptr, [](int f) { return 0.04 * f; });
  for (int round = 0; round < 20; ++round) {
    DynamicFrontEndConfig config;
    config.options.flow_thread = true;
    auto stage = std::make_unique<DynamicFrontEnd>(config, 1000, map_, nullptr);
    stage->BeginFrame(0.0, sequence.bgr[0]);
    stage->Filter(Extract(sequence, 0), sequence.bgr[0], sequence.images[0].depth);
    stage->BeginFrame(0.033, sequence.bgr[1]);
    stage.reset();
  }
  SUCCEED() << "no crash, no hang; ASan and TSan check the memory and the threads";
}

}  // namespace
}  // namespace drvslam
