// Bag-of-words matching (ORB-SLAM2's SearchByBoW): descriptors are compared only between
// features that fell under the same vocabulary node (the FeatureVector direct index), which
// makes matching a keyframe against a frame with no pose prior fast enough for relocalization
// and loop verification. Nearest neighbour within a distance threshold and ratio test, then the
// orientation check. Both sides must hold their bag of words (Frame::has_bow,
// KeyFrame::HasBow()); without one nothing matches.
#pragma once

#include <memory>
#include <vector>

#include "drvslam/map/frame.h"
#include "drvslam/map/keyframe.h"
#include "drvslam/map/map_point.h"

namespace drvslam {

struct BowMatchOptions {
  int max_distance = 50;  // ORB-SLAM2's TH_LOW
  double nn_ratio = 0.75;
  bool check_orientation = true;
};

// The keyframe's map points (not bad) matched to the frame's keypoints by the keyframe
// keypoint's descriptor. *matches is resized to frame.Size(); slot j receives the point matched
// to frame keypoint j (nullptr elsewhere). Returns the number of matches.
int SearchByBow(const KeyFrame& keyframe, const Frame& frame, const BowMatchOptions& options,
                std::vector<std::shared_ptr<MapPoint>>* matches);

// Map points of kf1 matched to map points of kf2 (both not bad), for loop verification.
// *matches12 is resized to kf1's keypoint count; slot i receives the kf2 map point matched to
// kf1 keypoint i. Each kf2 keypoint is matched at most once. Returns the number of matches.
int SearchByBow(const KeyFrame& kf1, const KeyFrame& kf2, const BowMatchOptions& options,
                std::vector<std::shared_ptr<MapPoint>>* matches12);

}  // namespace drvslam
