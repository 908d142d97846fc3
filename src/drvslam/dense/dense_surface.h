// The background of a keyframe as samples of its surfaces: depth smoothed along each surface
// (as KinectFusion filters depth before fusing it), so the sensor's noise at a few metres no
// longer spreads a wall over several voxel layers in front of and behind it, and each point
// weighted as a view of its surface: the inverse of its depth variance (structured-light noise
// grows with z^2) times the cosine between the viewing ray and the surface normal (a frontal
// view places a surface better than a grazing one).
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/dense/dense_frame.h"
#include "drvslam/dense/dense_options.h"
#include "drvslam/dense/dense_point.h"

namespace drvslam {

// The weight given when no surface normal can be estimated (isolated pixels, thin strips), and
// the least a grazing view counts.
inline constexpr float kMinViewCosine = 0.1f;

struct SurfaceSamples {
  DenseCloud points;           // camera frame
  std::vector<float> weights;  // one per point
};

// The inverse depth variance of a structured-light reading at depth z (metres), up to scale.
float DepthNoiseWeight(float z);

// Depth averaged over the (2 radius + 1)^2 pixels around each pixel that `usable` marks and
// whose depth lies within `step` times the centre's (the same surface); two 1-D passes. Pixels
// not usable keep their depth. radius 0 returns a copy.
cv::Mat SmoothDepthAlongSurfaces(const cv::Mat& depth, const cv::Mat& usable, int radius,
                                 float step);

// The cosine between the viewing ray of every usable pixel and the surface normal from the
// depth image (differences over `radius` pixels, one-sided at edges); kMinViewCosine where no
// normal can be formed or the view grazes. CV_32FC1; 0 on pixels not usable.
cv::Mat ViewCosines(const cv::Mat& depth, const cv::Mat& usable, const PixelRays& rays, int radius,
                    float step);

// The background pixels of `roles` (depth in [min_depth, max_depth]) back-projected from the
// depth smoothed with DenseMap.depthSmoothing, each with weight cosine / z^4. Throws Error when
// the rays are not of the frame's size.
SurfaceSamples BackProjectSurfaces(const DenseFrame& frame, const PixelRoles& roles,
                                   const PixelRays& rays, const DenseMapOptions& options);

}  // namespace drvslam
