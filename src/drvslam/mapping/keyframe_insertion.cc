#include "drvslam/mapping/keyframe_insertion.h"

namespace drvslam {
namespace {

// Replacement chains are short (a fusion replaces a point once, its survivor rarely again).
constexpr int kMaxReplacementHops = 16;

std::shared_ptr<MapPoint> LiveReplacement(std::shared_ptr<MapPoint> point) {
  for (int hop = 0; hop < kMaxReplacementHops && point && point->IsBad(); ++hop) {
    point = point->ReplacedBy();
  }
  return point && !point->IsBad() ? point : nullptr;
}

}  // namespace

std::vector<std::shared_ptr<MapPoint>> ProcessNewKeyFrame(
    const std::shared_ptr<KeyFrame>& keyframe) {
  const ScalePyramid& pyramid = keyframe->Geometry().pyramid;
  const long id = keyframe->Id();
  std::vector<std::shared_ptr<MapPoint>> created;
  const auto slots = keyframe->MapPoints();
  for (std::size_t i = 0; i < slots.size(); ++i) {
    std::shared_ptr<MapPoint> point = slots[i];
    if (!point) continue;
    if (point->IsBad()) {
      point = LiveReplacement(point);
      if (!point || point->IndexIn(id) >= 0) {
        keyframe->EraseMapPointAt(i);
        continue;
      }
      keyframe->ReplaceMapPointAt(i, point);
    }
    const int index = point->IndexIn(id);
    if (index < 0) {
      point->AddObservation(keyframe, static_cast<int>(i));
      point->UpdateNormalAndDepth(pyramid);
      point->ComputeDistinctiveDescriptor();
    } else if (static_cast<std::size_t>(index) != i) {
      keyframe->EraseMapPointAt(i);
    } else if (point->FirstKeyFrameId() == id) {
      created.push_back(point);
    }
  }
  keyframe->UpdateConnections();
  return created;
}

}  // namespace drvslam
