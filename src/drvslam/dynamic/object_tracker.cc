#include "drvslam/dynamic/object_tracker.h"

#include <algorithm>
#include <tuple>

#include "drvslam/core/error.h"

namespace drvslam {

int InstanceAt(const std::vector<Instance>& instances, const cv::Point2f& p) {
  const int x = static_cast<int>(p.x);
  const int y = static_cast<int>(p.y);
  for (std::size_t k = 0; k < instances.size(); ++k) {
    const Instance& instance = instances[k];
    if (!instance.box.contains(cv::Point(x, y))) continue;
    const cv::Mat& mask = instance.mask;
    if (x < 0 || y < 0 || x >= mask.cols || y >= mask.rows) continue;
    if (mask.at<uint8_t>(y, x) != 0) return static_cast<int>(k);
  }
  return -1;
}

ObjectIdTracker::ObjectIdTracker(int min_matches) : min_matches_(min_matches) {
  if (min_matches_ < 1) throw Error("Dynamic.minIdMatches must be at least 1");
}

IdAssignment ObjectIdTracker::Assign(std::vector<Instance>& previous,
                                     std::vector<Instance>& current,
                                     const std::vector<FlowTrack>& tracks) {
  const std::size_t n_cur = current.size();
  const std::size_t n_prev = previous.size();
  IdAssignment assignment;
  assignment.predecessor.assign(n_cur, -1);
  assignment.shared_tracks.assign(n_cur, 0);

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
  for (const auto& [negative_count, a, b] : proposals) {
    if (taken[b]) continue;
    taken[b] = true;
    assignment.predecessor[a] = b;
    if (previous[b].track_id < 0) previous[b].track_id = next_id_++;
    current[a].track_id = previous[b].track_id;
  }
  for (std::size_t a = 0; a < n_cur; ++a) {
    if (assignment.predecessor[a] < 0) current[a].track_id = next_id_++;
  }
  return assignment;
}

}  // namespace drvslam
