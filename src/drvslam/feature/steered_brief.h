// The per-keypoint half of ORB: orientation by intensity centroid and the 256-bit BRIEF
// descriptor whose sampling pattern is rotated by that orientation, which is what makes the
// descriptor rotation invariant.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

namespace drvslam {

// Angle (degrees, [0, 360), image axes: x right, y down) from the keypoint at integer position
// (x, y) of `image` (CV_8UC1) to the intensity centroid of the disc of radius 15 around it.
// Pixels x - 15 .. x + 16, y - 15 .. y + 15 must lie inside the image (the vectorized sum reads
// 32 pixels per row).
float IntensityCentroidAngle(const cv::Mat& image, int x, int y);

// Steered BRIEF: 32 bytes into `out`, bit i (byte i / 8, bit i % 8) set when the first sample of
// pattern pair i, rotated by `angle_deg` about (x, y), is darker than the second. `smoothed` is
// the Gaussian-smoothed level (CV_8UC1); the disc of radius 15 around (x, y) must lie inside it.
void ComputeSteeredBrief(const cv::Mat& smoothed, int x, int y, float angle_deg, uint8_t* out);

}  // namespace drvslam
