#include "drvslam/dynamic/motion_state.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "drvslam/core/error.h"
#include "drvslam/core/pixel_index.h"
#include "drvslam/feature/descriptor_distance.h"
#include "drvslam/semantic/mask_lookup.h"

namespace drvslam {
namespace {

// Buckets of feature indices on a square grid, for radius queries.
class PointGrid {
 public:
  PointGrid(const std::vector<cv::KeyPoint>& keypoints, double cell) : cell_(std::max(1.0, cell)) {
    for (std::size_t i = 0; i < keypoints.size(); ++i) {
      cells_[Key(Cell(keypoints[i].pt.x), Cell(keypoints[i].pt.y))].push_back(i);
    }
  }
  template <typename Visit>
  void ForEachNear(const cv::Point2f& p, Visit visit) const {
    // A point off every cell (NaN, beyond long) has no neighbours; Cell would be undefined.
    if (!std::isfinite(p.x / cell_) || !std::isfinite(p.y / cell_) ||
        std::abs(p.x / cell_) > kMaxCell || std::abs(p.y / cell_) > kMaxCell) {
      return;
    }
    const long cx = Cell(p.x);
    const long cy = Cell(p.y);
    for (long y = cy - 1; y <= cy + 1; ++y) {
      for (long x = cx - 1; x <= cx + 1; ++x) {
        const auto found = cells_.find(Key(x, y));
        if (found == cells_.end()) continue;
        for (const std::size_t i : found->second) visit(i);
      }
    }
  }

