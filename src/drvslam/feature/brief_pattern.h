// The fixed point-pair pattern of our steered BRIEF descriptor: 256 pairs of pixel offsets inside
// a disc of radius 15 (so any rotation keeps them inside the 31x31 patch), drawn once from an
// isotropic Gaussian by our own fixed-seed generator. Every process gets the same table, which
// is what makes descriptors comparable across runs and machines.
#pragma once

#include <array>

namespace drvslam {

struct BriefPointPair {
  int x1, y1;  // first sample, offset from the keypoint (pixels, y down)
  int x2, y2;  // second sample: bit = I(first) < I(second)
};

constexpr int kBriefBits = 256;
constexpr int kBriefPatchRadius = 15;

using BriefPattern = std::array<BriefPointPair, kBriefBits>;

// The pattern; built on first use (thread-safe) and never changed.
const BriefPattern& GetBriefPattern();

}  // namespace drvslam
