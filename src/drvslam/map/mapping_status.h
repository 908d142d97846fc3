// MappingStatus: what tracking needs to know of local mapping, which lives in a later module
// (mapping/ implements it). Tracking inserts keyframes more eagerly while mapping is idle, asks a
// running local bundle adjustment to stop when a keyframe is needed now, and tells mapping when
// the map is about to be cleared, and waits for it before the map is cleared. Implementations are
// thread-safe.
#pragma once

namespace drvslam {

class MappingStatus {
 public:
  virtual ~MappingStatus() = default;

  // True when nothing is queued or being processed: a keyframe would be taken at once.
  virtual bool AcceptsKeyFrames() const = 0;
  // Keyframes waiting to be processed.
  virtual int QueuedKeyFrames() const = 0;
  // Stops a running local bundle adjustment early; it keeps what it reached.
  virtual void InterruptBundleAdjustment() = 0;
  // The map is about to be cleared: queued keyframes and work on the old map are dropped.
  // Never blocks.
  virtual void RequestReset() = 0;
  // Returns once no keyframe is being processed (a paused mapper is idle). Called without
  // Map::UpdateMutex() held: the keyframe in flight may need it to finish.
  virtual void WaitUntilIdle() = 0;
};

}  // namespace drvslam
