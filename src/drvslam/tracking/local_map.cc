#include "drvslam/tracking/local_map.h"

#include <atomic>
#include <map>
#include <set>

namespace drvslam {

LocalMap BuildLocalMap(const Frame& frame, std::size_t max_keyframes) {
  LocalMap local;
  // Votes: how many of the frame's points each keyframe observes.
  std::map<long, std::pair<std::shared_ptr<KeyFrame>, int>> votes;
  for (std::size_t i = 0; i < frame.Size(); ++i) {
    const auto& point = frame.map_points[i];
    if (!point || point->IsBad()) continue;
    point->ForEachObservation([&votes](long id, const MapPoint::Observation& observation) {
      auto& entry = votes[id];
      if (!entry.first) entry.first = observation.keyframe.lock();
      ++entry.second;
    });
  }
  std::set<long> included;
  int best_votes = 0;
  for (const auto& [id, entry] : votes) {
    const auto& [keyframe, count] = entry;
    if (!keyframe || keyframe->IsBad()) continue;
    local.keyframes.push_back(keyframe);
    included.insert(id);
    if (count > best_votes) {
      best_votes = count;
      local.reference = keyframe;
    }
  }
  const auto try_add = [&](const std::shared_ptr<KeyFrame>& keyframe) {
    if (!keyframe || keyframe->IsBad() || included.count(keyframe->Id())) return false;
    included.insert(keyframe->Id());
    local.keyframes.push_back(keyframe);
    return true;
  };
  // Neighbours of the voting keyframes: one of each kind per keyframe, as ORB-SLAM2 does.
  const std::size_t voters = local.keyframes.size();
  for (std::size_t k = 0; k < voters && local.keyframes.size() < max_keyframes; ++k) {
    const auto keyframe = local.keyframes[k];
    for (const auto& neighbour : keyframe->BestCovisibles(10)) {
      if (try_add(neighbour)) break;
    }
    for (const auto& child : keyframe->Children()) {
      if (try_add(child)) break;
    }
    try_add(keyframe->Parent());
  }

  // Each point once, in the order first seen: a point carries the number of the listing that
  // took it, cheaper than a set of ids over tens of thousands of (mostly repeated) points.
  static std::atomic<long> listings{0};
  const long listing = listings.fetch_add(1, std::memory_order_relaxed);
  for (const auto& keyframe : local.keyframes) {
    for (const auto& point : keyframe->MapPoints()) {
      if (!point || point->local_map_listing == listing || point->IsBad()) continue;
      point->local_map_listing = listing;
      local.points.push_back(point);
    }
  }
  return local;
}

}  // namespace drvslam
