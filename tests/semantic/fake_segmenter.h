// A Segmenter for threading tests: each frame yields one instance whose class id is the frame
// index and whose mask is a fixed square; it can sleep, fail on chosen frames, or hold every
// call at a gate until the test opens it.
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam::testing {

class FakeSegmenter : public Segmenter {
 public:
  explicit FakeSegmenter(int sleep_ms = 0, std::set<std::size_t> failing = {})
      : sleep_ms_(sleep_ms), failing_(std::move(failing)) {}

  Segmentation Segment(const cv::Mat& bgr, double timestamp, std::size_t frame_index) override {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      started_.push_back(frame_index);
      threads_.insert(std::this_thread::get_id());
      changed_.notify_all();
      changed_.wait(lock, [&] { return open_; });
    }
    if (sleep_ms_ > 0) std::this_thread::sleep_for(std::chrono::milliseconds(sleep_ms_));
    if (failing_.count(frame_index)) throw Error("fake: frame " + std::to_string(frame_index));
    Segmentation seg;
    seg.timestamp = timestamp;
    seg.frame_index = frame_index;
    seg.image_size = bgr.size();
    Instance instance;
    instance.class_id = static_cast<int>(frame_index);
    instance.box = cv::Rect(bgr.cols / 4, bgr.rows / 4, bgr.cols / 2, bgr.rows / 2);
    instance.mask = cv::Mat::zeros(bgr.size(), CV_8UC1);
    instance.mask(instance.box).setTo(255);
    seg.instances.push_back(instance);
    return seg;
  }
  std::string Name() const override { return "fake"; }
  const std::vector<std::string>& ClassNames() const override { return names_; }

  // Calls block until Open().
  void Close() {
    std::lock_guard<std::mutex> lock(mutex_);
    open_ = false;
  }
  void Open() {
    std::lock_guard<std::mutex> lock(mutex_);
    open_ = true;
    changed_.notify_all();
  }
  // Blocks until `count` calls have started.
  void AwaitStarted(std::size_t count) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return started_.size() >= count; });
  }
  std::vector<std::size_t> Started() {
    std::lock_guard<std::mutex> lock(mutex_);
    return started_;
  }
  std::set<std::thread::id> Threads() {
    std::lock_guard<std::mutex> lock(mutex_);
    return threads_;
  }

 private:
  int sleep_ms_;
  std::set<std::size_t> failing_;
  std::vector<std::string> names_ = {"thing"};
  std::mutex mutex_;
  std::condition_variable changed_;
  bool open_ = true;
  std::vector<std::size_t> started_;
  std::set<std::thread::id> threads_;
};

}  // namespace drvslam::testing
