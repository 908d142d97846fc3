// Depth images in metres: the one conversion from a sensor's raw 16-bit depth (as TUM and Bonn
// files store it) or float metres to the CV_32FC1 metres the pipeline uses, shared by the
// dataset reader and System::TrackRGBD.
#pragma once

#include <opencv2/core/mat.hpp>
#include <string>

namespace drvslam {

// "16-bit unsigned 1-channel" and the like, for error messages about an image's type.
std::string DescribeImageType(const cv::Mat& image);

// Whether DepthToMetres takes this image type: CV_16UC1 (raw) or CV_32FC1 (metres).
bool IsDepthImageType(int type);

// CV_16UC1: each value / depth_map_factor (raw units per metre, e.g. 5000 for TUM), divided in
// double and rounded once to float, so a stored value maps to the nearest float of raw / factor
// (convertTo's float scale would round twice); 0 stays 0 (no measurement). CV_32FC1: a copy in
// which NaN, inf and negative values (no measurement) become 0. Any other type throws Error
// "<what> is <type>; expected ..."; `what` names the image (e.g. its file).
cv::Mat DepthToMetres(const cv::Mat& raw, double depth_map_factor, const std::string& what);

}  // namespace drvslam
