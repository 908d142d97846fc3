// PlaceHypotheses: the poses relocalization found for one frame, grouped into places, and the
// choice between them. In repeated structure (a tiled wall, identical shelves) a wrong place can
// gather as many PnP inliers as the right one, so the first pose with enough inliers is not
// enough: a place is taken only when no distinct place explains the frame almost as well.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "drvslam/core/se3.h"

namespace drvslam {

class KeyFrame;
class MapPoint;

struct PlaceHypothesis {
  SE3 T_cw;
  std::shared_ptr<KeyFrame> keyframe;  // matched against
  // One slot per frame keypoint: the inlier map point, or null.
  std::vector<std::shared_ptr<MapPoint>> matches;
  int inliers = 0;
  int bow_matches = 0;  // with the keyframe, before PnP (for the report)
  int pnp_inliers = 0;
};

struct PlaceChoiceOptions {
  // Poses closer than this (metres and radians) are the same place.
  double same_place_metres = 0.05;
  double same_place_radians = 3.0 * 3.14159265358979 / 180.0;
  // The runner-up place must explain fewer than this share of the best place's keypoints.
  double max_runner_up_ratio = 0.8;
};

struct PlaceChoice {
  int best = -1;              // index of the hypothesis to take (-1: none)
  int places = 0;             // distinct places among the hypotheses
  int best_support = 0;       // keypoints explained by the best place
  int runner_up_support = 0;  // by the best distinct other place (0: none)
  bool ambiguous = false;     // the runner-up came too close: nothing is taken
};

// Groups the hypotheses into places (a hypothesis joins the place of the first earlier one
// within the same-place distance) and scores each place by the frame keypoints that are inliers
// of any of its hypotheses. The best place's hypothesis with the most inliers is chosen when
// it has at least `min_inliers` and the runner-up's support is below the ratio of the best's.
PlaceChoice ChoosePlace(const std::vector<PlaceHypothesis>& hypotheses, int min_inliers,
                        const PlaceChoiceOptions& options = PlaceChoiceOptions());

}  // namespace drvslam
