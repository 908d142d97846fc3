// When tracking inserts a new keyframe: ORB-SLAM2's RGB-D criteria as a pure function, so they
// can be tested without a map.
#pragma once

namespace drvslam {

// ORB-SLAM2's RGB-D rule: tracking keeps adding keyframes to a busy local mapping until this many
// wait.
inline constexpr int kRgbdQueuedKeyFrames = 3;

struct KeyFrameEvidence {
  int frames_since_keyframe = 0;
  int max_frames = 30;  // a keyframe is due after this many frames
  int keyframes_in_map = 0;
  bool mapping_idle = true;          // local mapping can take a keyframe now
  int queued_keyframes = 0;          // keyframes waiting in local mapping's queue
  int tracked_inliers = 0;           // this frame's inlier matches
  int reference_tracked_points = 0;  // well-observed points of the reference keyframe
  int close_tracked = 0;             // close-depth features with a map point
  int close_untracked = 0;           // close-depth features without one
  // Keyframes may be added while mapping is busy until this many wait in its queue (0: only
  // when mapping is idle).
  int max_queued_keyframes = kRgbdQueuedKeyFrames;
};

// Whether the frame would make a useful keyframe (ORB-SLAM2's c1 and c2 conditions).
bool WantNewKeyFrame(const KeyFrameEvidence& e);
// Whether to insert one now: wanted, and mapping idle or with fewer than
// e.max_queued_keyframes waiting.
bool NeedNewKeyFrame(const KeyFrameEvidence& e);

}  // namespace drvslam
