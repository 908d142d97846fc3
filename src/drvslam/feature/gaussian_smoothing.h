// The smoothing BRIEF samples from: a separable 7x7 Gaussian with sigma 2 (the kernel ORB
// uses), in exact fixed-point arithmetic so every build gives the same bits, vectorized because
// it runs over every pyramid level of every frame.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace drvslam {

// dst = src (CV_8UC1, any size) smoothed, borders reflected as cv::BORDER_REFLECT_101 does.
// Within one grey level of cv::GaussianBlur(src, dst, {7, 7}, 2.0). `row_buffer` is scratch
// space kept by the caller to avoid allocations.
void SmoothGaussian7(const cv::Mat& src, cv::Mat* dst, std::vector<uint16_t>* row_buffer);

}  // namespace drvslam
