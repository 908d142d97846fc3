#include "drvslam/semantic/mask_propagator.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

cv::Mat ToGrey(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat grey;
  cv::cvtColor(image, grey, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return grey;
}

// Forward flow: where each pixel of `from` went in `to`.
cv::Mat ForwardFlow(const cv::Mat& from_grey, const cv::Mat& to_grey, double scale) {
  cv::Mat from_small = from_grey;
  cv::Mat to_small = to_grey;
  if (scale < 1.0) {
    cv::resize(from_grey, from_small, cv::Size(), scale, scale, cv::INTER_AREA);
    cv::resize(to_grey, to_small, cv::Size(), scale, scale, cv::INTER_AREA);
  }
  cv::Ptr<cv::DISOpticalFlow> dis =
      cv::DISOpticalFlow::create(cv::DISOpticalFlow::PRESET_ULTRAFAST);
  cv::Mat flow;
  dis->calc(from_small, to_small, flow);
  if (scale < 1.0) {
    cv::resize(flow, flow, from_grey.size(), 0, 0, cv::INTER_LINEAR);
    flow *= 1.0 / scale;
  }
  return flow;
}

// A similarity fitted (RANSAC) to point correspondences, or their median translation when there
// are too few for a fit; identity when there are none.
cv::Matx23d FitMotion(const std::vector<cv::Point2f>& from, const std::vector<cv::Point2f>& to) {
  cv::Matx23d motion(1, 0, 0, 0, 1, 0);
  if (from.size() >= 6) {
    const cv::Mat fitted = cv::estimateAffinePartial2D(from, to, cv::noArray(), cv::RANSAC, 1.5);
    if (!fitted.empty()) return cv::Matx23d(fitted);
  }
  if (from.empty()) return motion;
  std::vector<float> dx;
  std::vector<float> dy;
  for (std::size_t i = 0; i < from.size(); ++i) {
    dx.push_back(to[i].x - from[i].x);
    dy.push_back(to[i].y - from[i].y);
  }
  std::nth_element(dx.begin(), dx.begin() + dx.size() / 2, dx.end());
  std::nth_element(dy.begin(), dy.begin() + dy.size() / 2, dy.end());
  motion(0, 2) = dx[dx.size() / 2];
  motion(1, 2) = dy[dy.size() / 2];
  return motion;
}

cv::Mat WarpMask(const cv::Mat& mask, const cv::Matx23d& motion) {
  cv::Mat warped;
  cv::warpAffine(mask, warped, motion, mask.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
  return warped;
}

// The mask moved by a similarity fitted to the dense flow inside it. Flow at the mask's rim
// mixes object and background, so samples come from the eroded interior when there is one.
cv::Mat WarpByDenseFlow(const cv::Mat& mask, const cv::Mat& flow) {
  cv::Mat interior;
  cv::erode(mask, interior, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(7, 7)));
  if (cv::countNonZero(interior) < 20) interior = mask;
  const cv::Rect box = cv::boundingRect(interior);
  if (box.empty()) return mask.clone();
  // About 400 samples on a grid whatever the object's size.
  const int step = std::max(1, static_cast<int>(std::sqrt(box.area() / 400.0)));
  std::vector<cv::Point2f> from;
  std::vector<cv::Point2f> to;
  for (int y = box.y; y < box.br().y; y += step) {
    const unsigned char* inside = interior.ptr<unsigned char>(y);
    const cv::Vec2f* motion = flow.ptr<cv::Vec2f>(y);
    for (int x = box.x; x < box.br().x; x += step) {
      if (!inside[x]) continue;
      from.emplace_back(static_cast<float>(x), static_cast<float>(y));
      to.emplace_back(x + motion[x][0], y + motion[x][1]);
    }
  }
  return WarpMask(mask, FitMotion(from, to));
}

// The mask moved by a similarity fitted to corners tracked from inside it; unchanged when
// nothing could be tracked.
cv::Mat WarpBySparseFlow(const cv::Mat& mask, const cv::Mat& from_grey, const cv::Mat& to_grey) {
  cv::Mat search_area;
  cv::dilate(mask, search_area, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)));
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(from_grey, corners, 150, 0.01, 4, search_area, 5);
  if (corners.empty()) return mask.clone();
  std::vector<cv::Point2f> tracked;
  std::vector<cv::Point2f> back;
  std::vector<unsigned char> status;
  std::vector<unsigned char> back_status;
  std::vector<float> errors;
  const cv::Size window(21, 21);
  cv::calcOpticalFlowPyrLK(from_grey, to_grey, corners, tracked, status, errors, window, 3);
  cv::calcOpticalFlowPyrLK(to_grey, from_grey, tracked, back, back_status, errors, window, 3);
  std::vector<cv::Point2f> good_from;
  std::vector<cv::Point2f> good_to;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    // Forward-backward consistency rejects points lost at occlusion boundaries.
    if (status[i] && back_status[i] && cv::norm(back[i] - corners[i]) < 1.0) {
      good_from.push_back(corners[i]);
      good_to.push_back(tracked[i]);
    }
  }
  if (good_from.empty()) return mask.clone();
  return WarpMask(mask, FitMotion(good_from, good_to));
}

}  // namespace

