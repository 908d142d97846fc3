// ORB matching for tracking: by projection of the last frame's or the local map's points into
// the current frame (windowed search, descriptor distance, ratio and orientation checks), and
// by brute-force descriptor matching against a keyframe (the fallback without a vocabulary:
// match/bow_matcher.h is faster with one); for local mapping, the epipolar search for
// triangulation and the fusion of duplicate points.
// Tracking matches are written into Frame::map_points; functions return how many were added.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "drvslam/map/frame.h"
#include "drvslam/map/keyframe.h"
#include "drvslam/map/map_point.h"

namespace drvslam {

struct MatcherOptions {
  int high_threshold = 100;  // largest Hamming distance accepted for a projection match
  int low_threshold = 50;    // for brute-force matching, where no geometry limits the search
  double nn_ratio = 0.8;     // best / second best (on the same pyramid level) in local-map search
  bool check_orientation = true;
};

class OrbMatcher {
 public:
  explicit OrbMatcher(const MatcherOptions& options = {}) : options_(options) {}

  // Projects the last frame's matched points with the current frame's (predicted) pose and
  // searches windows of radius_factor * scale(level) pixels.
  int SearchByProjection(Frame& current, const Frame& last, double radius_factor) const;

  // Matches local map points not yet in `current`. `projections[i]` is the visibility result for
  // points[i] (ProjectIfVisible); absent entries are skipped.
  int SearchByProjection(Frame& current, const std::vector<std::shared_ptr<MapPoint>>& points,
                         const std::vector<std::optional<Frame::Projection>>& projections,
                         double radius_factor) const;

  // Matches the keyframe's map points to the frame's keypoints by descriptor alone (nearest
  // neighbour with ratio test), then the orientation check.
  int SearchByDescriptors(const KeyFrame& keyframe, Frame& current, double ratio) const;

  // Local mapping (orb_matcher_mapping.cc).
  // Candidate pairs (keypoint in kf1, keypoint in kf2) for triangulating new points: both
  // keypoints hold no map point, the kf2 keypoint lies within sqrt(3.84) sigma of the epipolar
  // line of the kf1 keypoint (fundamental matrix from the two poses) and, unless the kf1 keypoint
  // has depth, away from the epipole; descriptors within low_threshold and, against the second
  // best on the same pyramid level, within nn_ratio. Each kf2 keypoint goes to its best match.
  // Pairs come in kf1 keypoint order.
  std::vector<std::pair<std::size_t, std::size_t>> SearchForTriangulation(
      const KeyFrame& kf1, const KeyFrame& kf2) const;

  // Projects each point into the keyframe (frustum, distance range and viewing-angle checks)
  // and searches a window of radius_factor * scale(predicted level) pixels for a keypoint within
  // the chi2 gate (5.991 monocular, 7.8 with depth) and low_threshold in descriptor distance.
  // When that keypoint already holds a map point, the one with fewer observations is replaced by
  // the other (appended to *replaced, which may be null); otherwise the point gains the keypoint
  // as a new observation. Returns the number of points fused or added.
  int Fuse(const std::shared_ptr<KeyFrame>& keyframe,
           const std::vector<std::shared_ptr<MapPoint>>& points, double radius_factor,
           std::vector<std::shared_ptr<MapPoint>>* replaced) const;

 private:
  MatcherOptions options_;
};

}  // namespace drvslam
