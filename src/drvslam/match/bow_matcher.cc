#include "drvslam/match/bow_matcher.h"

#include "drvslam/feature/descriptor_distance.h"
#include "drvslam/match/nearest_two.h"
#include "drvslam/match/rotation_consistency.h"

namespace drvslam {
namespace {

// Walks two direct indexes in node order and calls visit(indices1, indices2) for every node
// both hold; lower_bound jumps make it cheap when one side is much sparser.
template <typename Visit>
void ForEachSharedNode(const FeatureVector& a, const FeatureVector& b, Visit visit) {
  auto it_a = a.begin();
  auto it_b = b.begin();
  while (it_a != a.end() && it_b != b.end()) {
    if (it_a->first == it_b->first) {
      visit(it_a->second, it_b->second);
      ++it_a;
      ++it_b;
    } else if (it_a->first < it_b->first) {
      it_a = a.lower_bound(it_b->first);
    } else {
      it_b = b.lower_bound(it_a->first);
    }
  }
}

const uint8_t* Row(const cv::Mat& descriptors, unsigned index) {
  return descriptors.ptr<uint8_t>(static_cast<int>(index));
}

// Drops the matches (slot indices) outside the dominant rotation bins.
int RejectRotations(const RotationConsistency& rotations,
                    std::vector<std::shared_ptr<MapPoint>>* matches, int count) {
  for (const int slot : rotations.Rejected()) {
    (*matches)[slot].reset();
    --count;
  }
  return count;
}

// One shared vocabulary node: for each index i of `indices1` whose point is usable, the nearest
// of the `indices2` rows that `free2(j)` allows, by descriptor distance; calls matched(i, j)
// when that one passes the distance and ratio tests.
template <typename Free, typename Matched>
void MatchInNode(const std::vector<unsigned>& indices1, const std::vector<unsigned>& indices2,
                 const std::vector<std::shared_ptr<MapPoint>>& points1, const cv::Mat& descriptors1,
                 const cv::Mat& descriptors2, const BowMatchOptions& options, Free free2,
                 Matched matched) {
  for (const unsigned i : indices1) {
    const auto& point1 = points1[i];
    if (!point1 || point1->IsBad()) continue;
    const uint8_t* descriptor = Row(descriptors1, i);
    NearestTwo nearest;
    for (const unsigned j : indices2) {
      if (!free2(j)) continue;
      nearest.Offer(DescriptorDistance(descriptor, Row(descriptors2, j)), static_cast<int>(j));
    }
    if (nearest.index < 0 || nearest.best > options.max_distance ||
        nearest.best >= options.nn_ratio * nearest.second) {
      continue;
    }
    matched(i, nearest.index);
  }
}

}  // namespace

int SearchByBow(const KeyFrame& keyframe, const Frame& frame, const BowMatchOptions& options,
                std::vector<std::shared_ptr<MapPoint>>* matches) {
  matches->assign(frame.Size(), nullptr);
  if (!keyframe.HasBow() || !frame.has_bow) return 0;
  const auto points = keyframe.MapPoints();
  const FrameFeatures& kf_features = keyframe.Features();
  const FrameFeatures& features = frame.Features();
  const cv::Mat& kf_descriptors = kf_features.Descriptors();
  const cv::Mat& descriptors = features.Descriptors();
  RotationConsistency rotations;
  int count = 0;
  ForEachSharedNode(
      keyframe.BowFeatures(), frame.bow_features,
      [&](const std::vector<unsigned>& kf_indices, const std::vector<unsigned>& frame_indices) {
        MatchInNode(
            kf_indices, frame_indices, points, kf_descriptors, descriptors, options,
            [&](unsigned j) { return !(*matches)[j]; },
            [&](unsigned i, int j) {
              (*matches)[j] = points[i];
              ++count;
              if (options.check_orientation) {
                rotations.Add(kf_features.KeypointsUn()[i].angle - features.KeypointsUn()[j].angle,
                              j);
              }
            });
      });
  if (options.check_orientation) count = RejectRotations(rotations, matches, count);
  return count;
}

int SearchByBow(const KeyFrame& kf1, const KeyFrame& kf2, const BowMatchOptions& options,
                std::vector<std::shared_ptr<MapPoint>>* matches12) {
  const FrameFeatures& features1 = kf1.Features();
  const FrameFeatures& features2 = kf2.Features();
  matches12->assign(features1.Size(), nullptr);
  if (!kf1.HasBow() || !kf2.HasBow()) return 0;
  const auto points1 = kf1.MapPoints();
  const auto points2 = kf2.MapPoints();
  const cv::Mat& descriptors1 = features1.Descriptors();
  const cv::Mat& descriptors2 = features2.Descriptors();
  std::vector<bool> taken2(features2.Size(), false);
  RotationConsistency rotations;
  int count = 0;
  ForEachSharedNode(
      kf1.BowFeatures(), kf2.BowFeatures(),
      [&](const std::vector<unsigned>& indices1, const std::vector<unsigned>& indices2) {
        MatchInNode(
            indices1, indices2, points1, descriptors1, descriptors2, options,
            [&](unsigned j) { return !taken2[j] && points2[j] && !points2[j]->IsBad(); },
            [&](unsigned i, int j) {
              (*matches12)[i] = points2[j];
              taken2[j] = true;
              ++count;
              if (options.check_orientation) {
                rotations.Add(features1.KeypointsUn()[i].angle - features2.KeypointsUn()[j].angle,
                              static_cast<int>(i));
              }
            });
      });
  if (options.check_orientation) count = RejectRotations(rotations, matches12, count);
  return count;
}

}  // namespace drvslam