 private:
  // Far inside long's range, and inside 32 bits so the key below packs two cells.
  static constexpr double kMaxCell = 1e9;
  long Cell(float v) const { return static_cast<long>(std::floor(v / cell_)); }
  // x in the high 32 bits, y in the low ones. Shifted as unsigned: a left shift of a negative
  // signed value is undefined (before C++20); the bits are those the signed shift gave.
  static long long Key(long x, long y) {
    const unsigned long long high = static_cast<unsigned long long>(static_cast<long long>(x))
                                    << 32;
    const unsigned long long low = static_cast<unsigned long long>(y) & 0xffffffffULL;
    return static_cast<long long>(high ^ low);
  }
  double cell_;
  std::unordered_map<long long, std::vector<std::size_t>> cells_;
};

}  // namespace

RingCount CountRingMatches(const cv::Rect& ring, const cv::Mat& mask, const FeatureView& previous,
                           const FeatureView& current, const std::vector<FlowTrack>& tracks,
                           double radius, int max_distance) {
  if (!previous.keypoints || !previous.descriptors || !current.keypoints || !current.descriptors) {
    throw Error("CountRingMatches: missing features");
  }
  const std::vector<cv::KeyPoint>& prev_kps = *previous.keypoints;
  const std::vector<cv::KeyPoint>& cur_kps = *current.keypoints;
  const cv::Mat& prev_desc = *previous.descriptors;
  const cv::Mat& cur_desc = *current.descriptors;
  if (cur_desc.rows != static_cast<int>(cur_kps.size()) ||
      prev_desc.rows != static_cast<int>(prev_kps.size())) {
    throw Error("CountRingMatches: one descriptor per keypoint is needed");
  }
  RingCount count;
  std::vector<std::size_t> inside;
  for (std::size_t i = 0; i < cur_kps.size(); ++i) {
    const cv::Point2f& p = cur_kps[i].pt;
    cv::Point pixel;
    if (!PixelIndex(p, &pixel) || !ring.contains(pixel)) continue;
    if (OnMask(mask, p)) continue;
    inside.push_back(i);
  }
  count.features = static_cast<int>(inside.size());
  if (inside.empty() || prev_kps.empty()) return count;

  // Where the background in the ring came from: the median flow of the static tracks there.
  std::vector<float> dx_local, dy_local, dx_all, dy_all;
  for (const FlowTrack& track : tracks) {
    if (track.moving || !track.model_pair) continue;
    const float dx = track.cur.x - track.prev.x;
    const float dy = track.cur.y - track.prev.y;
    dx_all.push_back(dx);
    dy_all.push_back(dy);
    cv::Point pixel;
    if (PixelIndex(track.cur, &pixel) && ring.contains(pixel)) {
      dx_local.push_back(dx);
      dy_local.push_back(dy);
    }
  }
  const auto median = [](std::vector<float>& values) {
    if (values.empty()) return 0.0f;
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
  };
  const bool local = dx_local.size() >= 3;
  const cv::Point2f flow(median(local ? dx_local : dx_all), median(local ? dy_local : dy_all));

  const PointGrid grid(prev_kps, radius);
  const double radius2 = radius * radius;
  for (const std::size_t i : inside) {
    const cv::Point2f from = cur_kps[i].pt - flow;
    const uint8_t* a = cur_desc.ptr<uint8_t>(static_cast<int>(i));
    int best_distance = std::numeric_limits<int>::max();
    grid.ForEachNear(from, [&](std::size_t j) {
      const float dx = prev_kps[j].pt.x - from.x;
      const float dy = prev_kps[j].pt.y - from.y;
      if (dx * dx + dy * dy > radius2) return;
      best_distance = std::min(best_distance,
                               DescriptorDistance(a, prev_desc.ptr<uint8_t>(static_cast<int>(j))));
    });
    if (best_distance <= max_distance) ++count.matched;
  }
  return count;
}

MotionStateClassifier::MotionStateClassifier(const DynamicOptions& options) : options_(options) {
  options_.Check();
}

cv::Rect MotionStateClassifier::ExpandBox(const cv::Rect& box, double margin,
                                          const cv::Size& image) {
  const int dx = static_cast<int>(std::lround(margin * box.width));
  const int dy = static_cast<int>(std::lround(margin * box.height));
  const cv::Rect grown(box.x - dx, box.y - dy, box.width + 2 * dx, box.height + 2 * dy);
  return grown & cv::Rect(0, 0, image.width, image.height);
}

std::vector<ObjectEvidence> MotionStateClassifier::Classify(
    const std::vector<Instance>& previous, const std::vector<Instance>& current,
    const std::vector<bool>& potentially_moving, const IdAssignment& ids,
    const MotionConsistencyResult& motion, const FeatureView& previous_features,
    const FeatureView& current_features) {
  if (potentially_moving.size() != current.size() || ids.predecessor.size() != current.size()) {
    throw Error("MotionStateClassifier: inputs of inconsistent lengths");
  }
  const std::vector<FlowTrack>& tracks = motion.tracks;
  const bool model_ok = motion.model != MotionModel::kNone;
  std::vector<ObjectEvidence> objects(current.size());
  for (const FlowTrack& track : tracks) {
    const int k = InstanceAt(current, track.cur);
    if (k < 0) continue;
    ++objects[k].tracks;
    if (track.moving) ++objects[k].moving_tracks;
    if (track.reprojection >= 0.0) {
      ++objects[k].reprojected_tracks;
      if (track.reprojection_moving) ++objects[k].reprojection_moving_tracks;
    }
  }

  std::map<int, LastState> delta_states;
  for (std::size_t k = 0; k < current.size(); ++k) {
    const Instance& instance = current[k];
    ObjectEvidence& e = objects[k];
    e.track_id = instance.track_id;
    e.predecessor = ids.predecessor[k];
    e.potentially_moving = potentially_moving[k];
    e.model_ok = model_ok;
    if (e.potentially_moving && e.predecessor >= 0 &&
        e.predecessor < static_cast<int>(previous.size())) {
      const cv::Rect ring =
          ExpandBox(previous[e.predecessor].box, options_.box_margin, instance.mask.size());
      const RingCount ring_count =
          CountRingMatches(ring, instance.mask, previous_features, current_features, tracks,
                           options_.match_radius, options_.max_descriptor_distance);
      e.ring_features = ring_count.features;
      e.ring_matched = ring_count.matched;
      if (e.ring_features >= options_.min_ring_features) {
        e.delta = static_cast<double>(e.ring_matched) / e.ring_features;
      }
    }
    const bool many_moving_points = e.moving_tracks > options_.min_moving_points;

    // The paper's rule.
    if (e.delta >= 0.0) {
      if (e.delta < options_.delta_moving) {
        e.moving_delta_rule = true;
      } else if (e.delta >= options_.delta_static) {
        e.moving_delta_rule = false;
      } else {
        const auto last = last_delta_state_.find(e.track_id);
        e.moving_delta_rule =
            last != last_delta_state_.end() ? last->second.moving : many_moving_points;
      }
    } else {
      e.moving_delta_rule = many_moving_points;
    }

    // The object's own tracks.
    if (e.tracks >= options_.min_object_tracks) {
      e.moving_share = static_cast<double>(e.moving_tracks) / e.tracks;
      e.moving_share_rule = e.moving_share >= options_.moving_share;
    } else {
      e.moving_share_rule = many_moving_points;
    }

    // The reprojection test alone: enough of the object's tracks fail it, or a few do (a moving
    // limb on a still body).
    const bool limb = e.reprojection_moving_tracks >= options_.min_moving_tracks &&
                      e.reprojection_moving_tracks >= options_.limb_share * e.reprojected_tracks;
    if (e.reprojected_tracks >= options_.min_object_tracks) {
      e.reprojection_share =
          static_cast<double>(e.reprojection_moving_tracks) / e.reprojected_tracks;
    }
    e.moving_reprojection_rule =
        limb || (e.reprojection_share >= 0.0 && e.reprojection_share >= options_.moving_share);

    // What ships: the reprojection test where enough tracks have one; the epipolar share where
    // depth edges leave too few (a thin, distant person); the paper's rule without tracks.
    if (e.reprojection_share >= 0.0) {
      e.moving_combined_rule = e.moving_reprojection_rule;
    } else if (e.moving_share >= 0.0) {
      e.moving_combined_rule = e.moving_share_rule || limb;
    } else {
      e.moving_combined_rule = limb || e.moving_delta_rule;
    }
    e.moving = options_.rule == MotionRule::kDelta ? e.moving_delta_rule : e.moving_combined_rule;
    if (!e.potentially_moving) {
      e.moving = e.moving_delta_rule = e.moving_share_rule = e.moving_reprojection_rule =
          e.moving_combined_rule = false;
    }
    delta_states[e.track_id] = {e.moving_delta_rule, 0};
  }
  for (const auto& [id, state] : last_delta_state_) {
    if (state.absent < options_.object_memory_frames && delta_states.count(id) == 0) {
      delta_states[id] = {state.moving, state.absent + 1};
    }
  }
  last_delta_state_ = std::move(delta_states);
  return objects;
}

}  // namespace drvslam
