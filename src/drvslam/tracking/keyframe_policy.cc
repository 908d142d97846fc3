#include "drvslam/tracking/keyframe_policy.h"

namespace drvslam {

bool WantNewKeyFrame(const KeyFrameEvidence& e) {
  // Many close points could be added while few are tracked: the map is thin here.
  const bool need_close = e.close_tracked < 100 && e.close_untracked > 70;
  const double reference_ratio = e.keyframes_in_map < 2 ? 0.4 : 0.75;
  const bool timed_out = e.frames_since_keyframe >= e.max_frames;
  const bool idle = e.mapping_idle;
  const bool weak = e.tracked_inliers < e.reference_tracked_points * 0.25 || need_close;
  const bool fewer_than_reference =
      (e.tracked_inliers < e.reference_tracked_points * reference_ratio || need_close) &&
      e.tracked_inliers > 15;
  return (timed_out || idle || weak) && fewer_than_reference;
}

bool NeedNewKeyFrame(const KeyFrameEvidence& e) {
  return WantNewKeyFrame(e) && (e.mapping_idle || e.queued_keyframes < e.max_queued_keyframes);
}

}  // namespace drvslam
