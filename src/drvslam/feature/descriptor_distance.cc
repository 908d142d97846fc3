#include "drvslam/feature/descriptor_distance.h"

#include <cstring>
#include <string>

#include "drvslam/core/error.h"

namespace drvslam {
namespace {

void CheckDescriptor(const cv::Mat& d, const char* name) {
  if (d.type() != CV_8UC1 || d.rows != 1 || d.cols != kDescriptorBytes) {
    throw Error(std::string("DescriptorDistance: descriptor ") + name +
                " must be 1x32 CV_8UC1, got " + std::to_string(d.rows) + "x" +
                std::to_string(d.cols) + " of type " + std::to_string(d.type()));
  }
}

}  // namespace

int DescriptorDistance(const uint8_t* a, const uint8_t* b) {
  int distance = 0;
  for (int i = 0; i < kDescriptorBytes; i += 8) {
    // memcpy: rows of a cv::Mat need not be 8-byte aligned.
    uint64_t wa, wb;
    std::memcpy(&wa, a + i, 8);
    std::memcpy(&wb, b + i, 8);
    distance += __builtin_popcountll(wa ^ wb);
  }
  return distance;
}

int DescriptorDistance(const cv::Mat& a, const cv::Mat& b) {
  CheckDescriptor(a, "a");
  CheckDescriptor(b, "b");
  return DescriptorDistance(a.ptr<uint8_t>(), b.ptr<uint8_t>());
}

}  // namespace drvslam
