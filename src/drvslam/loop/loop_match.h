// LoopMatch: a verified loop, as the verifier hands it to the corrector: the keyframe that
// closed it, the old keyframe it returned to, where the new keyframe really is (in the old
// keyframe's frame of reference) and which old map points its keypoints see.
#pragma once

#include <memory>
#include <vector>

#include "drvslam/core/se3.h"
#include "drvslam/map/keyframe.h"
#include "drvslam/map/map_point.h"

namespace drvslam {

struct LoopMatch {
  std::shared_ptr<KeyFrame> current;
  std::shared_ptr<KeyFrame> loop;
  SE3 corrected_T_cw;  // the current keyframe's pose consistent with the loop side
  // One slot per keypoint of `current`: the loop-side map point it sees, or null.
  std::vector<std::shared_ptr<MapPoint>> matched_points;
  int matches = 0;          // non-null slots
  int ransac_inliers = 0;   // of the bag-of-words matches
  double correction_m = 0;  // how far the current keyframe moves (drift removed), metres
  double correction_deg = 0;
};

}  // namespace drvslam
