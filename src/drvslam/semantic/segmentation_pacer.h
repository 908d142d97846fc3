// SegmentationPacer (--realtime): the network backs off before tracking does. On a machine
// with few cores the network and tracking compete for them; when tracking falls behind the
// camera, frames are skipped: lost to tracking for good, where late masks are still carried to
// the frame. A frame that follows the previous one by more than 1.5 camera periods shows that
// frames were skipped in between; the network then rests: it takes no new frame for
// `backoff_passes` times its own recent pass time, leaving the core to tracking. After a rest it
// runs freely for at least one pass before it can rest again, so however long tracking keeps
// skipping, the network still gets frames part of the time and masks keep coming. With no skips
// it runs at full rate.
//
// The period is the lower quartile of the recent gaps between frames: right while fewer than
// about 40 % of the frames are skipped (a quarter of the gaps are then still single periods) and
// for timestamps that jitter by up to about 15 % of a period. Camera.fps is not relied on: it
// is optional in the settings and may be wrong.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>

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
  // The camera's period: the lower quartile of the recent gaps between frames.
  std::optional<double> CameraPeriod() const;

  double backoff_passes_;
  std::optional<double> last_timestamp_;
  std::deque<double> recent_gaps_;
  // The current rest ends at rest_until_; the next may start at no_rest_before_ (one free pass
  // after it). Both in the frames' clock.
  std::optional<double> rest_until_;
  double no_rest_before_ = 0.0;
  SegmentationPacerStats stats_;
};

}  // namespace drvslam
