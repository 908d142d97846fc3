// Unlabelled motion: moving things no detector names (a pushed box, a door, a ball). Moving
// points (from MotionConsistency: by the reprojection test where known, else the epipolar one) that
// lie outside every potentially-moving mask are grouped: two join when they are close in the image
// and at similar depth. A group with enough points is one moving thing; its region is grown from
// the points over depth-connected pixels (neighbours whose depth differs by less than a step)
// within a margin around them: Dynamic.regionMargin pixels, or Dynamic.regionReach metres at the
// group's depth when that is more, as a mover near the camera is large in the image and its
// moving points sample it sparsely (a walker 1 m from the camera spans half the image, and a
// 20-pixel margin left most of him in the map). With the reach, growth also stays within it in
// depth, so a surface joined to the mover (the floor under its feet) is not followed away from
// it. Every feature on a region is removed. Isolated moving points are flow noise and are left
// alone.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/dynamic/dynamic_options.h"
#include "drvslam/dynamic/motion_consistency.h"

namespace drvslam {

struct MovingRegion {
  cv::Rect box;              // the region's extent in the image
  cv::Mat mask;              // CV_8UC1 of box's size, 255 inside the region
  int points = 0;            // moving points that formed it
  std::vector<int> members;  // those points: indices into the tracks given
};

// tracks: MotionConsistency's output. labelled: empty or CV_8UC1 of the depth's size (nonzero =
// already handled by segmentation; points there are skipped). depth: CV_32FC1 metres (0 = no
// depth); points without depth are skipped. focal_px: the camera's focal length in pixels, for
// options.region_reach (0: the pixel margin only; DynamicFrontEnd puts
// Dynamic.regionReachWithoutSegmenter there when no segmenter runs). Throws drvslam::Error on
// inconsistent sizes/types.
std::vector<MovingRegion> FindUnlabelledMotion(const std::vector<FlowTrack>& tracks,
                                               const cv::Mat& labelled, const cv::Mat& depth,
                                               const DynamicOptions& options,
                                               double focal_px = 0.0);

// Paints the regions into `mask` (CV_8UC1 of the image size) with 255.
void PaintRegions(const std::vector<MovingRegion>& regions, cv::Mat& mask);

}  // namespace drvslam
