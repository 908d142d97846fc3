// DenseFrame: what the dense mapping thread needs of one tracked frame - its pose at tracking
// time, colour, depth and the instances the dynamic module saw with their roles - and the
// per-pixel roles and back-projection built from it. Frames are handed over by value (images
// shared, never written afterwards), so the thread needs no access to tracking's state.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/core/camera.h"
#include "drvslam/core/se3.h"
#include "drvslam/dense/dense_options.h"
#include "drvslam/dense/dense_point.h"

namespace drvslam {

struct DenseInstance {
  cv::Mat mask;  // CV_8UC1 (0 / non-zero) of the image's size; read only
  int class_id = -1;
  int track_id = -1;  // the dynamic module's object ID; -1 = none
  bool moving = false;
  bool potentially_moving = false;
  bool key_object = false;  // a static key-object class: enhanced
};

struct DenseFrame {
  long frame_id = 0;
  double timestamp = 0.0;
  SE3 T_wc;       // at tracking time
  cv::Mat bgr;    // CV_8UC3
  cv::Mat depth;  // CV_32FC1 metres, 0 = none
  std::vector<DenseInstance> instances;
};

// What each pixel contributes.
enum class PixelRole : uint8_t { kBackground = 0, kExcluded = 1, kKeyObject = 2 };

struct PixelRoles {
  cv::Mat role;    // CV_8UC1 of PixelRole
  cv::Mat label;   // CV_16SC1 class id, -1 = none
  cv::Mat track;   // CV_32SC1 object ID of a kept potentially-moving object, -1 = none
  cv::Mat moving;  // CV_8UC1, non-zero on left-out objects (grown masks); empty when none
};

// The viewing ray of every pixel, with lens distortion removed: normalised image coordinates
// (x/z, y/z) of the ray through pixel (x, y). Built once per camera.
struct PixelRays {
  cv::Mat xy;  // CV_32FC2, the camera's height x width
};
PixelRays MakePixelRays(const CameraOptions& camera);

// Where a camera-frame point (z > 0) is seen in the (distorted) image: the inverse of the rays.
Eigen::Vector2f ProjectToImage(const CameraOptions& camera, const Eigen::Vector3f& point_c);

// Throws Error naming the frame when depth is not CV_32FC1, colour not CV_8UC3 of its size or a
// mask not CV_8UC1 of its size.
void CheckDenseFrame(const DenseFrame& frame);

// Paints the roles: key objects enhanced, moving objects (and with
// remove_all_potentially_moving every potentially-moving one) excluded with their masks grown
// along the object's continuous depth (mask_growth) and then by mask_dilation; with
// remove_dynamic off nothing is excluded. Flying pixels at depth edges are excluded too
// (flying_pixel_step). Throws Error as CheckDenseFrame.
PixelRoles PaintRoles(const DenseFrame& frame, const DenseMapOptions& options);

// Camera-frame points of the pixels with `role` whose depth lies in [min_depth, max_depth],
// coloured from bgr, labelled and tracked from `roles`, along `rays` (pixel (x, y) is the ray
// through (x, y) itself; with lens distortion, the undistorted one). Throws Error when the rays
// are not of the frame's size.
DenseCloud BackProject(const DenseFrame& frame, const PixelRoles& roles, PixelRole role,
                       const PixelRays& rays, const DenseMapOptions& options);
// The same with the rays built from `camera` for this call.
DenseCloud BackProject(const DenseFrame& frame, const PixelRoles& roles, PixelRole role,
                       const CameraOptions& camera, const DenseMapOptions& options);

// Pixels with valid depth that are not excluded: the frame's share of a full-resolution map.
std::size_t CountMappedPixels(const DenseFrame& frame, const PixelRoles& roles,
                              const DenseMapOptions& options);

}  // namespace drvslam
