// SegmentationPacer (--realtime): the network backs off before tracking does. On a machine
// with few cores the network and tracking compete for them; when tracking falls behind the
// camera, frames are skipped: lost to tracking for good, where late masks are still carried to
// the frame. A frame that follows the previous one by more than 1.5 camera periods shows that
// frames were skipped in between; the network then takes no new frame for `backoff_passes`
// times its own recent pass time, so while tracking skips frames the network idles at least
// that share of the time and leaves the core to tracking. With no skips it runs at full rate.
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
  std::size_t backoffs = 0;     // frames that showed a skip and started or extended a back-off
  std::size_t frames_held = 0;  // frames not handed to the network during a back-off
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
  double hold_until_ = 0.0;
  bool holding_ = false;
  SegmentationPacerStats stats_;
};

}  // namespace drvslam