MaskPropagator::MaskPropagator(const MaskPropagatorOptions& options) : options_(options) {
  if (options_.method == MaskPropagation::kObjects) {
    throw Error(
        "mask propagation: Segmentation.propagation objects is carried by flow tracks "
        "(ObjectMaskCarrier), not by MaskPropagator");
  }
  options_.flow_scale = std::clamp(options_.flow_scale, 0.1, 1.0);
}

Segmentation MaskPropagator::Propagate(const Segmentation& masks, const cv::Mat& from,
                                       const cv::Mat& to, double to_timestamp,
                                       std::size_t to_frame_index) const {
  if (from.empty() || to.empty() || from.size() != to.size()) {
    throw Error("mask propagation: the two images must be non-empty and of one size");
  }
  if (from.depth() != CV_8U || to.depth() != CV_8U) {
    throw Error("mask propagation: images must be 8-bit");
  }
  Segmentation out;
  out.timestamp = to_timestamp;
  out.frame_index = to_frame_index;
  out.image_size = to.size();
  for (const Instance& instance : masks.instances) {
    if (instance.mask.size() != to.size() || instance.mask.type() != CV_8UC1) {
      throw Error("mask propagation: an instance mask differs from the image in size or type");
    }
  }
  if (options_.method == MaskPropagation::kNone || masks.instances.empty()) {
    out.instances = masks.instances;
    return out;
  }
  const cv::Mat from_grey = ToGrey(from);
  const cv::Mat to_grey = ToGrey(to);
  cv::Mat flow;
  if (options_.method == MaskPropagation::kDenseFlow) {
    flow = ForwardFlow(from_grey, to_grey, options_.flow_scale);
  }
  for (const Instance& instance : masks.instances) {
    const cv::Mat warped = options_.method == MaskPropagation::kDenseFlow
                               ? WarpByDenseFlow(instance.mask, flow)
                               : WarpBySparseFlow(instance.mask, from_grey, to_grey);
    Instance moved = instance;
    // A fresh buffer: the copied header still shares the source mask's pixels.
    moved.mask = cv::Mat();
    cv::threshold(warped, moved.mask, 127, 255, cv::THRESH_BINARY);
    if (cv::countNonZero(moved.mask) < options_.min_area) continue;
    moved.box = cv::boundingRect(moved.mask);
    out.instances.push_back(std::move(moved));
  }
  return out;
}

double MaskIoU(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size()) throw Error("mask IoU: masks differ in size");
  const cv::Mat inside_a = a != 0;
  const cv::Mat inside_b = b != 0;
  const int intersection = cv::countNonZero(inside_a & inside_b);
  const int uni = cv::countNonZero(inside_a | inside_b);
  return uni == 0 ? 0.0 : static_cast<double>(intersection) / uni;
}

}  // namespace drvslam
