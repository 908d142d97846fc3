// Segmenters for the dynamic stage's tests: prepared segmentations by frame index, returned
// after an optional network latency, optionally held at a gate until the test lets them go.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <set>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "drvslam/core/coco_classes.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam::test {

// Returns prepared segmentations by frame index.
class ScriptedSegmenter : public Segmenter {
 public:
  // sleep_ms: the network's latency per frame.
  explicit ScriptedSegmenter(std::vector<Segmentation> frames, int sleep_ms = 0)
      : frames_(std::move(frames)), sleep_ms_(sleep_ms) {
    for (std::string_view name : CocoClassNames()) names_.emplace_back(name);
  }
  Segmentation Segment(const cv::Mat&, double timestamp, std::size_t index) override {
    if (sleep_ms_ > 0) std::this_thread::sleep_for(std::chrono::milliseconds(sleep_ms_));
    Segmentation s = frames_.at(index);
    s.timestamp = timestamp;
    s.frame_index = index;
    return s;
  }
  std::string Name() const override { return "scripted"; }
  const std::vector<std::string>& ClassNames() const override { return names_; }

 private:
  std::vector<Segmentation> frames_;
  int sleep_ms_;
  std::vector<std::string> names_;
};

// ScriptedSegmenter whose calls after the first block until Open(): segmentation that lags.
class GatedSegmenter : public ScriptedSegmenter {
 public:
  using ScriptedSegmenter::ScriptedSegmenter;
  Segmentation Segment(const cv::Mat& bgr, double timestamp, std::size_t index) override {
    if (index > 0) {
      std::unique_lock<std::mutex> lock(mutex_);
      opened_.wait(lock, [&] { return open_; });
    }
    return ScriptedSegmenter::Segment(bgr, timestamp, index);
  }
  void Open() {
    std::lock_guard<std::mutex> lock(mutex_);
    open_ = true;
    opened_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable opened_;
  bool open_ = false;
};

// ScriptedSegmenter that holds the chosen frames at a gate until Release(frame): the test decides
// when their passes may end, so that a pass is still running when a frame asks, by order.
class HoldingSegmenter : public ScriptedSegmenter {
 public:
  HoldingSegmenter(std::vector<Segmentation> frames, int sleep_ms, std::set<std::size_t> held)
      : ScriptedSegmenter(std::move(frames), sleep_ms), held_(std::move(held)) {}
  Segmentation Segment(const cv::Mat& bgr, double timestamp, std::size_t index) override {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      entered_.insert(index);
      released_.notify_all();
      released_.wait(lock, [&] { return held_.count(index) == 0; });
    }
    return ScriptedSegmenter::Segment(bgr, timestamp, index);
  }
  void Release(std::size_t index) {
    std::lock_guard<std::mutex> lock(mutex_);
    held_.erase(index);
    released_.notify_all();
  }
  void ReleaseAll() {
    std::lock_guard<std::mutex> lock(mutex_);
    held_.clear();
    released_.notify_all();
  }
  // Whether the network has started on frame `index` (a generous bound against hangs): a frame
  // it has taken can no longer be replaced in its one-frame queue by the next one.
  bool AwaitStarted(std::size_t index) {
    std::unique_lock<std::mutex> lock(mutex_);
    return released_.wait_for(lock, std::chrono::seconds(10),
                              [&] { return entered_.count(index) != 0; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable released_;
  std::set<std::size_t> held_;
  std::set<std::size_t> entered_;
};

// Lets every frame of a held or gated network go when a test ends, however it ends (an
// assertion that returns early included), before the stage that waits for its passes is
// destroyed: declare it after the stage.
template <typename Network>
class OpenAtExit {
 public:
  explicit OpenAtExit(Network& network) : network_(network) {}
  ~OpenAtExit() { Open(network_); }
  OpenAtExit(const OpenAtExit&) = delete;
  OpenAtExit& operator=(const OpenAtExit&) = delete;

 private:
  static void Open(GatedSegmenter& network) { network.Open(); }
  static void Open(HoldingSegmenter& network) { network.ReleaseAll(); }
  Network& network_;
};

}  // namespace drvslam::test
