// SequenceWriter: puts a synthetic sequence on disk in the TUM RGB-D layout, plus its exact
// masks and instance list:
//   rgb/<stamp>.png, depth/<stamp>.png (16-bit, depth_factor per metre, 0 = no depth),
//   masks/<stamp>.png (16-bit instance id, 0 = background; same name as the colour image),
//   rgb.txt, depth.txt, associations.txt, groundtruth.txt, instances.txt, settings.yaml.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "drvslam/core/settings.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/tools/synth/instances_file.h"

namespace drvslam::synth {

// Metres (CV_32F) to the 16-bit depth file format: round(z * factor); 0 where there is no depth
// or the value does not fit 16 bits.
cv::Mat EncodeDepth(const cv::Mat& depth_m, double factor);

class SequenceWriter {
 public:
  // Prepares `folder` (creating it and rgb/, depth/, masks/). A non-empty folder is accepted
  // only when it holds an earlier synthetic sequence, which is then replaced; anything else is
  // an Error, so no user file is ever overwritten.
  explicit SequenceWriter(const std::string& folder);

  // Throws the Error the constructor would, without touching anything: lets a caller refuse a
  // bad output folder before spending time on a sequence.
  static void CheckFolder(const std::string& folder);

  // The image file name of a stamp: 6 decimals, as in the TUM datasets.
  static std::string StampName(double stamp);

  // Writes one frame's three PNGs. Frames with distinct stamps may be written concurrently.
  void WriteFrame(double stamp, const cv::Mat& bgr, const cv::Mat& depth16,
                  const cv::Mat& mask16) const;
  // Writes the lists, ground truth, instances and settings; call after every frame.
  void WriteLists(const Trajectory& ground_truth, const InstancesFile& instances,
                  const Settings& settings, const std::string& settings_extra_yaml) const;

  const std::string& Folder() const { return folder_; }

 private:
  std::string folder_;
};

}  // namespace drvslam::synth
