// Map: owns every keyframe and map point of a run (shared_ptr), hands out ids, and is the
// structure every thread reads. Thread-safety: mutex_ guards the containers; update_mutex_ is
// held by whoever moves many poses at once (BA, loop correction) so that readers see a
// consistent map. The correction epoch counts the changes that move many keyframes at once, so
// that whoever keeps a pose relative to the map (tracking's last frame) notices every one.
#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "drvslam/map/keyframe.h"
#include "drvslam/map/map_point.h"

namespace drvslam {

class Map {
 public:
  Map() = default;
  Map(const Map&) = delete;
  Map& operator=(const Map&) = delete;

  long NextKeyFrameId();
  long NextMapPointId();

  // After a saved map was added: the next ids handed out are at least these, so new keyframes
  // and points never take a loaded one's id.
  void AdvanceIds(long next_keyframe_id, long next_map_point_id);

  void AddKeyFrame(const std::shared_ptr<KeyFrame>& keyframe);
  void AddMapPoint(const std::shared_ptr<MapPoint>& point);
  void EraseKeyFrame(long id);
  void EraseMapPoint(long id);

  // In id order (deterministic).
  std::vector<std::shared_ptr<KeyFrame>> KeyFrames() const;
  std::vector<std::shared_ptr<MapPoint>> MapPoints() const;
  std::size_t KeyFrameCount() const;
  std::size_t MapPointCount() const;

  // Drops everything (keeping the id counters, so ids stay unique across resets).
  void Clear();

  std::mutex& UpdateMutex() { return update_mutex_; }

  // Raised, under UpdateMutex(), by each step of a loop correction or global bundle adjustment
  // merge that moves keyframes and points; a reader holding UpdateMutex() that last saw another
  // value re-poses what it holds in the old map before using it (ORB-SLAM3's map-change index).
  long CorrectionEpoch() const { return correction_epoch_.load(); }
  void RaiseCorrectionEpoch() { ++correction_epoch_; }

 private:
  mutable std::mutex mutex_;
  std::map<long, std::shared_ptr<KeyFrame>> keyframes_;
  std::map<long, std::shared_ptr<MapPoint>> map_points_;
  long next_keyframe_id_ = 0;
  long next_map_point_id_ = 0;
  std::mutex update_mutex_;
  std::atomic<long> correction_epoch_{0};
};

}  // namespace drvslam
