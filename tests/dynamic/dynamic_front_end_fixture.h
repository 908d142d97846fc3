// The dynamic stage's test fixture: a rendered scene (a wall, a table, a far person and an
// optional near one, moved per frame by the caller) with ground-truth person masks, and the
// helpers both dynamic_front_end test files use to run frames through the stage.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <thread>
#include <vector>

#include "drvslam/dynamic/dynamic_front_end.h"
#include "drvslam/feature/orb_extractor.h"
#include "drvslam/map/keyframe.h"
#include "plane_scene.h"
#include "scripted_segmenters.h"

namespace drvslam {
namespace test {

struct Sequence {
  std::vector<test::Rendered> images;
  std::vector<cv::Mat> bgr;
  std::vector<Segmentation> masks;
};

// `near_x(f)`: x offset of a person at 1.2 m (large in the image) per frame, `far_x(f)`: of a
// person at 3 m. Either may be absent (no plane).
inline Sequence Render(int frames, bool with_near, const std::function<double(int)>& near_x,
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

  Frame Extract(const Sequence& sequence, int f, int target = 0,
                const cv::Mat& skip_mask = cv::Mat()) {
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    extractor_.Extract(sequence.images[f].gray, skip_mask, target, &keypoints, &descriptors);
    return Frame(f, 0.033 * f,
                 std::make_shared<const FrameFeatures>(geometry_, std::move(keypoints), descriptors,
                                                       sequence.images[f].depth));
  }

  // Realtime mode over a scripted network that takes network_ms a frame; a likely keyframe
  // waits up to keyframe_wait_ms for its own masks.
  static DynamicFrontEndConfig RealtimeConfig(const Sequence& sequence, int network_ms,
                                              double keyframe_wait_ms) {
    DynamicFrontEndConfig config;
    config.segmenter = std::make_shared<ScriptedSegmenter>(sequence.masks, network_ms);
    config.realtime = true;
    config.segmentation.keyframe_wait_ms = keyframe_wait_ms;
    return config;
  }

  // Frame f (at 30 fps) through the stage: BeginFrame, then Filter on its features.
  void RunFrame(DynamicFrontEnd& stage, const Sequence& sequence, int f,
                bool keyframe_likely = false) {
    stage.BeginFrame(0.033 * f, sequence.bgr[f], keyframe_likely);
    stage.Filter(Extract(sequence, f), sequence.bgr[f], sequence.images[f].depth);
  }

  // Waits until the network has dealt with every frame handed to it (segmented, failed or
  // dropped), so that the next frame finds it idle: an order, where a sleep of a few passes'
  // length only made it likely. False only after 30 s, a hang guard.
  static bool AwaitIdleNetwork(const DynamicFrontEnd& stage) {
    for (int wait = 0; wait < 6000; ++wait) {
      const AsyncSegmenterStats s = stage.Stats().segmentation.value();
      if (s.segmented + s.failed + s.dropped == s.submitted) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
  }

  // Begins frame f of a run whose network stalls after frame 0 (GatedSegmenter): frame 0 waits
  // until its masks are back (a generous hang bound: they come at once), for later frames to
  // carry.
  static void BeginGatedFrame(DynamicFrontEnd& stage, const Sequence& sequence, int f) {
    stage.BeginFrame(0.033 * f, sequence.bgr[f]);
    if (f != 0) return;
    for (int wait = 0; wait < 2000 && stage.Stats().segmentation->segmented < 1; ++wait) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }

  // The keyframe tracking made of frame f when `made`, else null (for NoteKeyFrame). It has no
  // features: late masks cull nothing of it.
  std::shared_ptr<KeyFrame> KeyFrameIf(bool made, int f) {
    if (!made) return nullptr;
    auto features = std::make_shared<const FrameFeatures>(geometry_, std::vector<cv::KeyPoint>(),
                                                          cv::Mat(), cv::Mat());
    return std::make_shared<KeyFrame>(map_.NextKeyFrameId(), f, 0.033 * f, features, SE3(),
                                      std::vector<std::shared_ptr<MapPoint>>());
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

}  // namespace test
}  // namespace drvslam
