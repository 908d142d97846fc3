// ORB matching for tracking: by projection of the last frame's or the local map's points into
// the current frame (windowed search, descriptor distance, ratio and orientation checks), and
// by brute-force descriptor matching against a keyframe (until a vocabulary exists).
// Matches are written into Frame::map_points; functions return how many were added.
#pragma once

#include <memory>
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

 private:
  MatcherOptions options_;
};

}  // namespace drvslam
