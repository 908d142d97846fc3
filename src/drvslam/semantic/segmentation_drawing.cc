#include "drvslam/semantic/segmentation_drawing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "drvslam/core/error.h"

namespace drvslam {

cv::Scalar ClassColor(int class_id) {
  // Golden-ratio steps around the hue circle keep neighbouring ids apart.
  const double hue = std::fmod(0.61803398875 * (class_id + 1), 1.0) * 180.0;
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue, 220, 255));
  cv::Mat bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
  return cv::Scalar(c[0], c[1], c[2]);
}

cv::Mat DrawSegmentation(const cv::Mat& bgr, const Segmentation& segmentation) {
  cv::Mat canvas;
  if (bgr.channels() == 1) {
    cv::cvtColor(bgr, canvas, cv::COLOR_GRAY2BGR);
  } else if (bgr.channels() == 4) {
    cv::cvtColor(bgr, canvas, cv::COLOR_BGRA2BGR);
  } else {
    canvas = bgr.clone();
  }
  for (const Instance& instance : segmentation.instances) {
    if (instance.mask.size() != canvas.size() || instance.mask.type() != CV_8UC1) {
      throw Error("drawing: an instance mask is not the image's size");
    }
    const cv::Scalar color = ClassColor(instance.class_id);
    cv::Mat tinted;
    cv::addWeighted(canvas, 0.5, cv::Mat(canvas.size(), canvas.type(), color), 0.5, 0.0, tinted);
    tinted.copyTo(canvas, instance.mask);
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(instance.mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    cv::drawContours(canvas, contours, -1, color, 2, cv::LINE_AA);
  }
  // Boxes and labels last, so no mask covers a label.
  for (const Instance& instance : segmentation.instances) {
    const cv::Scalar color = ClassColor(instance.class_id);
    cv::rectangle(canvas, instance.box, color, 2);
    char label[128];
    std::snprintf(label, sizeof(label), "%s %.2f", instance.class_name.c_str(), instance.score);
    int baseline = 0;
    const cv::Size text = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, 0.5, 1, &baseline);
    const int top = std::max(0, instance.box.y - text.height - baseline - 2);
    const cv::Rect background(instance.box.x, top, text.width + 4, text.height + baseline + 2);
    cv::rectangle(canvas, background, color, cv::FILLED);
    cv::putText(canvas, label, cv::Point(instance.box.x + 2, top + text.height + 1),
                cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  return canvas;
}

cv::Mat MakeCutout(const cv::Mat& bgr, const Instance& instance) {
  const cv::Rect box = instance.box & cv::Rect(cv::Point(), bgr.size());
  if (box.empty()) return cv::Mat();
  if (instance.mask.size() != bgr.size() || instance.mask.type() != CV_8UC1) {
    throw Error("cut-out: the instance mask is not the image's size");
  }
  cv::Mat color;
  if (bgr.channels() == 1) {
    cv::cvtColor(bgr(box), color, cv::COLOR_GRAY2BGR);
  } else if (bgr.channels() == 4) {
    cv::cvtColor(bgr(box), color, cv::COLOR_BGRA2BGR);
  } else {
    color = bgr(box);
  }
  std::vector<cv::Mat> planes;
  cv::split(color, planes);
  planes.push_back(instance.mask(box).clone());
  cv::Mat cutout;
  cv::merge(planes, cutout);
  return cutout;
}

}  // namespace drvslam
