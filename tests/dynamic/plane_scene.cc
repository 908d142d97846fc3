#include "dynamic/plane_scene.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace drvslam::test {
namespace {

float HashValue(uint32_t seed, int64_t x, int64_t y) {
  uint64_t h = seed * 0x9E3779B97F4A7C15ull ^ (static_cast<uint64_t>(x) * 0xC2B2AE3D27D4EB4Full) ^
               (static_cast<uint64_t>(y) * 0x165667B19E3779F9ull);
  h ^= h >> 29;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 32;
  return static_cast<float>(h & 0xffff) / 65535.0f;
}

// Value noise with two octaves: smooth enough for optical flow, cornery enough for FAST.
float Texture(const Plane& plane, double u, double v) {
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

}  // namespace

Rendered Render(const std::vector<Plane>& planes, const Camera& camera,
                const std::vector<cv::Point2d>& offsets) {
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

std::vector<Instance> InstancesOf(const Rendered& rendered, const std::vector<int>& planes,
                                  int class_id) {
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
