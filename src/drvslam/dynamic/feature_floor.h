// The feature floor: removal never leaves tracking with fewer features than it needs
// (Dynamic.minKeptFeatures). When it would, removed features are kept back, weakest moving
// evidence first: unlabelled regions (geometry alone), then potentially-moving objects that
// were not judged moving (removed for their class only), then objects judged moving by
// semantics and geometry, which are kept back only when nothing else is left. Within a tier,
// weaker evidence first, then the stronger corner (the likelier match).
#pragma once

#include <vector>

namespace drvslam {

enum class RemovalTier { kUnlabelled = 0, kStillObject = 1, kMovingObject = 2 };

struct RemovalCandidate {
  int feature = -1;  // the caller's index
  RemovalTier tier = RemovalTier::kUnlabelled;
  double evidence = 0.0;  // how strongly it is believed moving, within its tier
  float response = 0.0f;  // the keypoint's corner response
};

// The features (RemovalCandidate::feature) to keep back so that `kept` plus them reaches
// `floor`, in the order above; none when kept >= floor. Deterministic: ties go to the lower
// feature index.
std::vector<int> KeepBack(std::vector<RemovalCandidate> removed, int kept, int floor);

}  // namespace drvslam
