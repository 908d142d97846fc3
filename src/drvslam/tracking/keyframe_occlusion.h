// Which of the reference keyframe's points the current frame cannot see because something nearer
// stands in front of them. ORB-SLAM2 asks for a keyframe when a frame tracks clearly fewer points
// than its reference keyframe; when people walk between the camera and the scene, that happens
// every few frames although the camera has seen nothing new, and keyframes whose view is half
// people come one after another. The keyframe rule therefore compares the inliers against the
// reference's points that are still in view (docs/architecture.md#keyframes-behind-movers).
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "drvslam/core/camera.h"
#include "drvslam/core/se3.h"
#include "drvslam/map/keyframe.h"

namespace drvslam {

// A depth reading counts as in front of a point when it is nearer than this share of the
// point's depth: three times the ~3 % relative depth spread measured on a structured-light
// sensor (docs/benchmarks.md#real-data), so noise alone never hides a point.
inline constexpr double kOccluderDepthShare = 0.9;
// Half the side of the square of depth readings that must all be nearer.
inline constexpr int kOccluderRadius = 3;

// Whether `point_w` projects into the image of a camera at `T_cw` where the depth image
// (CV_32FC1 metres, the frame's own) reads clearly nearer than the point. False behind the
// camera, outside the image and where depth is missing (nothing says it is hidden).
bool HiddenBehindNearer(const Eigen::Vector3d& point_w, const SE3& T_cw,
                        const PinholeCamera& camera, const cv::Mat& depth);

// The reference keyframe's well-observed points (observation_weight.h, min_weight), and how many
// of them are hidden behind something nearer in a frame at `T_cw` with `depth` (0 when depth is
// empty). One pass: tracking asks every frame.
struct ReferencePointCount {
  int well_observed = 0;
  int hidden = 0;
};
ReferencePointCount CountReferencePoints(const KeyFrame& reference, int min_weight, const SE3& T_cw,
                                         const PinholeCamera& camera, const cv::Mat& depth);

}  // namespace drvslam
