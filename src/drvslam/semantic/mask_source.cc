#include "drvslam/semantic/mask_source.h"

#include <chrono>

namespace drvslam {

MaskSource::MaskSource(AsyncSegmenter& segmenter, const MaskPropagator& propagator, bool realtime)
    : segmenter_(segmenter), propagator_(propagator), realtime_(realtime) {}

Segmentation MaskSource::MasksFor(std::size_t frame_index, double timestamp, const cv::Mat& bgr) {
  if (!realtime_) {
    Segmentation own = segmenter_.Wait(frame_index)->segmentation;
    recorder_.AddFresh();
    return own;
  }
  if (auto own = segmenter_.TryGet(frame_index)) {
    recorder_.AddFresh();
    return own->segmentation;
  }
  const std::shared_ptr<const SegmentedFrame> latest = segmenter_.Latest();
  if (!latest || latest->segmentation.frame_index > frame_index ||
      latest->image.size() != bgr.size()) {
    recorder_.AddWithoutMasks();
    Segmentation empty;
    empty.timestamp = timestamp;
    empty.frame_index = frame_index;
    empty.image_size = bgr.size();
    return empty;
  }
  const auto start = std::chrono::steady_clock::now();
  Segmentation carried =
      propagator_.Propagate(latest->segmentation, latest->image, bgr, timestamp, frame_index);
  const double propagation_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  recorder_.AddPropagated(frame_index - latest->segmentation.frame_index,
                          (timestamp - latest->segmentation.timestamp) * 1000.0, propagation_ms);
  return carried;
}

MaskSource::Newest MaskSource::NewestFor(std::size_t frame_index, const cv::Size& size) const {
  Newest newest;
  if (auto own = segmenter_.TryGet(frame_index)) {
    newest.masks = std::move(own);
    newest.own = true;
    return newest;
  }
  std::shared_ptr<const SegmentedFrame> latest = segmenter_.Latest();
  if (latest && latest->segmentation.frame_index < frame_index && latest->image.size() == size) {
    newest.masks = std::move(latest);
  }
  return newest;
}

}  // namespace drvslam
