// MotionPersistence: a region of unlabelled motion is believed once the same thing has been
// seen moving in several consecutive frames. Flow noise, a blurred frame or a rolling-shutter
// wobble rarely puts moving points on the same surface frame after frame; a moving thing does.
// Regions are matched through the flow tracks that formed them: a region continues last
// frame's region when at least a quarter of its points' previous positions lie in it (the
// regions are painted into a per-pixel count of consecutive frames).
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/dynamic/motion_consistency.h"
#include "drvslam/dynamic/unlabelled_motion.h"

namespace drvslam {

class MotionPersistence {
 public:
  // regions: this frame's (FindUnlabelledMotion over `tracks`); image: the frame's size.
  // Returns, per region, the number of consecutive frames up to this one it has been seen
  // moving (1 = new), and remembers the regions for the next frame. Throws drvslam::Error when
  // a region names a track that does not exist.
  std::vector<int> Update(const std::vector<MovingRegion>& regions,
                          const std::vector<FlowTrack>& tracks, const cv::Size& image);
  // Regions carried through a frame (region_carrier.h) join what the frame remembers (its own
  // regions after Update, nothing after Forget) with `streak` frames, the count that confirms
  // a region: the next believed frame's regions that overlap them are confirmed at once rather
  // than starting over.
  void Add(const std::vector<MovingRegion>& carried, const cv::Size& image, int streak);
  // A frame whose motion evidence is not believed breaks every chain (what it carries is then
  // Added).
  void Forget();

 private:
  // The regions painted with their streaks into a new previous-frame image, or, with
  // `keep_previous`, into the current one (where a pixel has two streaks, the longer counts).
  void Remember(const std::vector<MovingRegion>& regions, const std::vector<int>& streaks,
                const cv::Size& image, bool keep_previous = false);

  cv::Mat streaks_;  // CV_8UC1 of the previous frame: consecutive frames seen moving, 0 = none
};

}  // namespace drvslam
