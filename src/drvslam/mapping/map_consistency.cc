#include "drvslam/mapping/map_consistency.h"

#include <map>
#include <set>

namespace drvslam {
namespace {

// Enough to diagnose; a broken map would otherwise produce one line per observation.
constexpr std::size_t kMaxProblems = 50;

class Problems {
 public:
  void Add(const std::string& problem) {
    if (list_.size() < kMaxProblems) list_.push_back(problem);
    ++count_;
  }
  std::vector<std::string> Take() {
    if (count_ > list_.size()) {
      list_.push_back("... and " + std::to_string(count_ - list_.size()) + " more");
    }
    return std::move(list_);
  }

 private:
  std::vector<std::string> list_;
  std::size_t count_ = 0;
};

std::string Kf(long id) { return "keyframe " + std::to_string(id); }
std::string Mp(long id) { return "map point " + std::to_string(id); }

}  // namespace

std::vector<std::string> CheckMapConsistency(const Map& map) {
  Problems problems;
  const auto keyframes = map.KeyFrames();
  const auto points = map.MapPoints();
  std::map<long, const KeyFrame*> keyframe_ids;
  for (const auto& keyframe : keyframes) keyframe_ids[keyframe->Id()] = keyframe.get();
  std::set<long> point_ids;
  for (const auto& point : points) point_ids.insert(point->Id());

  for (const auto& keyframe : keyframes) {
    const std::string name = Kf(keyframe->Id());
    if (keyframe->IsBad()) problems.Add(name + " is bad but still in the map");
    const auto slots = keyframe->MapPoints();
    for (std::size_t i = 0; i < slots.size(); ++i) {
      const auto& point = slots[i];
      if (!point) continue;
      const std::string where = name + " slot " + std::to_string(i) + ": " + Mp(point->Id());
      if (point->IsBad()) {
        problems.Add(where + " is bad");
        continue;
      }
      if (!point_ids.count(point->Id())) problems.Add(where + " is not in the map");
      const int index = point->IndexIn(keyframe->Id());
      if (index < 0) {
        problems.Add(where + " has no observation of the keyframe");
      } else if (static_cast<std::size_t>(index) != i) {
        problems.Add(where + " records the keyframe at index " + std::to_string(index));
      }
    }
    // Spanning tree: the first keyframe of the map is the root.
    if (keyframe.get() == keyframes.front().get()) continue;
    const auto parent = keyframe->Parent();
    if (!parent) {
      problems.Add(name + " has no parent");
      continue;
    }
    if (parent->IsBad() || !keyframe_ids.count(parent->Id())) {
      problems.Add(name + " has parent " + Kf(parent->Id()) + " that is bad or not in the map");
    }
    bool listed = false;
    for (const auto& child : parent->Children()) listed = listed || child.get() == keyframe.get();
    if (!listed) problems.Add(name + " is missing from its parent's children");
  }
  for (const auto& keyframe : keyframes) {
    for (const auto& child : keyframe->Children()) {
      if (child->Parent().get() != keyframe.get()) {
        problems.Add(Kf(child->Id()) + " is a child of " + Kf(keyframe->Id()) +
                     " but has another parent");
      }
    }
  }

  for (const auto& point : points) {
    const std::string name = Mp(point->Id());
    if (point->IsBad()) {
      problems.Add(name + " is bad but still in the map");
      continue;
    }
    const auto observations = point->Observations();
    if (observations.empty()) problems.Add(name + " has no observations");
    for (const auto& [keyframe_id, observation] : observations) {
      const std::string where = name + " observation of " + Kf(keyframe_id);
      const auto keyframe = observation.keyframe.lock();
      if (!keyframe) {
        problems.Add(where + ": the keyframe no longer exists");
        continue;
      }
      if (keyframe->IsBad()) problems.Add(where + ": the keyframe is bad");
      if (!keyframe_ids.count(keyframe_id))
        problems.Add(where + ": the keyframe is not in the map");
      if (observation.index < 0 ||
          static_cast<std::size_t>(observation.index) >= keyframe->Features().Size()) {
        problems.Add(where + ": index " + std::to_string(observation.index) + " out of range");
        continue;
      }
      if (keyframe->MapPointAt(observation.index).get() != point.get()) {
        problems.Add(where + ": slot " + std::to_string(observation.index) +
                     " holds another point");
      }
    }
  }
  return problems.Take();
}

}  // namespace drvslam
