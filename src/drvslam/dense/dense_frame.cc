#include "drvslam/dense/dense_frame.h"

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

}  // namespace

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
  }
  return roles;
}

DenseCloud BackProject(const DenseFrame& frame, const PixelRoles& roles, PixelRole role,
                       const CameraOptions& camera, const DenseMapOptions& options) {
  CheckImages(frame);
  DenseCloud cloud;
  const uint8_t wanted = static_cast<uint8_t>(role);
  const float inv_fx = static_cast<float>(1.0 / camera.fx);
  const float inv_fy = static_cast<float>(1.0 / camera.fy);
  const float cx = static_cast<float>(camera.cx);
  const float cy = static_cast<float>(camera.cy);
  for (int y = 0; y < frame.depth.rows; ++y) {
    const float* depth = frame.depth.ptr<float>(y);
    const uint8_t* roles_row = roles.role.ptr<uint8_t>(y);
    const int16_t* labels = roles.label.ptr<int16_t>(y);
    const int32_t* tracks = roles.track.ptr<int32_t>(y);
    const cv::Vec3b* colour = frame.bgr.ptr<cv::Vec3b>(y);
    const float ny = (static_cast<float>(y) - cy) * inv_fy;
    for (int x = 0; x < frame.depth.cols; ++x) {
      if (roles_row[x] != wanted) continue;
      const float z = depth[x];
      if (!InRange(z, options)) continue;
      DensePoint p;
      p.position = {(static_cast<float>(x) - cx) * inv_fx * z, ny * z, z};
      p.b = colour[x][0];
      p.g = colour[x][1];
      p.r = colour[x][2];
      p.label = labels[x];
      p.track = tracks[x];
      cloud.push_back(p);
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
