// MovingPointCuller: map points that sit on a potentially-moving object (a person standing still
// when people fill the view, so their features were kept) must not outlive the object's
// stillness. After each tracked frame the points the frame matched on such objects are filed
// under the object's track ID; when that object is later judged moving, its points are marked bad
// and erased from the map before the frame is tracked, so neither tracking nor local mapping
// uses them again. (Points are never created on objects already judged moving: their features
// are removed before tracking.) Used by the tracking thread only.
#pragma once

#include <map>
#include <memory>
#include <vector>

#include "drvslam/dynamic/motion_state.h"
#include "drvslam/map/frame.h"
#include "drvslam/map/map.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

class MovingPointCuller {
 public:
  // Files the map points `frame` holds (not bad, not outliers) whose keypoint lies on a
  // potentially-moving instance's mask under that instance's track ID. `objects[k]` belongs to
  // `instances[k]`. Objects unseen for kForgetAfter frames are forgotten (memory bound).
  void Observe(const Frame& frame, const std::vector<Instance>& instances,
               const std::vector<ObjectEvidence>& objects);

  // Marks bad and erases from `map` every filed point of the objects moving now, holding
  // map.UpdateMutex() (the caller must not); returns how many points were culled.
  int CullMoving(const std::vector<ObjectEvidence>& objects, Map& map);

  // Points filed now (some may have turned bad since).
  std::size_t FiledPoints() const;

 private:
  struct Filed {
    std::map<long, std::weak_ptr<MapPoint>> points;  // by map point id
    long last_seen = 0;
  };
  static constexpr long kForgetAfter = 300;
  std::map<int, Filed> by_object_;
  long observations_ = 0;
};

}  // namespace drvslam
