// LateKeyFrameMasks: with --realtime a keyframe is mostly made before the network has finished
// its image (a pass takes longer than a frame period), so it maps through masks carried from
// older frames, and those miss the parts of people that moved since. Its image is kept for the
// network (AsyncSegmenter::Keep) and, when its own masks come a few frames later, the map points
// it created on potentially-moving objects are culled. The frame's own masks would have kept
// features of moving people out of the map, and still ones are filed for culling only when
// their points are matched later (MovingPointCuller); a keyframe's late points on a person
// who stands still cost less than a mover mapped for good. Used by the tracking thread only.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "drvslam/map/keyframe.h"
#include "drvslam/map/map.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

class LateKeyFrameMasks {
 public:
  // `keyframe` was made from frame `frame_index` without that frame's own masks.
  void Expect(std::size_t frame_index, const std::shared_ptr<KeyFrame>& keyframe);
  // Frames whose keyframes still await their masks, oldest first.
  std::vector<std::size_t> Awaited() const;
  // Frame `frame_index`'s own masks came: marks bad and erases from `map` the points its
  // keyframe created (first observed there, not bad) whose keypoints lie on an instance with
  // potentially_moving[k] true, holding map.UpdateMutex() (the caller must not). The frame is no
  // longer awaited. Returns how many points were culled; nullopt for a frame not awaited or a
  // keyframe gone since (removed by local mapping, or freed).
  std::optional<int> Apply(std::size_t frame_index, const std::vector<Instance>& instances,
                           const std::vector<bool>& potentially_moving, Map& map);
  // The frame's masks will not come (dropped, failed, no longer kept): it is no longer awaited.
  void GiveUp(std::size_t frame_index);

 private:
  std::map<std::size_t, std::weak_ptr<KeyFrame>> awaited_;  // by frame index
};

}  // namespace drvslam
