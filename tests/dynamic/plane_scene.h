// A tiny ray-cast renderer for dynamic-module tests: textured rectangles parallel to the image
// plane at fixed depths (background, boxes, "people"), seen by a pinhole camera that may move.
// Gives the grey image, the depth (metres) and a label image (index of the visible plane + 1),
// so tests know exactly which pixels belong to which object and where objects moved.
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

inline float HashValue(uint32_t seed, int64_t x, int64_t y) {
  uint64_t h = seed * 0x9E3779B97F4A7C15ull ^ (static_cast<uint64_t>(x) * 0xC2B2AE3D27D4EB4Full) ^
               (static_cast<uint64_t>(y) * 0x165667B19E3779F9ull);
  h ^= h >> 29;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 32;
  return static_cast<float>(h & 0xffff) / 65535.0f;
}

// Value noise with two octaves: smooth enough for optical flow, cornery enough for FAST.
inline float Texture(const Plane& plane, double u, double v) {
  float value = 0.0f;
  double cell = plane.cell;
  float weight = 0.65f;
  for (int octave = 0; octave < 2; ++octave) {
    const double gx = u / cell;
    const double gy = v / cell;
    const int64_t x0 = static_cast<int64_t>(std::floor(gx));
    const int64_t y0 = static_cast<int64_t>(std::floor(gy));
    const float fx = static_cast<float>(gx - x0);
    const float fy = static_cast<float>(gy - y0);
    const uint32_t s = plane.seed * 7 + octave;
    const float a = HashValue(s, x0, y0), b = HashValue(s, x0 + 1, y0);
    const float c = HashValue(s, x0, y0 + 1), d = HashValue(s, x0 + 1, y0 + 1);
    value += weight * ((a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy);
    weight = 1.0f - weight;
    cell *= 0.3;
  }
  return value;
}

// Planes are given in world coordinates; `offsets[k]` moves plane k (and its texture) by
// (dx, dy) metres, so an object can move between two renders.
inline Rendered Render(const std::vector<Plane>& planes, const Camera& camera,
                       const std::vector<cv::Point2d>& offsets = {}) {
  Rendered out;
  out.gray = cv::Mat(camera.size, CV_8UC1);
  out.depth = cv::Mat::zeros(camera.size, CV_32FC1);
  out.labels = cv::Mat::zeros(camera.size, CV_32SC1);
  const double cx = 0.5 * (camera.size.width - 1);
  const double cy = 0.5 * (camera.size.height - 1);
  const double cs = std::cos(camera.yaw), sn = std::sin(camera.yaw);
  for (int v = 0; v < camera.size.height; ++v) {
    for (int u = 0; u < camera.size.width; ++u) {
      const double dxc = (u - cx) / camera.f;
      const double dyc = (v - cy) / camera.f;
      // Camera-to-world rotation about y.
      const double dx = cs * dxc + sn * 1.0;
      const double dy = dyc;
      const double dz = -sn * dxc + cs * 1.0;
      double best_t = 1e18;
      int best = -1;
      double best_u = 0, best_v = 0;
      for (std::size_t k = 0; k < planes.size(); ++k) {
        const Plane& p = planes[k];
        const double t = (p.z - camera.center[2]) / dz;
        if (t <= 0 || t >= best_t) continue;
        const cv::Point2d shift = k < offsets.size() ? offsets[k] : cv::Point2d(0, 0);
        const double x = camera.center[0] + t * dx - shift.x;
        const double y = camera.center[1] + t * dy - shift.y;
        if (x < p.extent.x || x >= p.extent.x + p.extent.width || y < p.extent.y ||
            y >= p.extent.y + p.extent.height) {
          continue;
        }
        best_t = t;
        best = static_cast<int>(k);
        best_u = x - p.extent.x;
        best_v = y - p.extent.y;
      }
      if (best < 0) {
        out.gray.at<uint8_t>(v, u) = 0;
        continue;
      }
      out.gray.at<uint8_t>(v, u) =
          cv::saturate_cast<uint8_t>(20.0f + 215.0f * Texture(planes[best], best_u, best_v));
      // Camera-frame depth: the ray's z component in the camera is 1.
      out.depth.at<float>(v, u) = static_cast<float>(best_t);
      out.labels.at<int>(v, u) = best + 1;
    }
  }
  return out;
}

// One instance per listed plane index that is visible: full-size 0/255 mask and its box.
inline std::vector<Instance> InstancesOf(const Rendered& rendered, const std::vector<int>& planes,
                                         int class_id = 0) {
  std::vector<Instance> instances;
  for (const int k : planes) {
    Instance instance;
    instance.class_id = class_id;
    instance.class_name = "person";
    instance.score = 1.0f;
    cv::compare(rendered.labels, k + 1, instance.mask, cv::CMP_EQ);
    if (cv::countNonZero(instance.mask) == 0) continue;
    instance.box = cv::boundingRect(instance.mask);
    instance.source_id = k;
    instances.push_back(instance);
  }
  return instances;
}

}  // namespace drvslam::test
