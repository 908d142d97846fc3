#include "drvslam/semantic/object_mask_carrier.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/semantic/mask_lookup.h"

namespace drvslam {
namespace {

bool Inside(const Instance& instance, const cv::Point2f& p) {
  const cv::Point pixel(static_cast<int>(p.x), static_cast<int>(p.y));
  return instance.box.contains(pixel) && OnMask(instance.mask, p);
}

float Median(std::vector<float> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// The box's corners moved by `motion`, bounded, one pixel wider for interpolation, clipped.
cv::Rect MovedBox(const cv::Rect& box, const cv::Matx23d& motion, const cv::Size& size) {
  double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
  for (const cv::Point2d corner :
       {cv::Point2d(box.x, box.y), cv::Point2d(box.br().x, box.y), cv::Point2d(box.x, box.br().y),
        cv::Point2d(box.br().x, box.br().y)}) {
    const double x = motion(0, 0) * corner.x + motion(0, 1) * corner.y + motion(0, 2);
    const double y = motion(1, 0) * corner.x + motion(1, 1) * corner.y + motion(1, 2);
    x0 = std::min(x0, x);
    y0 = std::min(y0, y);
    x1 = std::max(x1, x);
    y1 = std::max(y1, y);
  }
  const double limit = 1e6;  // a wild fit must not overflow int
  x0 = std::clamp(x0, -limit, limit);
  y0 = std::clamp(y0, -limit, limit);
  x1 = std::clamp(x1, -limit, limit);
  y1 = std::clamp(y1, -limit, limit);
  const cv::Rect moved(
      cv::Point(static_cast<int>(std::floor(x0)) - 1, static_cast<int>(std::floor(y0)) - 1),
      cv::Point(static_cast<int>(std::ceil(x1)) + 2, static_cast<int>(std::ceil(y1)) + 2));
  return moved & cv::Rect(0, 0, size.width, size.height);
}

}  // namespace

void ObjectMaskCarrierOptions::Check() const {
  if (min_support < 1) {
    throw Error("Segmentation.carryMinSupport must be at least 1, got " +
                std::to_string(min_support));
  }
  if (min_fit < 2) throw Error("mask carrier: min_fit must be at least 2");
  if (!(ransac_threshold > 0.0)) throw Error("mask carrier: ransac_threshold must be positive");
  if (!(min_inlier_share >= 0.0 && min_inlier_share <= 1.0)) {
    throw Error("mask carrier: min_inlier_share must be in [0, 1]");
  }
  if (min_area < 1) throw Error("mask carrier: min_area must be at least 1");
}

ObjectMaskCarrier::ObjectMaskCarrier(const ObjectMaskCarrierOptions& options) : options_(options) {
  options_.Check();
}

CarriedObject ObjectMaskCarrier::FitStep(const Instance& source, const cv::Matx23d& carried,
                                         const std::vector<PointMotion>& motions) const {
  // A point of the frame before this step lies on the carried mask when it maps back onto the
  // source mask.
  cv::Matx23d back;
  cv::invertAffineTransform(carried, back);
  std::vector<cv::Point2f> from;
  std::vector<cv::Point2f> to;
  for (const PointMotion& m : motions) {
    const cv::Point2f origin(
        static_cast<float>(back(0, 0) * m.from.x + back(0, 1) * m.from.y + back(0, 2)),
        static_cast<float>(back(1, 0) * m.from.x + back(1, 1) * m.from.y + back(1, 2)));
    if (!Inside(source, origin)) continue;
    from.push_back(m.from);
    to.push_back(m.to);
  }
  CarriedObject step;
  step.support = static_cast<int>(from.size());
  if (step.support < options_.min_support) return step;
  if (step.support >= options_.min_fit) {
    std::vector<uchar> inliers;
    const cv::Mat fitted = cv::estimateAffinePartial2D(from, to, inliers, cv::RANSAC,
                                                       options_.ransac_threshold, 200, 0.99, 10);
    const int inlier_count = fitted.empty() ? 0 : cv::countNonZero(inliers);
    if (inlier_count >= options_.min_inlier_share * step.support) {
      step.motion = cv::Matx23d(fitted);
      step.fitted = true;
      step.inliers = inlier_count;
    }
  }
  if (!step.fitted) {
    std::vector<float> dx(from.size());
    std::vector<float> dy(from.size());
    for (std::size_t i = 0; i < from.size(); ++i) {
      dx[i] = to[i].x - from[i].x;
      dy[i] = to[i].y - from[i].y;
    }
    step.motion(0, 2) = Median(std::move(dx));
    step.motion(1, 2) = Median(std::move(dy));
    step.inliers = step.support;
  }
  return step;
}

std::vector<Instance> ObjectMaskCarrier::Carry(const std::vector<Instance>& instances,
                                               const std::vector<PointMotion>& motions,
                                               const cv::Size& size,
                                               std::vector<CarriedObject>* report) const {
  return CarryThrough(instances, {&motions}, size, report);
}

std::vector<Instance> ObjectMaskCarrier::CarryThrough(
    const std::vector<Instance>& instances,
    const std::vector<const std::vector<PointMotion>*>& steps, const cv::Size& size,
    std::vector<CarriedObject>* report) const {
  if (report != nullptr) report->assign(instances.size(), CarriedObject());
  std::vector<Instance> carried;
  carried.reserve(instances.size());
  for (std::size_t k = 0; k < instances.size(); ++k) {
    const Instance& instance = instances[k];
    if (instance.mask.size() != size || instance.mask.type() != CV_8UC1) {
      throw Error("mask carrier: an instance mask is not CV_8UC1 of the image's size");
    }
    Instance source = instance;
    // Boxes from the network are tight but may be missing (hand-built instances).
    if (source.box.empty()) source.box = cv::boundingRect(source.mask);
    if (source.box.empty()) continue;
    // The steps' motions composed: source frame -> the latest frame so far.
    CarriedObject object;
    bool expired = false;
    for (const std::vector<PointMotion>* motions : steps) {
      const CarriedObject step = FitStep(source, object.motion, *motions);
      if (step.support < options_.min_support) {
        object.support = step.support;
        expired = true;
        break;
      }
      const cv::Matx23d& m = step.motion;
      const cv::Matx23d& a = object.motion;
      object.motion = cv::Matx23d(
          m(0, 0) * a(0, 0) + m(0, 1) * a(1, 0), m(0, 0) * a(0, 1) + m(0, 1) * a(1, 1),
          m(0, 0) * a(0, 2) + m(0, 1) * a(1, 2) + m(0, 2), m(1, 0) * a(0, 0) + m(1, 1) * a(1, 0),
          m(1, 0) * a(0, 1) + m(1, 1) * a(1, 1), m(1, 0) * a(0, 2) + m(1, 1) * a(1, 2) + m(1, 2));
      object.support = step.support;
      object.inliers = step.inliers;
      object.fitted = step.fitted;
    }
    if (report != nullptr) (*report)[k] = object;
    if (expired) continue;

    // Warp only the neighbourhood the box moves to: dst(p) = src(M^-1 p) with p offset by the
    // region's corner.
    const cv::Rect region = MovedBox(source.box, object.motion, size);
    if (region.empty()) continue;
    cv::Matx23d shifted = object.motion;
    shifted(0, 2) -= region.x;
    shifted(1, 2) -= region.y;
    cv::Mat warped;
    cv::warpAffine(source.mask, warped, shifted, region.size(), cv::INTER_LINEAR,
                   cv::BORDER_CONSTANT, 0);
    Instance moved = source;
    // A new buffer: assigning Mat::zeros would write into the shared source mask.
    moved.mask = cv::Mat(size, CV_8UC1, cv::Scalar(0));
    cv::threshold(warped, moved.mask(region), 127, 255, cv::THRESH_BINARY);
    const cv::Rect tight = cv::boundingRect(moved.mask(region));
    if (tight.empty() || cv::countNonZero(moved.mask(region)) < options_.min_area) continue;
    moved.box = tight + region.tl();
    carried.push_back(std::move(moved));
  }
  return carried;
}

}  // namespace drvslam
