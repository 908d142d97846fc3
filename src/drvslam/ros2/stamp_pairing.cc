#include "drvslam/ros2/stamp_pairing.h"

#include <cstdlib>
#include <utility>

namespace drvslam::ros2 {
namespace {

void PushBounded(std::deque<StampedImage>* images, StampedImage image, std::size_t capacity,
                 std::size_t* dropped) {
  images->push_back(std::move(image));
  while (images->size() > capacity) {
    images->pop_front();
    ++*dropped;
  }
}

}  // namespace

StampPairer::StampPairer(std::int64_t tolerance_ns, std::size_t capacity)
    : tolerance_ns_(tolerance_ns), capacity_(capacity < 1 ? 1 : capacity) {}

void StampPairer::AddColour(std::int64_t stamp_ns, cv::Mat bgr) {
  PushBounded(&colour_, {stamp_ns, std::move(bgr)}, capacity_, &dropped_);
}

void StampPairer::AddDepth(std::int64_t stamp_ns, cv::Mat depth) {
  PushBounded(&depth_, {stamp_ns, std::move(depth)}, capacity_, &dropped_);
}

std::optional<RgbdPair> StampPairer::TakeNewest() {
  // Newest colour first; for each, the depth image nearest in time.
  for (std::size_t c = colour_.size(); c-- > 0;) {
    const std::int64_t stamp = colour_[c].stamp_ns;
    std::size_t best = depth_.size();
    std::int64_t best_gap = 0;
    for (std::size_t d = 0; d < depth_.size(); ++d) {
      const std::int64_t gap = std::llabs(depth_[d].stamp_ns - stamp);
      if (gap <= tolerance_ns_ && (best == depth_.size() || gap < best_gap)) {
        best = d;
        best_gap = gap;
      }
    }
    if (best == depth_.size()) continue;
    RgbdPair pair{stamp, std::move(colour_[c].image), std::move(depth_[best].image)};
    skipped_ += c;  // the older colour images this pair passes over
    colour_.erase(colour_.begin(), colour_.begin() + static_cast<std::ptrdiff_t>(c) + 1);
    depth_.erase(depth_.begin(), depth_.begin() + static_cast<std::ptrdiff_t>(best) + 1);
    return pair;
  }
  return std::nullopt;
}

}  // namespace drvslam::ros2
