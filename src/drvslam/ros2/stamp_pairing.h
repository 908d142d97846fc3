// StampPairer: pairs colour and depth images that arrive on separate topics by their header
// stamps, as a live camera's drivers publish them (aligned depth carries the colour frame's
// stamp, or one within a fraction of a frame). Like a camera's one-frame hand-off, it gives the
// newest pair and drops the older colour frames it passed over, counting them as skipped.
// Not thread-safe: the node's one loop adds and takes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <opencv2/core.hpp>
#include <optional>

namespace drvslam::ros2 {

struct StampedImage {
  std::int64_t stamp_ns = 0;
  cv::Mat image;
};

struct RgbdPair {
  std::int64_t stamp_ns = 0;  // the colour image's stamp
  cv::Mat bgr;
  cv::Mat depth;
};

class StampPairer {
 public:
  // Images further apart than `tolerance_ns` never pair. Each side keeps at most `capacity`
  // waiting images (the oldest goes first, counted as dropped).
  explicit StampPairer(std::int64_t tolerance_ns, std::size_t capacity = 8);

  void AddColour(std::int64_t stamp_ns, cv::Mat bgr);
  void AddDepth(std::int64_t stamp_ns, cv::Mat depth);

  // The newest colour image that has a depth image within the tolerance (the nearest one), with
  // it; every image up to that stamp leaves the buffers. Colour images passed over count in
  // Skipped(). nullopt when no colour image has its depth yet.
  std::optional<RgbdPair> TakeNewest();

  // Colour images left unpaired because a newer pair was taken.
  std::size_t Skipped() const { return skipped_; }
  // Images pushed out of a full buffer without ever pairing (their partner never came).
  std::size_t Dropped() const { return dropped_; }

 private:
  std::int64_t tolerance_ns_;
  std::size_t capacity_;
  std::deque<StampedImage> colour_;  // in arrival order
  std::deque<StampedImage> depth_;
  std::size_t skipped_ = 0;
  std::size_t dropped_ = 0;
};

}  // namespace drvslam::ros2
