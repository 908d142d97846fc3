// Timing records of the segmentation thread, in the form `drvslam run` writes to stats.json:
// how long segmentation takes per frame, and, when tracking runs at sensor rate (--realtime),
// how old the masks it used were (frames and milliseconds between the masks' frame and the
// current frame) and how often they had to be carried forward by optical flow.
#pragma once

#include <cstddef>
#include <vector>

#include "drvslam/core/bounded_sample.h"

namespace drvslam {

// Median, 95th percentile and maximum of a sample (all 0 when it is empty).
struct Spread {
  double median = 0.0;
  double p95 = 0.0;
  double max = 0.0;
  double mean = 0.0;
};
Spread SpreadOf(std::vector<double> values);
// The same for a BoundedSample: SpreadOf(values) while it is exact; past that the median and p95
// are its nearest-rank quantiles (within 0.5 %, no interpolation), mean and max exact.
Spread SpreadOf(const BoundedSample& sample);

struct SegmentationLatencyStats {
  std::size_t frames = 0;         // frames that asked for masks
  std::size_t fresh = 0;          // got the masks of their own image
  std::size_t propagated = 0;     // got an older frame's masks, carried by optical flow
  std::size_t without_masks = 0;  // no segmentation had finished yet
  Spread lag_frames;              // over frames with masks (fresh ones count 0)
  Spread lag_ms;                  // timestamp difference, milliseconds
  Spread propagation_ms;          // wall time of the flow and warps, over propagated frames
};

// Accumulates SegmentationLatencyStats; not thread-safe (the tracking thread owns it).
class LatencyRecorder {
 public:
  void AddFresh();
  void AddPropagated(std::size_t lag_frames, double lag_ms, double propagation_ms);
  void AddWithoutMasks();
  SegmentationLatencyStats Summary() const;

 private:
  SegmentationLatencyStats counts_;
  // Bounded memory over hours of frames (BoundedSample).
  BoundedSample lag_frames_;
  BoundedSample lag_ms_;
  BoundedSample propagation_ms_;
};

}  // namespace drvslam
