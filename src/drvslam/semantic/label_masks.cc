#include "drvslam/semantic/label_masks.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "drvslam/semantic/class_table.h"

namespace drvslam {
namespace {

std::string SizeText(cv::Size size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

template <typename T>
std::map<int, cv::Rect> LabelBoxes(const cv::Mat& labels) {
  // Bounding extents per id in one pass: x0, y0, x1, y1 (inclusive).
  std::map<int, cv::Vec4i> extents;
  for (int y = 0; y < labels.rows; ++y) {
    const T* row = labels.ptr<T>(y);
    int x = 0;
    while (x < labels.cols) {
      const int id = row[x];
      int end = x + 1;
      while (end < labels.cols && row[end] == row[x]) ++end;
      if (id != 0) {
        auto [it, inserted] = extents.try_emplace(id, cv::Vec4i(x, y, end - 1, y));
        if (!inserted) {
          cv::Vec4i& e = it->second;
          e[0] = std::min(e[0], x);
          e[2] = std::max(e[2], end - 1);
          e[3] = y;
        }
      }
      x = end;
    }
  }
  std::map<int, cv::Rect> boxes;
  for (const auto& [id, e] : extents) {
    boxes[id] = cv::Rect(e[0], e[1], e[2] - e[0] + 1, e[3] - e[1] + 1);
  }
  return boxes;
}

}  // namespace

cv::Mat ReadLabelImage(const std::string& path, cv::Size expected_size) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": mask file does not exist");
  cv::Mat image;
  try {
    image = cv::imread(path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw Error(path + ": cannot decode the mask image (" + e.err + ")");
  }
  if (image.empty()) throw Error(path + ": not a readable image");
  if (image.depth() != CV_8U && image.depth() != CV_16U) {
    throw Error(path + ": mask must hold 8- or 16-bit instance ids");
  }
  if (image.channels() == 3 || image.channels() == 4) {
    std::vector<cv::Mat> planes;
    cv::split(image, planes);
    if (cv::countNonZero(planes[0] != planes[1]) > 0 ||
        cv::countNonZero(planes[0] != planes[2]) > 0) {
      throw Error(path + ": mask is a colour image; expected one channel of instance ids");
    }
    image = planes[0];
  } else if (image.channels() != 1) {
    throw Error(path + ": mask must have one channel of instance ids");
  }
  if (!expected_size.empty() && image.size() != expected_size) {
    throw Error(path + ": mask is " + SizeText(image.size()) + " but the image is " +
                SizeText(expected_size));
  }
  return image;
}

void RequireFrameImage(const std::string& backend, const cv::Mat& bgr, std::size_t frame_index) {
  if (bgr.empty()) {
    throw Error(backend + ": frame " + std::to_string(frame_index) + " is an empty image");
  }
}

Segmentation SegmentationFromLabelFile(const std::string& path, const cv::Size& image_size,
                                       double timestamp, std::size_t frame_index) {
  const cv::Mat labels = ReadLabelImage(path, image_size);
  Segmentation result;
  result.timestamp = timestamp;
  result.frame_index = frame_index;
  result.image_size = image_size;
  result.instances = InstancesFromLabels(labels);
  return result;
}

std::vector<Instance> InstancesFromLabels(const cv::Mat& labels) {
  if (labels.channels() != 1 || (labels.depth() != CV_8U && labels.depth() != CV_16U)) {
    throw Error("label image must be one channel of 8- or 16-bit ids");
  }
  const std::map<int, cv::Rect> boxes = labels.depth() == CV_8U ? LabelBoxes<std::uint8_t>(labels)
                                                                : LabelBoxes<std::uint16_t>(labels);
  std::vector<Instance> instances;
  instances.reserve(boxes.size());
  for (const auto& [id, box] : boxes) {
    Instance instance;
    instance.source_id = id;
    instance.score = 1.0f;
    instance.box = box;
    instance.mask = cv::Mat::zeros(labels.size(), CV_8UC1);
    cv::Mat roi = instance.mask(box);
    cv::compare(labels(box), cv::Scalar(id), roi, cv::CMP_EQ);
    instances.push_back(std::move(instance));
  }
  return instances;
}

void StampIndex::Add(double stamp, std::string path) { entries_[stamp] = std::move(path); }

const std::string* StampIndex::Find(double stamp, double tolerance) const {
  const auto after = entries_.lower_bound(stamp);
  auto best = entries_.end();
  if (after != entries_.end()) best = after;
  if (after != entries_.begin()) {
    const auto before = std::prev(after);
    if (best == entries_.end() || stamp - before->first < best->first - stamp) best = before;
  }
  if (best == entries_.end() || !(std::abs(best->first - stamp) <= tolerance)) return nullptr;
  return &best->second;
}

int ResolveClassId(const std::string& name, int coco_id, std::vector<std::string>& class_names) {
  if (coco_id >= 0 && coco_id < static_cast<int>(class_names.size())) return coco_id;
  const std::string wanted = NormalizeClassName(name);
  for (std::size_t i = 0; i < class_names.size(); ++i) {
    if (NormalizeClassName(class_names[i]) == wanted) return static_cast<int>(i);
  }
  class_names.push_back(wanted);
  return static_cast<int>(class_names.size()) - 1;
}

bool ParseStamp(const std::string& text, double& value) {
  if (text.empty()) return false;
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  value = std::strtod(begin, &end);
  return errno == 0 && end == begin + text.size() && std::isfinite(value) &&
         (std::isdigit(static_cast<unsigned char>(text[0])) || text[0] == '-' || text[0] == '.');
}

}  // namespace drvslam
