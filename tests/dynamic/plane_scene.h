// A tiny ray-cast renderer for dynamic-module tests: textured rectangles parallel to the image
// plane at fixed depths (background, boxes, "people"), seen by a pinhole camera that may move.
// Gives the grey image, the depth (metres) and a label image (index of the visible plane + 1),
// so tests know exactly which pixels belong to which object and where objects moved.
// Compiled once and optimized in every tree (tests/dynamic/CMakeLists.txt says why).
#pragma once

#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "drvslam/semantic/segmenter.h"

namespace drvslam::test {

struct Plane {
  double z = 4.0;      // world depth of the plane (z = const)
  cv::Rect2d extent;   // world x, y range (metres)
  uint32_t seed = 1;   // texture
  double cell = 0.04;  // texture cell size (metres)
};

struct Camera {
  double f = 525.0;
  cv::Size size{640, 480};
  cv::Vec3d center{0, 0, 0};  // world position
  double yaw = 0.0;           // rotation about the vertical axis, radians
};

struct Rendered {
  cv::Mat gray;    // CV_8UC1
  cv::Mat depth;   // CV_32FC1 metres
  cv::Mat labels;  // CV_32SC1: plane index + 1, 0 = nothing
};

// Planes are given in world coordinates; `offsets[k]` moves plane k (and its texture) by
// (dx, dy) metres, so an object can move between two renders.
Rendered Render(const std::vector<Plane>& planes, const Camera& camera,
                const std::vector<cv::Point2d>& offsets = {});

// One instance per listed plane index that is visible: full-size 0/255 mask and its box.
std::vector<Instance> InstancesOf(const Rendered& rendered, const std::vector<int>& planes,
                                  int class_id = 0);

}  // namespace drvslam::test
