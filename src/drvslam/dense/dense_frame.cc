#include "drvslam/dense/dense_frame.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

bool InRange(float z, const DenseMapOptions& options) {
  return std::isfinite(z) && z >= options.min_depth && z <= options.max_depth && z > 0.0f;
}

void CheckImages(const DenseFrame& frame) {
  if (frame.depth.empty() || frame.depth.type() != CV_32FC1) {
    throw Error("dense frame " + std::to_string(frame.frame_id) + ": depth is not CV_32FC1");
  }
  if (frame.bgr.size() != frame.depth.size() || frame.bgr.type() != CV_8UC3) {
    throw Error("dense frame " + std::to_string(frame.frame_id) +
                ": colour is not CV_8UC3 of the depth image's size");
  }
}

bool Valid(float z) { return std::isfinite(z) && z > 0.0f; }

// Median of the valid depths under `mask` inside `box`; 0 when there are none.
float MedianDepth(const cv::Mat& depth, const cv::Mat& mask, const cv::Rect& box) {
  std::vector<float> values;
  for (int y = box.y; y < box.y + box.height; ++y) {
    const float* d = depth.ptr<float>(y);
    const uint8_t* m = mask.ptr<uint8_t>(y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (m[x] && Valid(d[x])) values.push_back(d[x]);
    }
  }
  if (values.empty()) return 0.0f;
  auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// Grows `excluded` from the pixels of `mask` along the object's depth: breadth first, at most
// `steps` pixels, into pixels whose depth continues their neighbour's (relative step below
// `continuity`) and stays within `band` of the object's median depth.
void GrowAlongDepth(const cv::Mat& depth, const cv::Mat& mask, int steps, float band,
                    float continuity, cv::Mat* excluded) {
  const cv::Rect box = cv::boundingRect(mask);
  if (box.empty()) return;
  const float median = MedianDepth(depth, mask, box);
  if (median <= 0.0f) return;
  const int w = depth.cols, h = depth.rows;
  std::vector<int> frontier;
  for (int y = box.y; y < box.y + box.height; ++y) {
    const float* d = depth.ptr<float>(y);
    const uint8_t* m = mask.ptr<uint8_t>(y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (m[x] && Valid(d[x]) && std::abs(d[x] - median) <= band) frontier.push_back(y * w + x);
    }
  }
  const float* d = depth.ptr<float>(0);
  uint8_t* out = excluded->ptr<uint8_t>(0);
  std::vector<int> next;
  for (int step = 0; step < steps && !frontier.empty(); ++step) {
    next.clear();
    for (const int p : frontier) {
      const int px = p % w, py = p / w;
      const int neighbours[4] = {px > 0 ? p - 1 : -1, px + 1 < w ? p + 1 : -1, py > 0 ? p - w : -1,
                                 py + 1 < h ? p + w : -1};
      for (const int q : neighbours) {
        if (q < 0 || out[q]) continue;
        if (!Valid(d[q]) || std::abs(d[q] - median) > band) continue;
        if (std::abs(d[q] - d[p]) > continuity * d[p]) continue;
        out[q] = 255;
        next.push_back(q);
      }
    }
    frontier.swap(next);
  }
}

// Marks both pixels of every 4-neighbour pair whose depths differ by more than `step` times
// the nearer depth.
void MarkFlyingPixels(const cv::Mat& depth, float step, cv::Mat* flying) {
  for (int y = 0; y < depth.rows; ++y) {
    const float* d = depth.ptr<float>(y);
    const float* below = y + 1 < depth.rows ? depth.ptr<float>(y + 1) : nullptr;
    uint8_t* f = flying->ptr<uint8_t>(y);
    uint8_t* f_below = below ? flying->ptr<uint8_t>(y + 1) : nullptr;
    for (int x = 0; x < depth.cols; ++x) {
      if (!Valid(d[x])) continue;
      if (x + 1 < depth.cols && Valid(d[x + 1]) &&
          std::abs(d[x + 1] - d[x]) > step * std::min(d[x], d[x + 1])) {
        f[x] = f[x + 1] = 255;
      }
      if (below && Valid(below[x]) && std::abs(below[x] - d[x]) > step * std::min(d[x], below[x])) {
        f[x] = f_below[x] = 255;
      }
    }
  }
}

}  // namespace

PixelRays MakePixelRays(const CameraOptions& camera) {
  PixelRays rays;
  rays.xy = cv::Mat(camera.height, camera.width, CV_32FC2);
  if (!camera.HasDistortion()) {
    for (int y = 0; y < camera.height; ++y) {
      cv::Vec2f* row = rays.xy.ptr<cv::Vec2f>(y);
      const float ny = static_cast<float>((y - camera.cy) / camera.fy);
      for (int x = 0; x < camera.width; ++x) {
        row[x] = {static_cast<float>((x - camera.cx) / camera.fx), ny};
      }
    }
    return rays;
  }
  std::vector<cv::Point2f> pixels;
  pixels.reserve(static_cast<std::size_t>(camera.width) * camera.height);
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) pixels.emplace_back(x, y);
  }
  const PinholeCamera pinhole(camera);
  std::vector<cv::Point2f> normalised;
  // More iterations than OpenCV's default of 5: image corners of wide lenses need them.
  cv::undistortPoints(pixels, normalised, pinhole.K(), pinhole.DistortionCoeffs(), cv::noArray(),
                      cv::noArray(),
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 1e-8));
  for (int y = 0; y < camera.height; ++y) {
    cv::Vec2f* row = rays.xy.ptr<cv::Vec2f>(y);
    for (int x = 0; x < camera.width; ++x) {
      const cv::Point2f& n = normalised[static_cast<std::size_t>(y) * camera.width + x];
      row[x] = {n.x, n.y};
    }
  }
  return rays;
}

