// TumDataset: an RGB-D sequence in the TUM RGB-D benchmark layout (rgb.txt, depth.txt, optional
// associations.txt and groundtruth.txt beside rgb/ and depth/ folders); the Bonn RGB-D Dynamic
// dataset uses the same layout. Only the lists are read up front; Read() loads one frame's images
// on demand, so a long sequence costs no more memory than a short one.
#pragma once

#include <cstddef>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "drvslam/io/frame_fault.h"
#include "drvslam/io/trajectory_io.h"

namespace drvslam {

struct RgbdFrame {
  std::size_t index = 0;             // position in the sequence
  double timestamp = 0.0;            // colour image stamp (s)
  double depth_timestamp = 0.0;      // depth image stamp (s)
  cv::Mat bgr;                       // CV_8UC3, BGR order
  cv::Mat depth;                     // CV_32FC1 metres, 0 where the sensor gave nothing
  std::string rgb_path, depth_path;  // absolute or folder-joined paths
};

struct TumDatasetOptions {
  double depth_map_factor = 5000.0;  // raw 16-bit units per metre
  int expected_width = 0;            // 0 = take the first image's size; else must match
  int expected_height = 0;
  double max_difference = 0.02;   // association window (s)
  bool rgb_is_rgb_order = false;  // true: stored images are RGB (swap to BGR on read)
  // Throws Error naming the bad option.
  void Check() const;
};

class TumDataset {
 public:
  // Opens `folder`: reads rgb.txt and depth.txt ('#' comments and blank lines allowed) and pairs
  // colour with depth as the TUM associate.py does (AssociateStamps, offset 0), or takes the pairs
  // from associations.txt when present ("t_rgb rgb_path t_depth depth_path" per line). Reads
  // groundtruth.txt when present. Images are not loaded here. Throws Error naming the file (and
  // line) on a missing folder or list, a malformed line, or an empty sequence. A list entry
  // whose timestamp repeats or goes back (against the last kept entry) is dropped and described
  // in DroppedEntries().
  explicit TumDataset(const std::string& folder, const TumDatasetOptions& options = {});

  std::size_t Size() const;
  double Timestamp(std::size_t index) const;
  // Loads and checks both images of frame `index`. Every call reads the files again and keeps no
  // per-frame state, so it may be called in any order and from several threads. When the options
  // give no expected size, every frame must match the colour image of frame 0. Throws FrameError
  // (an Error naming the file, with the FrameFault) for a missing, empty, corrupt, wrongly sized
  // or wrongly typed image; a plain Error when frame 0, which sets the size, cannot be read.
  // NaN, infinite and negative float depths are stored as 0 (no measurement).
  RgbdFrame Read(std::size_t index) const;

  bool HasGroundTruth() const;
  const Trajectory& GroundTruth() const;  // empty when absent
  const std::string& Folder() const;
  // List entries dropped on opening because their timestamp did not increase (kind
  // kTimestampNotIncreasing; the message names the list file and line).
  const std::vector<FrameError>& DroppedEntries() const;

 private:
  struct Entry {
    double rgb_stamp;
    double depth_stamp;
    std::string rgb_path;
    std::string depth_path;
  };
  struct SizeCache;

  void CheckIndex(std::size_t index) const;
  cv::Size ReferenceSize(std::size_t index, const cv::Mat& bgr) const;

  std::string folder_;
  TumDatasetOptions options_;
  std::vector<Entry> entries_;
  Trajectory ground_truth_;
  std::vector<FrameError> dropped_;
  // The size of frame 0, found on first need; shared so the dataset stays copyable and movable.
  std::shared_ptr<SizeCache> size_cache_;
};

}  // namespace drvslam
