// FAST corners of one pyramid level with a per-cell fallback threshold: the whole level is
// searched at the initial threshold, and every grid cell that kept no corner is searched again
// at the lower one, so low-texture areas still offer candidates to the distribution step.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "drvslam/feature/level_skip_mask.h"

namespace drvslam {

struct FastGridParams {
  int ini_threshold = 20;
  int min_threshold = 7;
  int border = 16;     // corners keep this distance (pixels) from the level's edges
  int cell_size = 32;  // fallback cell side (pixels, approximate: cells split the region evenly)
};

// Appends nothing and returns an empty list when the level is smaller than 2 * border + 1.
// Corners (level coordinates, response = FAST score) that `mask` skips are dropped before a
// cell counts as empty, so a cell whose corners are all masked falls back too. `scratch` is
// reused between calls to avoid allocations.
void DetectFastGrid(const cv::Mat& level, const FastGridParams& params, const LevelSkipMask& mask,
                    std::vector<cv::KeyPoint>* corners, std::vector<cv::KeyPoint>* scratch);

// The rectangle corners can lie in: [border, cols - border) x [border, rows - border).
cv::Rect DetectionRegion(const cv::Size& level_size, int border);

}  // namespace drvslam
