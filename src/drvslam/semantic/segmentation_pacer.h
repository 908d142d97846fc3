// SegmentationPacer (--realtime): the network backs off before tracking does. On a machine
// with few cores the network and tracking compete for them; when tracking falls behind the
// camera, frames are skipped: lost to tracking for good, where late masks are still carried to
// the frame. When a frame's timestamp shows that frames were skipped before it (FrameCadence),
// the network rests: it takes no new frame for `backoff_passes` times its own recent pass time,
// leaving the core to tracking. After a rest it runs freely for at least one pass before it can
// rest again, so however long tracking keeps skipping, the network still gets frames part of
// the time and masks keep coming. With no skips it runs at full rate.
#pragma once

#include <cstddef>
#include <optional>

#include "drvslam/core/frame_cadence.h"

namespace drvslam {

struct SegmentationPacerStats {
  std::size_t backoffs = 0;     // rests started (each by a frame that showed a skip)
  std::size_t frames_held = 0;  // frames not handed to the network during a rest
};

class SegmentationPacer {
 public:
  // backoff_passes > 0 (throws Error otherwise).
  explicit SegmentationPacer(double backoff_passes);

  // Whether the frame at `timestamp` (seconds, increasing) goes to the network. pass_ms: the
  // network's recent forward-pass time; before the first pass (nullopt) nothing is held.
  bool ShouldSubmit(double timestamp, std::optional<double> pass_ms);

  const SegmentationPacerStats& Stats() const { return stats_; }

 private:
  double backoff_passes_;
  FrameCadence cadence_;
  // The current rest ends at rest_until_; the next may start at no_rest_before_ (one free pass
  // after it). Both in the frames' clock.
  std::optional<double> rest_until_;
  double no_rest_before_ = 0.0;
  SegmentationPacerStats stats_;
};

}  // namespace drvslam
