// Hamming distance between two 256-bit ORB descriptors: the metric every matcher uses.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

namespace drvslam {

constexpr int kDescriptorBytes = 32;

// a, b: 1x32 CV_8UC1 (e.g. descriptors.row(i)). Throws drvslam::Error on any other shape.
int DescriptorDistance(const cv::Mat& a, const cv::Mat& b);

// The same on raw 32-byte rows, for inner loops that already hold row pointers.
int DescriptorDistance(const uint8_t* a, const uint8_t* b);

}  // namespace drvslam
