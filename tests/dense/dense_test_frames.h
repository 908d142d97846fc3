// Test inputs for the dense module: frames of a fronto-parallel plane with known depth, with
// optional instance squares, so every back-projected point has a known place.
#pragma once

#include <opencv2/core.hpp>

#include "drvslam/core/camera.h"
#include "drvslam/dense/dense_frame.h"

namespace drvslam::testing {

inline CameraOptions SmallCamera() {
  CameraOptions camera;
  camera.width = 160;
  camera.height = 120;
  camera.fx = camera.fy = 150.0;
  camera.cx = 80.0;
  camera.cy = 60.0;
  return camera;
}

// Frames are this far apart in time: three keyframes span DenseMap.minViewSpan's default
// (1 s), so three views confirm a voxel as before that rule; tests of the time span set
// timestamps themselves.
constexpr double kFrameSeconds = 0.5;

// A plane at `depth` metres filling the image, grey colour `grey`.
inline DenseFrame PlaneFrame(const CameraOptions& camera, float depth, const SE3& T_wc = SE3(),
                             long id = 0) {
  DenseFrame frame;
  frame.frame_id = id;
  frame.timestamp = kFrameSeconds * static_cast<double>(id);
  frame.T_wc = T_wc;
  frame.bgr = cv::Mat(camera.height, camera.width, CV_8UC3, cv::Scalar(10, 20, 30));
  frame.depth = cv::Mat(camera.height, camera.width, CV_32FC1, cv::Scalar(depth));
  return frame;
}

// An instance covering `box`.
inline DenseInstance BoxInstance(const CameraOptions& camera, const cv::Rect& box, int class_id) {
  DenseInstance instance;
  instance.mask = cv::Mat::zeros(camera.height, camera.width, CV_8UC1);
  instance.mask(box).setTo(255);
  instance.class_id = class_id;
  return instance;
}

}  // namespace drvslam::testing
