#include "drvslam/dynamic/object_tracker.h"

#include <algorithm>
#include <opencv2/core.hpp>
#include <tuple>

#include "drvslam/core/error.h"
#include "drvslam/core/pixel_index.h"
#include "drvslam/dynamic/point_motions.h"
#include "drvslam/semantic/mask_lookup.h"

namespace drvslam {

int InstanceAt(const std::vector<Instance>& instances, const cv::Point2f& p) {
  cv::Point pixel;
  if (!PixelIndex(p, &pixel)) return -1;
  for (std::size_t k = 0; k < instances.size(); ++k) {
    const Instance& instance = instances[k];
    if (instance.box.contains(pixel) && OnMask(instance.mask, p)) return static_cast<int>(k);
  }
  return -1;
}

double InstanceIoU(const Instance& a, const Instance& b) {
  if (a.mask.size() != b.mask.size()) throw Error("InstanceIoU: masks differ in size");
  const cv::Rect image(0, 0, a.mask.cols, a.mask.rows);
  const cv::Rect region = (a.box | b.box) & image;
  if (region.empty()) return 0.0;
  const cv::Mat in_a = a.mask(region) != 0;
  const cv::Mat in_b = b.mask(region) != 0;
  const int both = cv::countNonZero(in_a & in_b);
  const int either = cv::countNonZero(in_a | in_b);
  return either == 0 ? 0.0 : static_cast<double>(both) / either;
}

ObjectIdTracker::ObjectIdTracker(int min_matches, int memory_frames, double memory_iou)
    : min_matches_(min_matches), memory_frames_(memory_frames), memory_iou_(memory_iou) {
  if (min_matches_ < 1) throw Error("Dynamic.minIdMatches must be at least 1");
  if (memory_frames_ < 0) throw Error("Dynamic.objectMemoryFrames must be at least 0");
  if (!(memory_iou_ > 0.0 && memory_iou_ <= 1.0)) {
    throw Error("Dynamic.objectMemoryIou must be in (0, 1]");
  }
}

IdAssignment ObjectIdTracker::Assign(std::vector<Instance>& previous,
                                     std::vector<Instance>& current,
                                     const std::vector<FlowTrack>& tracks) {
  const std::size_t n_cur = current.size();
  const std::size_t n_prev = previous.size();
  IdAssignment assignment;
  assignment.predecessor.assign(n_cur, -1);
  assignment.shared_tracks.assign(n_cur, 0);
  assignment.remembered.assign(n_cur, -1);

  std::vector<std::vector<int>> counts(n_cur, std::vector<int>(n_prev, 0));
  if (n_prev > 0 && n_cur > 0) {
    for (const FlowTrack& track : tracks) {
      const int a = InstanceAt(current, track.cur);
      if (a < 0) continue;
      const int b = InstanceAt(previous, track.prev);
      if (b < 0) continue;
      ++counts[a][b];
    }
  }
  // Each current instance proposes its best previous instance; proposals are granted strongest
  // first, so a previous instance split into two passes its ID to the larger share.
  std::vector<std::tuple<int, int, int>> proposals;  // (-count, current, previous)
  for (std::size_t a = 0; a < n_cur; ++a) {
    int best = -1;
    for (std::size_t b = 0; b < n_prev; ++b) {
      if (best < 0 || counts[a][b] > counts[a][best]) best = static_cast<int>(b);
    }
    if (best < 0) continue;
    assignment.shared_tracks[a] = counts[a][best];
    if (counts[a][best] < min_matches_ || previous[best].class_id != current[a].class_id) continue;
    proposals.emplace_back(-counts[a][best], static_cast<int>(a), best);
  }
  std::sort(proposals.begin(), proposals.end());
  std::vector<bool> taken(n_prev, false);
  // Carried instances continue the previous instance whose ID they carry.
  for (std::size_t a = 0; a < n_cur; ++a) {
    if (current[a].track_id < 0) continue;
    for (std::size_t b = 0; b < n_prev; ++b) {
      if (taken[b] || previous[b].track_id != current[a].track_id ||
          previous[b].class_id != current[a].class_id) {
        continue;
      }
      taken[b] = true;
      assignment.predecessor[a] = static_cast<int>(b);
      assignment.shared_tracks[a] = counts[a][b];
      break;
    }
  }
  for (const auto& [negative_count, a, b] : proposals) {
    if (taken[b] || assignment.predecessor[a] >= 0) continue;
    taken[b] = true;
    assignment.predecessor[a] = b;
    if (previous[b].track_id < 0) previous[b].track_id = next_id_++;
    current[a].track_id = previous[b].track_id;
  }
  if (memory_frames_ > 0) {
    Remember(previous, taken, current, tracks, assignment);
  } else {
    lost_.clear();
  }
  for (std::size_t a = 0; a < n_cur; ++a) {
    if (assignment.predecessor[a] < 0 && assignment.remembered[a] < 0) {
      current[a].track_id = next_id_++;
    }
  }
  return assignment;
}

void ObjectIdTracker::Remember(const std::vector<Instance>& previous,
                               const std::vector<bool>& continued, std::vector<Instance>& current,
                               const std::vector<FlowTrack>& tracks, IdAssignment& assignment) {
  for (std::size_t b = 0; b < previous.size(); ++b) {
    if (!continued[b] && previous[b].track_id >= 0) lost_.push_back({previous[b], 0});
  }
  if (lost_.empty()) return;
  const cv::Size size = lost_.front().instance.mask.size();
  const std::vector<PointMotion> motions = PointMotionsOf(tracks);
  std::vector<Lost> still;
  for (Lost& lost : lost_) {
    std::vector<Instance> carried = carrier_.Carry({lost.instance}, motions, size);
    if (!carried.empty()) still.push_back({std::move(carried.front()), lost.absent});
  }
  lost_ = std::move(still);

  for (std::size_t a = 0; a < current.size(); ++a) {
    if (assignment.predecessor[a] >= 0 || current[a].mask.size() != size) continue;
    int best = -1;
    double best_iou = memory_iou_;
    for (std::size_t l = 0; l < lost_.size(); ++l) {
      if (lost_[l].instance.class_id != current[a].class_id) continue;
      const double iou = InstanceIoU(lost_[l].instance, current[a]);
      if (iou >= best_iou) {
        best_iou = iou;
        best = static_cast<int>(l);
      }
    }
    if (best < 0) continue;
    current[a].track_id = lost_[best].instance.track_id;
    assignment.remembered[a] = lost_[best].absent;
    lost_.erase(lost_.begin() + best);
  }
  std::vector<Lost> kept;
  for (Lost& lost : lost_) {
    if (++lost.absent <= memory_frames_) kept.push_back(std::move(lost));
  }
  lost_ = std::move(kept);
}

}  // namespace drvslam
