// New map points from a new keyframe and its best covisible keyframes: features that hold no
// point yet are matched along epipolar lines (OrbMatcher::SearchForTriangulation), triangulated
// (linear two-view method, or a depth measurement when the rays are nearly parallel), and kept
// when they lie in front of both cameras, reproject within the chi2 gates and have distances
// consistent with their pyramid levels.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "drvslam/core/se3.h"
#include "drvslam/map/map.h"
#include "drvslam/match/orb_matcher.h"

namespace drvslam {

// The world point seen along normalized image rays (x, y, 1) from two cameras T1w, T2w, by the
// linear (DLT) method; nullopt when the solution lies at infinity. No cheirality check.
std::optional<Eigen::Vector3d> TriangulateTwoViews(const SE3& T1w, const Eigen::Vector3d& ray1,
                                                   const SE3& T2w, const Eigen::Vector3d& ray2);

struct TriangulationRules {
  int neighbours = 10;         // best covisible keyframes searched
  double chi2_mono = 5.991;    // reprojection gate, 2 DoF, 95%
  double chi2_stereo = 7.815;  // with the virtual right coordinate, 3 DoF, 95%
  // Rays closer than this cosine count as parallel: without depth no point is made.
  double max_parallax_cos = 0.9998;
};

// Creates, links and adds to the map the new points (observed by `keyframe` and one neighbour)
// and returns them. Neighbours closer than the camera baseline are skipped, as ORB-SLAM2 does
// for RGB-D. `stop` (may be empty) is asked before every neighbour but the first; when it
// returns true the search ends early.
std::vector<std::shared_ptr<MapPoint>> CreateNewMapPoints(const std::shared_ptr<KeyFrame>& keyframe,
                                                          Map& map, const OrbMatcher& matcher,
                                                          const TriangulationRules& rules,
                                                          const std::function<bool()>& stop = {});

}  // namespace drvslam