Eigen::Vector2f ProjectToImage(const CameraOptions& camera, const Eigen::Vector3f& point_c) {
  const double x = point_c.x() / point_c.z(), y = point_c.y() / point_c.z();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (camera.k1 + r2 * (camera.k2 + r2 * camera.k3));
  const double xd = x * radial + 2.0 * camera.p1 * x * y + camera.p2 * (r2 + 2.0 * x * x);
  const double yd = y * radial + camera.p1 * (r2 + 2.0 * y * y) + 2.0 * camera.p2 * x * y;
  return {static_cast<float>(camera.fx * xd + camera.cx),
          static_cast<float>(camera.fy * yd + camera.cy)};
}

void CheckDenseFrame(const DenseFrame& frame) {
  CheckImages(frame);
  for (const DenseInstance& instance : frame.instances) {
    if (instance.mask.size() != frame.depth.size() || instance.mask.type() != CV_8UC1) {
      throw Error("dense frame " + std::to_string(frame.frame_id) +
                  ": an instance mask is not CV_8UC1 of the depth image's size");
    }
  }
}

PixelRoles PaintRoles(const DenseFrame& frame, const DenseMapOptions& options) {
  CheckDenseFrame(frame);
  const cv::Size size = frame.depth.size();
  PixelRoles roles;
  roles.role = cv::Mat(size, CV_8UC1, cv::Scalar(static_cast<int>(PixelRole::kBackground)));
  roles.label = cv::Mat(size, CV_16SC1, cv::Scalar(-1));
  roles.track = cv::Mat(size, CV_32SC1, cv::Scalar(-1));
  cv::Mat excluded = cv::Mat::zeros(size, CV_8UC1);
  bool any_excluded = false;
  for (const DenseInstance& instance : frame.instances) {
    const bool exclude =
        options.remove_dynamic &&
        (instance.moving || (options.remove_all_potentially_moving && instance.potentially_moving));
    roles.label.setTo(instance.class_id, instance.mask);
    if (exclude) {
      excluded.setTo(255, instance.mask);
      any_excluded = true;
      if (options.mask_growth > 0) {
        const float continuity =
            static_cast<float>(options.flying_pixel_step > 0.0 ? options.flying_pixel_step : 0.03);
        GrowAlongDepth(frame.depth, instance.mask, options.mask_growth,
                       static_cast<float>(options.mask_growth_depth_band), continuity, &excluded);
      }
    } else if (instance.key_object) {
      roles.role.setTo(static_cast<int>(PixelRole::kKeyObject), instance.mask);
    } else if (instance.potentially_moving && instance.track_id >= 0) {
      roles.track.setTo(instance.track_id, instance.mask);
    }
  }
  if (any_excluded) {
    if (options.mask_dilation > 0) {
      const int k = 2 * options.mask_dilation + 1;
      cv::dilate(excluded, excluded, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
    }
    roles.role.setTo(static_cast<int>(PixelRole::kExcluded), excluded);
    roles.moving = excluded;
  }
  if (options.flying_pixel_step > 0.0) {
    cv::Mat flying = cv::Mat::zeros(size, CV_8UC1);
    MarkFlyingPixels(frame.depth, static_cast<float>(options.flying_pixel_step), &flying);
    roles.role.setTo(static_cast<int>(PixelRole::kExcluded), flying);
  }
  return roles;
}

DenseCloud BackProject(const DenseFrame& frame, const PixelRoles& roles, PixelRole role,
                       const CameraOptions& camera, const DenseMapOptions& options) {
  return BackProject(frame, roles, role, MakePixelRays(camera), options);
}

DenseCloud BackProject(const DenseFrame& frame, const PixelRoles& roles, PixelRole role,
                       const PixelRays& rays, const DenseMapOptions& options) {
  CheckImages(frame);
  if (rays.xy.size() != frame.depth.size() || rays.xy.type() != CV_32FC2) {
    throw Error("dense frame " + std::to_string(frame.frame_id) +
                ": the camera's image size differs from the depth image's");
  }
  DenseCloud cloud;
  const uint8_t wanted = static_cast<uint8_t>(role);
  for (int y = 0; y < frame.depth.rows; ++y) {
    const cv::Vec2f* ray = rays.xy.ptr<cv::Vec2f>(y);
    const float* depth = frame.depth.ptr<float>(y);
    const uint8_t* roles_row = roles.role.ptr<uint8_t>(y);
    const int16_t* labels = roles.label.ptr<int16_t>(y);
    const int32_t* tracks = roles.track.ptr<int32_t>(y);
    const cv::Vec3b* colour = frame.bgr.ptr<cv::Vec3b>(y);
    for (int x = 0; x < frame.depth.cols; ++x) {
      if (roles_row[x] != wanted) continue;
      const float z = depth[x];
      if (!InRange(z, options)) continue;
      cloud.push_back(PixelPoint(ray[x], z, colour[x], labels[x], tracks[x]));
    }
  }
  return cloud;
}

std::size_t CountMappedPixels(const DenseFrame& frame, const PixelRoles& roles,
                              const DenseMapOptions& options) {
  CheckImages(frame);
  std::size_t count = 0;
  const uint8_t excluded = static_cast<uint8_t>(PixelRole::kExcluded);
  for (int y = 0; y < frame.depth.rows; ++y) {
    const float* depth = frame.depth.ptr<float>(y);
    const uint8_t* roles_row = roles.role.ptr<uint8_t>(y);
    for (int x = 0; x < frame.depth.cols; ++x) {
      count += roles_row[x] != excluded && InRange(depth[x], options);
    }
  }
  return count;
}

}  // namespace drvslam
