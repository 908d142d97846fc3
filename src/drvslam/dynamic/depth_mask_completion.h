// Depth completion of instance masks. A network's mask of a person often misses an arm, a hand
// or the legs, or leaves holes in a near body (measured on the real Bonn crowd sequence; see
// docs/dynamic-handling.md). The missing parts belong to the same body: connected to the mask in
// the depth image, at about its depth. So each potentially-moving instance's mask is grown over
// the pixels that are depth-connected to its own pixels (neighbours differing by less than
// Dynamic.completionDepthStep metres), within its box grown by Dynamic.completionMargin of its
// size and within Dynamic.completionDepthBand metres of the instance's median depth. The mask
// never shrinks; pixels without depth are never added. A static surface the body touches (the
// floor under a foot) can join only inside the grown box and the depth band, so what it costs is
// a few static features next to the person, never features across the image.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/semantic/segmenter.h"

namespace drvslam {

struct MaskCompletionOptions {
  double margin = 0.15;      // box growth on each side, share of the box's size
  double depth_step = 0.04;  // metres between neighbouring pixels of one surface
  double depth_band = 0.6;   // metres from the instance's median depth
};

// Grows `instance.mask` (CV_8UC1, 0/255, image size) and its box in place. depth: CV_32FC1
// metres of the same size (0 or non-finite: no depth). Returns the pixels added. An instance with
// too few valid depth pixels on its mask (fewer than 20) is left as it is. Throws drvslam::Error
// on mismatched sizes or types.
int CompleteMaskWithDepth(Instance& instance, const cv::Mat& depth,
                          const MaskCompletionOptions& options);

}  // namespace drvslam
