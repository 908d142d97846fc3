// VerifyLoop: geometric verification of loop candidates (ORB-SLAM2's ComputeSim3 with a rigid
// transform: depth fixes the scale). Per candidate, best first: bag-of-words matches between
// the new keyframe's keypoints and the candidate's map points; the new keyframe's depth points
// against those map points give, by RANSAC, the new keyframe's pose on the loop side; the
// candidate's neighbourhood points are then searched near their projections with that pose
// (guided matching) and the pose is refined by robust pose-only optimization on every match.
// The first candidate that keeps enough matches closes the loop.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "drvslam/loop/loop_match.h"
#include "drvslam/map/keyframe.h"

namespace drvslam {

struct LoopVerifierRules {
  int min_bow_matches = 20;
  int ransac_iterations = 300;
  int min_inliers = 20;
  double ransac_tolerance = 0.03;  // metres at 1 m depth, scaled by the squared depth
  int min_total_matches = 40;
  double guided_radius_factor = 10.0;  // pixels at level 0
  int guided_max_distance = 50;        // Hamming
};

struct LoopVerification {
  int candidates_tried = 0;
  int best_bow_matches = 0;
  int best_ransac_inliers = 0;
  int best_total_matches = 0;
};

// Candidates must hold their bags of words. Read-only on the map.
std::optional<LoopMatch> VerifyLoop(const std::shared_ptr<KeyFrame>& current,
                                    const std::vector<std::shared_ptr<KeyFrame>>& candidates,
                                    const LoopVerifierRules& rules,
                                    LoopVerification* report = nullptr);

// Searches the points (not bad, not in `matches`) near their projections into `keyframe` at
// pose T_cw, on the predicted pyramid level +-1, writing the nearest keypoint within
// max_distance into the free slots of *matches (one per keypoint). Returns the number added.
int SearchByProjectionAtPose(const KeyFrame& keyframe, const SE3& T_cw,
                             const std::vector<std::shared_ptr<MapPoint>>& points,
                             double radius_factor, int max_distance,
                             std::vector<std::shared_ptr<MapPoint>>* matches);

}  // namespace drvslam
