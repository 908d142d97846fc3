// The work of `drvslam segment`: segment a list of images and videos with one Segmenter, and
// write a JSON list of the instances found, overlay pictures and RGBA cut-outs. Lives in the
// library so the command only parses options and prints.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "drvslam/semantic/latency_stats.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

struct SegmentJobOptions {
  std::vector<std::string> inputs;  // image or video files
  std::string json_path;            // empty: no JSON
  std::string overlay_dir;          // empty: no overlays
  std::string cutouts_dir;          // empty: no cut-outs
  int every = 1;                    // videos: segment every N-th frame
  int max_frames = 0;               // videos: at most this many segmented frames each (0: all)
  std::vector<std::string> cutout_classes = {"person"};

  // Throws drvslam::Error naming the bad option.
  void Check() const;
};

struct SegmentedImage {
  std::string source;  // the input file
  int frame = -1;      // video frame number, -1 for an image
  Segmentation segmentation;
  double segment_ms = 0.0;
};

struct SegmentJobSummary {
  std::size_t images = 0;  // images and video frames segmented
  std::size_t instances = 0;
  std::size_t cutouts = 0;
  Spread segment_ms;
};

// Runs the job; `on_image` (optional) sees each result as it is made, for progress output.
// Throws drvslam::Error naming the file when an input is missing or unreadable, or an output
// cannot be written.
SegmentJobSummary RunSegmentJob(Segmenter& segmenter, const SegmentJobOptions& options,
                                const std::function<void(const SegmentedImage&)>& on_image = {});

}  // namespace drvslam
