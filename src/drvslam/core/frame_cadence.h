// FrameCadence: tells from a live camera's frame timestamps when frames were skipped. A frame
// that follows the previous one by more than 1.5 camera periods shows that frames were skipped
// in between (replaced in the one-frame slot while tracking was busy, or never loaded).
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

class FrameCadence {
 public:
  // Records the frame at `timestamp` (seconds, increasing) and says whether its gap to the frame
  // before shows skipped frames, judged against the period of the gaps before it. False until a
  // few gaps are known, and for a timestamp that does not increase.
  bool ShowsSkip(double timestamp);

  // The camera's period in seconds, from the gaps recorded so far (nullopt until a few are).
  std::optional<double> Period() const;

  static constexpr std::size_t kGapWindow = 32;   // recent gaps the period is judged from
  static constexpr std::size_t kMinGaps = 4;      // gaps needed before any skip is judged
  static constexpr double kSkipGapPeriods = 1.5;  // a gap this many periods long skipped a frame

 private:
  std::optional<double> last_timestamp_;
  std::deque<double> recent_gaps_;
};

}  // namespace drvslam
