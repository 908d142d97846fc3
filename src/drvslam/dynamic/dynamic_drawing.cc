#include "drvslam/dynamic/dynamic_drawing.h"

#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

const cv::Scalar kRed(0, 0, 255);
const cv::Scalar kGreen(0, 200, 0);
const cv::Scalar kGrey(160, 160, 160);

void Tint(cv::Mat& image, const cv::Mat& mask, const cv::Rect& box, const cv::Scalar& color) {
  const cv::Rect area = box & cv::Rect(0, 0, image.cols, image.rows);
  if (area.area() <= 0) return;
  cv::Mat roi = image(area);
  cv::Mat tinted(roi.size(), roi.type(), color);
  cv::Mat blended;
  cv::addWeighted(roi, 0.55, tinted, 0.45, 0.0, blended);
  blended.copyTo(roi, mask(area));
}

void Outline(cv::Mat& image, const cv::Mat& mask, const cv::Point& offset,
             const cv::Scalar& color) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE, offset);
  cv::drawContours(image, contours, -1, color, 2);
}

}  // namespace

cv::Mat DrawDynamicFrame(const cv::Mat& bgr, const std::vector<Instance>& instances,
                         const std::vector<ObjectEvidence>& objects,
                         const std::vector<MovingRegion>& regions,
                         const std::vector<cv::KeyPoint>& kept,
                         const std::vector<cv::KeyPoint>& removed) {
  cv::Mat canvas;
  if (bgr.type() == CV_8UC3) {
    canvas = bgr.clone();
  } else if (bgr.type() == CV_8UC1) {
    cv::cvtColor(bgr, canvas, cv::COLOR_GRAY2BGR);
  } else {
    throw Error("DrawDynamicFrame: image must be 8-bit BGR or grey");
  }
  for (std::size_t k = 0; k < instances.size(); ++k) {
    const Instance& instance = instances[k];
    if (instance.mask.size() != canvas.size()) {
      throw Error("DrawDynamicFrame: instance masks must have the image's size");
    }
    const bool known = k < objects.size() && objects[k].potentially_moving;
    const bool moving = known && objects[k].moving;
    const cv::Scalar color = !known ? kGrey : moving ? kRed : kGreen;
    if (known) Tint(canvas, instance.mask, instance.box, color);
    Outline(canvas, instance.mask, cv::Point(), color);
    char label[160];
    if (known) {
      const ObjectEvidence& e = objects[k];
      std::snprintf(label, sizeof(label), "#%d %s %s d=%.2f e=%.2f r=%.2f", e.track_id,
                    instance.class_name.c_str(), moving ? "moving" : "static", e.delta,
                    e.moving_share, e.reprojection_share);
    } else {
      std::snprintf(label, sizeof(label), "%s", instance.class_name.c_str());
    }
    const cv::Point at(instance.box.x, std::max(12, instance.box.y - 4));
    cv::putText(canvas, label, at, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 3);
    cv::putText(canvas, label, at, cv::FONT_HERSHEY_SIMPLEX, 0.45, color, 1);
  }
  for (const MovingRegion& region : regions) {
    const cv::Rect box = region.box & cv::Rect(0, 0, canvas.cols, canvas.rows);
    if (box != region.box) continue;
    cv::Mat roi = canvas(box);
    Tint(roi, region.mask, cv::Rect(0, 0, box.width, box.height), kRed);
    Outline(canvas, region.mask, box.tl(), kRed);
    cv::rectangle(canvas, box, kRed, 1);
  }
  for (const cv::KeyPoint& kp : kept) cv::circle(canvas, kp.pt, 2, kGreen, -1);
  for (const cv::KeyPoint& kp : removed) cv::circle(canvas, kp.pt, 2, kRed, -1);
  return canvas;
}

}  // namespace drvslam
