// Label images: one PNG per frame whose pixel values are instance ids (0 = background), the
// on-disk form of segmentations made offline or by the synthetic generator. Shared by the
// mask-file and ground-truth segmenters: reading and checking the image, splitting it into
// per-instance masks, and finding a frame's file by its timestamp.
#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "drvslam/semantic/segmenter.h"

namespace drvslam {

// Reads an 8- or 16-bit single-channel label PNG (a 3-channel grey one is accepted too). Throws
// drvslam::Error naming `path` when it is missing, unreadable, of another type, or not
// `expected_size` (when that is not empty).
cv::Mat ReadLabelImage(const std::string& path, cv::Size expected_size);

// One instance per non-zero id, in increasing id order: source_id = id, score 1, the exact box
// and a full-size 0/255 mask. Class fields are left for the caller.
std::vector<Instance> InstancesFromLabels(const cv::Mat& labels);

// Throws drvslam::Error naming `backend` and the frame when `bgr` is empty: a label file is
// matched to a frame by its image, so an empty one cannot be segmented.
void RequireFrameImage(const std::string& backend, const cv::Mat& bgr, std::size_t frame_index);

// The segmentation the label image at `path` gives a frame of `image_size`: ReadLabelImage, then
// InstancesFromLabels, stamped with the frame's time and index. Class fields are left for the
// caller.
Segmentation SegmentationFromLabelFile(const std::string& path, const cv::Size& image_size,
                                       double timestamp, std::size_t frame_index);

// File stems that are numbers, sorted, for nearest-timestamp lookup.
class StampIndex {
 public:
  void Add(double stamp, std::string path);
  // The entry nearest to `stamp` within `tolerance` seconds, or nullptr.
  const std::string* Find(double stamp, double tolerance) const;
  bool Empty() const { return entries_.empty(); }

 private:
  std::map<double, std::string> entries_;
};

// The class id of a labelled instance in a table that starts with the COCO-80 names: its COCO id
// when it has one (0..79), else the id of the same name (compared as NormalizeClassName does),
// appending the name to `class_names` the first time it is seen.
int ResolveClassId(const std::string& name, int coco_id, std::vector<std::string>& class_names);

// Parses a whole string as a finite decimal number; false when it is anything else.
bool ParseStamp(const std::string& text, double& value);

}  // namespace drvslam
