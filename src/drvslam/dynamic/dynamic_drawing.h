// Pictures of the dynamic module's decisions, like Fig. 5 of the DRV-SLAM paper: masks of
// moving objects tinted red and of static (potentially-moving) objects green, regions of
// unlabelled motion outlined red, kept features as green dots and removed ones as red dots, and
// per object its ID, state and evidence (d = the paper's delta, e = share of its tracks failing
// the epipolar test, r = ... the reprojection test; -1 = undefined). `drvslam run --debug-frames
// DIR` writes one per frame.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/dynamic/motion_state.h"
#include "drvslam/dynamic/unlabelled_motion.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

// `objects[k]` belongs to `instances[k]` (may be shorter: then the rest are drawn as static
// background classes). Throws drvslam::Error when bgr is not CV_8UC3/CV_8UC1 or a mask is not
// the image's size.
cv::Mat DrawDynamicFrame(const cv::Mat& bgr, const std::vector<Instance>& instances,
                         const std::vector<ObjectEvidence>& objects,
                         const std::vector<MovingRegion>& regions,
                         const std::vector<cv::KeyPoint>& kept,
                         const std::vector<cv::KeyPoint>& removed);

}  // namespace drvslam
