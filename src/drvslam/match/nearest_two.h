// NearestTwo: the smallest and second-smallest descriptor distance over a scan of candidates,
// which every nearest-neighbour ratio test needs.
#pragma once

namespace drvslam {

struct NearestTwo {
  int best = 256;  // above any 256-bit Hamming distance
  int second = 256;
  int index = -1;  // candidate with the best distance; -1 while none was offered

  void Offer(int distance, int candidate) {
    if (distance < best) {
      second = best;
      best = distance;
      index = candidate;
    } else if (distance < second) {
      second = distance;
    }
  }
};

}  // namespace drvslam
