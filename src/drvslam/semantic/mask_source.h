// MaskSource: what the tracking thread asks for the masks of the frame it is tracking. Normally
// it waits for that frame's segmentation. At sensor rate (--realtime) it never waits: it takes
// the frame's own masks if they are ready, else the newest finished ones carried to the current
// image by optical flow, and records how old they were (SegmentationLatencyStats). With
// object-level carrying (Segmentation.propagation = objects) the caller carries the masks with
// its own flow tracks: NewestFor hands out the newest masks as they are, and the caller
// records what it did (RecordFresh / RecordCarried / RecordWithoutMasks).
#pragma once

#include <cstddef>
#include <opencv2/core.hpp>

#include "drvslam/semantic/async_segmenter.h"
#include "drvslam/semantic/latency_stats.h"
#include "drvslam/semantic/mask_propagator.h"

namespace drvslam {

class MaskSource {
 public:
  // `segmenter` must outlive this object.
  MaskSource(AsyncSegmenter& segmenter, const MaskPropagator& propagator, bool realtime);

  // The masks for frame `frame_index` (image `bgr`, already submitted to the segmenter when not
  // realtime). Blocking mode rethrows the segmenter's errors. Realtime mode returns an empty
  // segmentation of the image's size when nothing has finished yet. Call from one thread.
  Segmentation MasksFor(std::size_t frame_index, double timestamp, const cv::Mat& bgr);

  struct Newest {
    std::shared_ptr<const SegmentedFrame> masks;  // null: none usable yet
    bool own = false;                             // masks of frame `frame_index` itself
  };
  // Never blocks: frame `frame_index`'s own masks when finished, else the newest finished ones
  // (null when none has finished, or they are of a later frame or another image size).
  Newest NewestFor(std::size_t frame_index, const cv::Size& size) const;
  void RecordFresh() { recorder_.AddFresh(); }
  void RecordCarried(std::size_t lag_frames, double lag_ms, double carry_ms) {
    recorder_.AddPropagated(lag_frames, lag_ms, carry_ms);
  }
  void RecordWithoutMasks() { recorder_.AddWithoutMasks(); }

  SegmentationLatencyStats Latency() const { return recorder_.Summary(); }
  bool Realtime() const { return realtime_; }

 private:
  AsyncSegmenter& segmenter_;
  MaskPropagator propagator_;
  bool realtime_;
  LatencyRecorder recorder_;
};

}  // namespace drvslam
